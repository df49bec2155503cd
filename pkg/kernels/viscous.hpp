// Viscous forces of a pendular liquid bridge (Elskamp2018 section 2.2.3, eq. 25-29) and the
// dynamic rupture distance (Elskamp2018 eq. 33, Pitois et al.). Pure kernels: SI units, no YADE
// types. ViscousBridge holds a bridge's invariants and is the one place of the formulas: the checked
// functions below and the YADE layer (Law2_ScGeom_PendularPhys_Bridge) evaluate through it.
//
// Conventions (those of Elskamp2018):
//   n       unit vector along the line of centres, pointing from particle 1 (i) to particle 2 (j);
//   v_rel   v1 - v2, the relative translational velocity [m/s];
//   v_n     (v1 - v2) . n [m/s]: > 0 when the particles approach, < 0 when they separate;
//   r*      r_reff = R1 R2 / (R1 + R2), the REDUCED radius of Elskamp2018 (after eq. 25), i.e. half
//           of the harmonic mean 2 R1 R2 / (R1 + R2) used by the capillary models (conventions.hpp);
//           a wall (R2 = wall_radius = inf) gives its limit r* = R1;
//   S       the surface separation [m]. Elskamp2018 (after eq. 29): "a minimum separation distance
//           S_min = 0.001 r_reff is introduced and added to S", so every formula here is evaluated
//           at S_eff = max(S, 0) + S_min, S_min = S_min_factor r*. The max(S, 0) is ours: an overlap
//           (S < 0) gets the force at contact, S_eff = S_min, instead of a negative or zero gap.
//   forces  on particle 1; particle 2 gets the opposite force.
// Validation: every input is checked (capillary::out_of_range, naming the parameter; limits in
// viscous_limits below); eta = 0 gives exactly zero viscous forces.
#pragma once

#include "conventions.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace capillary {

using Vec3 = std::array<double, 3>;

// ---- normal viscous force -------------------------------------------------------------------
enum class NormalViscous : std::uint8_t {
	pitois,        // Elskamp2018 eq. (26), Pitois et al. 2000: finite bridge volume (the default)
	adams_perchard // Elskamp2018 eq. (25), Adams & Perchard 1985: 6 pi eta r*^2 v_n / S
};
struct NormalViscousInfo {
	NormalViscous law;
	const char*   name;
	const char*   reference;
};
const std::vector<NormalViscousInfo>& normal_viscous_laws();
NormalViscous                         normal_viscous_from_name(const std::string& name); // throws std::invalid_argument
const char*                           name_of(NormalViscous law);
std::string                           normal_viscous_names(); // "pitois, adams_perchard"

// Limits of meaningful input beyond those of conventions.hpp (Plausible): outside them a value is a
// mistake, and inside them every result is finite. eta up to 1e9 Pa s (pitch is ~1e8); velocities
// and angular velocities (each component, n included) up to 1e10 in magnitude; static rupture
// distances up to Plausible::range_max * Plausible::radius_max; S_min_factor in [1e-12, 1] (> 0: the
// floor keeps every force finite at contact).
struct viscous_limits {
	static constexpr double eta_max      = 1e9;  // [Pa s]
	static constexpr double velocity_max = 1e10; // [m/s], [rad/s]
	static constexpr double rupture_max  = Plausible::range_max * Plausible::radius_max; // [m]
	static constexpr double s_min_factor_min = 1e-12, s_min_factor_max = 1;             // S_min / r* [-]
};

constexpr double default_s_min_factor = 0.001; // S_min / r*, Elskamp2018 after eq. (29)

// r* = R1 R2 / (R1 + R2) [m] (Elskamp2018 after eq. 25); R1 for a wall (R2 = wall_radius).
inline double reduced_radius(double R1, double R2) { return is_wall(R2) ? R1 : R1 * R2 / (R1 + R2); }

// The separation at which the formulas are evaluated: max(S, 0) + S_min_factor r* [m].
double effective_separation(double S, double R1, double R2, double S_min_factor = default_s_min_factor);

// Damping coefficient c [N s/m] of the normal viscous force, F1 = -c v_n n (F2 = -F1):
//   adams_perchard  c = 6 pi eta r*^2 / S_eff                                    Elskamp2018 eq. (25)
//   pitois          c = 6 pi eta r*^2 / S_eff (1 - 1/sqrt(1 + V/(pi r* S_eff^2)))^2 eq. (26)
// volume V [m^3] is the bridge volume: required by pitois (V* = V/R^3 in the range of the capillary
// models, R the harmonic mean of the Derjaguin-equivalent pair), ignored by adams_perchard (must be
// finite and >= 0). eta [Pa s] >= 0.
double normal_viscous_coefficient(NormalViscous law, double S, double R1, double R2, double eta, double volume,
                                  double S_min_factor = default_s_min_factor);
// The signed normal force on particle 1 along n [N]: f = -c v_n, i.e. F1 = f n. It opposes the
// relative normal motion: f v_n = -c v_n^2 <= 0 (repulsive while approaching, attractive while
// separating).
double normal_viscous_force(NormalViscous law, double S, double v_n, double R1, double R2, double eta, double volume,
                            double S_min_factor = default_s_min_factor);

// ---- tangential viscous force and moments (Goldman, Cox & Brenner 1967) ------------------------
// Elskamp2018 eq. (28) for S_eff < 0.1 r*, eq. (29) for S_eff >= 0.1 r*:
//   F1 = -c_t v_t - c_r (omega_r x n),  v_t = v_rel - (v_rel . n) n,  omega_r = R1 omega1 + R2 omega2,
//   c_t = 6 pi eta r* (8/15 ln(r*/S_eff) + 0.9588)                                  (28), (29)
//   c_r = 6 pi eta r* (2/15 ln(r*/S_eff) - 0.2526)                      S_eff < 0.1 r*  (28)
//   c_r = 6 pi eta r* / 8 (r*/(S_eff + r*))^4 (1 - 3 r*/(8 (S_eff + r*)))  S_eff >= 0.1 r* (29)
// omega_r (Elskamp2018 after eq. 27) is a velocity [m/s]: with n from 1 to 2, omega_r x n is the
// rotational part of the relative velocity of the two surfaces at the contact point, so that
// v_t + omega_r x n is the relative sliding velocity (eq. 27 damps it with one coefficient).
// Moments (Elskamp2018 after eq. 6, M_L,i = r_i x F_i with r_i from the centre to the contact):
//   M1 = R1 n x F1 and M2 = (-R2 n) x (-F1) = R2 n x F1; a wall gets M2 = 0.
// Branch jump: eq. (28) and (29) differ at S_eff = 0.1 r* in c_r only, by 3.3 % (c_r/(6 pi eta r*)
// = 0.05441 from (28), 0.05627 from (29)); c_t is continuous. The paper's jump is kept (a
// blend would change a 3 % step of a coefficient that is itself a fit; the curves cross at
// S_eff = 0.0984 r*; see docs/models.md, "Viscous forces").
// Deviation: c_t is floored at 0. It is positive for S_eff < r* exp(15/8 0.9588) = 6.03 r* and
// would turn negative (a driving force) beyond, outside Goldman's range.
// Dissipation: each part opposes its own velocity (c_t, c_r >= 0). Because c_t != c_r, the pair
// (force, moments) is not dissipative for every combination of v_t and omega_r (the power
// -(c_t v_t + c_r w).(v_t + w), w = omega_r x n, is > 0 for v_t = -k w with k between c_r/c_t and
// 1): a property of the paper's model, which keeps only the force terms of Goldman's resistances.
struct TangentialViscous {
	double c_t = 0;                  // [N s/m] coefficient of v_t
	double c_r = 0;                  // [N s/m] coefficient of omega_r x n
	bool   near = true;              // true: eq. (28) (S_eff < 0.1 r*), false: eq. (29)
	Vec3   force{ { 0, 0, 0 } };     // [N] on particle 1 (particle 2: -force)
	Vec3   moment1{ { 0, 0, 0 } };   // [N m] on particle 1, R1 n x force
	Vec3   moment2{ { 0, 0, 0 } };   // [N m] on particle 2, R2 n x force (0 for a wall)
};
// Coefficients only: the separation, radii, eta as above.
void tangential_viscous_coefficients(double S, double R1, double R2, double eta, double S_min_factor, double& c_t, double& c_r,
                                     bool& near);
// n: unit vector from particle 1 to particle 2 (|n| = 1 within 1e-6); v_rel = v1 - v2 [m/s]; omega1,
// omega2 [rad/s]. A wall (R2 = wall_radius): pass the wall's velocity at the contact point in v_rel
// and omega2 = 0 (anything else is refused: a plane has no radius to turn a rotation into a
// surface velocity).
TangentialViscous tangential_viscous(double S, const Vec3& n, const Vec3& v_rel, const Vec3& omega1, const Vec3& omega2, double R1,
                                     double R2, double eta, double S_min_factor = default_s_min_factor);

// ---- one bridge: invariants computed once, per-step evaluation ---------------------------------
// make_viscous validates (as the functions above) and computes everything that does not depend on
// the gap; the members below are the per-step calls, without checks. eta = 0 gives exactly zero
// coefficients. gamma [N/m] is needed only by the dynamic rupture rule (0: no dynamic rupture).
struct ViscousBridge {
	NormalViscous law   = NormalViscous::pitois;
	double        rs    = 0; // r* [m]
	double        s_min = 0; // S_min = S_min_factor r* [m]
	double        cn0   = 0; // 6 pi eta r*^2 [N s], eq. (25), (26)
	double        ct0   = 0; // 6 pi eta r* [N s/m], eq. (28), (29)
	double        x0    = 0; // V / (pi r*) [m^2]: eq. (26) has V/(pi r* S^2) = x0 / S^2
	double        ca    = 0; // sqrt(eta / gamma) [sqrt(s/m)]: eq. (33) has sqrt(|v| eta/gamma) = ca sqrt(|v|)

	// S_eff = max(S, 0) + S_min [m] (Elskamp2018 after eq. 29; an overlap gets the force at contact).
	double separation(double S) const { return std::max(S, 0.0) + s_min; }
	// c of F1 = -c v_n n [N s/m], eq. (25) or (26).
	double normal_coefficient(double S) const
	{
		const double Se = separation(S), c = cn0 / Se;
		if (law == NormalViscous::adams_perchard) return c; // eq. (25)
		// 1 - 1/sqrt(1 + x) = x / (sqrt(1 + x) (1 + sqrt(1 + x))): no cancellation at small x.
		const double x = x0 / (Se * Se), q = std::sqrt(1 + x), g = x / (q * (1 + q));
		return c * g * g; // eq. (26)
	}
	// c_t, c_r of F1 = -c_t v_t - c_r (omega_r x n) [N s/m]; near: eq. (28) (S_eff < 0.1 r*), else (29).
	void tangential_coefficients(double S, double& c_t, double& c_r, bool& near) const
	{
		const double Se = separation(S), L = std::log(rs / Se);
		near = Se < 0.1 * rs;
		c_t  = ct0 * std::max(8.0 / 15 * L + 0.9588, 0.0); // eq. (28), (29); floored at 0 beyond 6.03 r*
		if (near) c_r = ct0 * (2.0 / 15 * L - 0.2526);     // eq. (28); > 0.054 ct0 here
		else {
			const double h = rs / (Se + rs);
			c_r = ct0 / 8 * h * h * h * h * (1 - 3 * h / 8); // eq. (29)
		}
	}
	// S_rup,dyn / S_rup = 1 + sqrt(|v_rel| eta / gamma) [-], eq. (33); v_rel [m/s] the relative speed.
	double rupture_stretch(double v_rel) const { return 1 + ca * std::sqrt(std::abs(v_rel)); }
};
// Validates like the functions above (volume: required by pitois; gamma: 0, or in the Plausible
// range for the dynamic rupture rule).
ViscousBridge make_viscous(NormalViscous law, double R1, double R2, double eta, double volume, double gamma = 0,
                           double S_min_factor = default_s_min_factor);

// F1 = -c_t v_t - c_r (omega_r x n) [N] (eq. 28, 29): the one vector form, for any 3-vector type V
// with operator[] (Vec3 here, Vector3r in the YADE layer).
template <class V> V tangential_viscous_force(double c_t, double c_r, const V& n, const V& v_t, const V& omega_r)
{
	V f;
	f[0] = -c_t * v_t[0] - c_r * (omega_r[1] * n[2] - omega_r[2] * n[1]);
	f[1] = -c_t * v_t[1] - c_r * (omega_r[2] * n[0] - omega_r[0] * n[2]);
	f[2] = -c_t * v_t[2] - c_r * (omega_r[0] * n[1] - omega_r[1] * n[0]);
	return f;
}

// ---- dynamic rupture distance -------------------------------------------------------------
// Elskamp2018 eq. (33), Pitois et al. 2001: S_rup,dyn = S_rup (1 + sqrt(|v1 - v2| eta / gamma)) [m],
// the static rupture distance S_rup [m] (> 0) stretched by the capillary number Ca = |v_rel| eta /
// gamma. v_rel [m/s] is the magnitude of the relative velocity (its sign is ignored); eta [Pa s]
// >= 0 (eta = 0 gives S_rup); gamma [N/m] in the Plausible range.
double dynamic_rupture_distance(double static_rupture, double v_rel, double eta, double gamma);

} // namespace capillary
