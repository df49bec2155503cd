// Capillary bridge models: SI units in and out, angles in radians, no YADE types. Forces are
// magnitudes of the attraction along the line of centres (>= 0); the gap a is the surface
// separation (>= 0).
//
// Each model is one small type, listed once in CAPILLARY_MODELS below. A type declares
//   reference    the source of its formula;
//   domain       where its formula holds (V*, contact angle, size ratio, walls) and the source of
//                that range;
//   monotone     whether its force never grows with the gap;
//   own_rupture  whether it defines its own interaction range instead of the rupture rule;
//   needs_linear whether it uses linear_fmax, linear_kc and calibrate_from (others refuse them);
// and provides
//   make(spec, pair, rupture)  its named per-bridge invariants, computed once (it may replace the
//                              rupture distance of the rule by its own);
//   force0()                   the force at contact, F(0) [N];
//   force(a)                   the force at a gap a in (0, rupture] [N], the per-step evaluation.
// make_bridge() validates the inputs, refuses a bridge outside its model's domain (or, with
// BridgeSpec::extrapolate, evaluates the model at the nearest point of its domain, see
// Extrapolated) and returns a Bridge: the model as a variant index plus its invariants.
// bridge_force() is the cheap per-step call. Adding a model: one type here, one line in
// CAPILLARY_MODELS, one reference file in tests/data/models/, one literal-formula test in
// tests/kernels/test_models.cpp, one row in docs/models.md (see docs/CONTRIBUTING.md).
#pragma once

#include "conventions.hpp"
#include "young_laplace_table.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace capillary {

// ---- the one list of models: X(name, Type). The name is the user-facing identifier. -----------
#define CAPILLARY_MODELS(X)                                                                                                                          \
	X(weigert, Weigert)                                                                                                                          \
	X(willett_full, WillettFull)                                                                                                                 \
	X(willett_reduced, WillettReduced)                                                                                                           \
	X(rabinovich, Rabinovich)                                                                                                                    \
	X(rabinovich_lambert, RabinovichLambert)                                                                                                     \
	X(richefeu, Richefeu)                                                                                                                        \
	X(soulie, Soulie)                                                                                                                            \
	X(linear_irreversible, LinearIrreversible)                                                                                                   \
	X(young_laplace_table, YoungLaplaceTable)

#define CAPILLARY_ENUM_(name, Type) name,
enum class Model : std::uint8_t { CAPILLARY_MODELS(CAPILLARY_ENUM_) };
#undef CAPILLARY_ENUM_
// The names as one string literal (" weigert willett_full ..."), for docstrings that must be
// literals (YADE's attribute macros).
#define CAPILLARY_NAME_(name, Type) " " #name
#define CAPILLARY_MODEL_NAMES_LITERAL CAPILLARY_MODELS(CAPILLARY_NAME_)

enum class Rupture : std::uint8_t {
	lian,           // (1 + theta/2) V^(1/3): Lian 1993, Richefeu2008 eq. (6), Roy eq. (15)
	willett,        // Gladkyy2014 eq. (2), Elskamp2018 eq. (31)
	willett_elskamp // unequal spheres and angles: Elskamp2018 eq. (32)
};

// Where a model's formula holds. V* = V/R^3 with R the harmonic mean radius of the
// Derjaguin-equivalent pair (a wall: R = 2 R1); ratio = R_large/R_small of two spheres.
struct Domain {
	double      vstar_min, vstar_max; // [-]
	double      theta_max;            // [rad], each contact angle
	double      ratio_max;            // [-]
	bool        wall;                 // sphere-wall and sphere-facet bridges
	bool        equal_angles;         // the two contact angles must be equal
	const char* source;               // where the range comes from
	// The bounds hold to rounding (slack): V* = V/R^3 of a volume given as 0.1 R^3 may come out as
	// 0.1 + 1 ulp. Every check against a domain (kernels and YADE layer) goes through these.
	static constexpr double slack = 1e-12;
	bool allows_vstar(double vstar) const { return vstar >= vstar_min * (1 - slack) && vstar <= vstar_max * (1 + slack); }
	bool allows_theta(double theta) const { return theta <= theta_max * (1 + slack); }
	bool allows_ratio(double ratio) const { return ratio <= ratio_max * (1 + slack); }
	bool allows_angles(double theta1, double theta2) const { return !equal_angles || std::abs(theta1 - theta2) <= slack; }
};

// Inputs of one bridge. R2 = wall_radius (infinity) means a sphere-wall (plane) bridge.
struct BridgeSpec {
	double  R1      = 0; // [m] sphere radius
	double  R2      = 0; // [m] sphere radius, or wall_radius
	double  volume  = 0; // [m^3] liquid bridge volume
	double  gamma   = 0; // [N/m] surface tension
	double  theta1  = 0; // [rad] contact angle on body 1
	double  theta2  = 0; // [rad] contact angle on body 2
	Model   model   = Model::willett_full;
	Rupture rupture = Rupture::willett;
	// linear_irreversible only: if both > 0 they are used as given, otherwise they are calibrated
	// from `calibrate_from` by equal maximum force and equal adhesive energy (Roy et al. 4.2).
	double linear_fmax    = 0;                   // [N] maximum adhesive force
	double linear_kc      = 0;                   // [N/m] adhesive stiffness
	Model  calibrate_from = Model::willett_full; // reference model (not linear_irreversible)
	// Outside its model's domain a bridge is refused; true: the model is evaluated at the nearest
	// point of its domain instead (see Extrapolated).
	bool extrapolate = false;
};

// A validated bridge geometry, computed once from a BridgeSpec.
struct Pair {
	double R1, R2;         // [m] as given (R2 = inf: wall)
	double r1, r2;         // [m] Derjaguin-equivalent pair (a wall: r1 = r2 = 2 R1)
	double R;              // [m] harmonic mean of r1, r2 (Gladkyy2014 eq. 1)
	double volume, gamma;  // [m^3], [N/m]
	double theta1, theta2; // [rad]
	double theta;          // [rad] equivalent contact angle of the force models (equivalent_angle, conventions.hpp)
	double theta_mean;     // [rad] (theta1 + theta2)/2, the angle of the lian and willett rupture rules
	double vstar;          // V/R^3 [-]
	double ratio;          // max(r1, r2) / min(r1, r2) [-]
	bool   wall;
};
// Validates the inputs of any bridge (std::invalid_argument naming the parameter, its value and
// the allowed range; Plausible in conventions.hpp) and derives the geometry.
Pair pair_of(const BridgeSpec& spec);

// Rupture distance [m] of a rule for a validated pair, or for the given pair (validated here).
double rupture_distance(Rupture rule, const Pair& p);
double rupture_distance(Rupture rule, double R1, double R2, double volume, double theta1, double theta2);

// Willett's full-model coefficients f1..f4 (Gladkyy2014 eq. B1-B4) for V* = V/R^3, theta [rad].
std::array<double, 4> willett_coefficients(double vstar, double theta);

// ---- the models ------------------------------------------------------------------------------
// The pendular range of Willett's fits, the only range printed in our sources (Gladkyy2014
// section 2.3: "valid for theta < 50 deg and V* < 0.1"). Models without a printed range of their
// own are held to it: it is where Gladkyy compared them with experiments and where the contract
// suite and the exact table check them. Lower end: 1e-5, the smallest V* of the exact table (no
// source prints one). The Derjaguin-based models (harmonic mean radius) take any size ratio: a
// wall is their limit R_large -> inf. The models whose formula depends on the size ratio
// (Richefeu's h(r), Soulie's R_large) are held to ratios up to 4, the largest at which they are
// checked here against the exact solution (no range printed in our sources).
constexpr double inf_ratio = std::numeric_limits<double>::infinity();
constexpr double theta_50deg = 50 * pi / 180;

struct Weigert { // Gladkyy2014 eq. (5), (A2)-(A7); Weigert & Ripperger 1999
	static constexpr const char* reference = "Gladkyy2014 eq. (5), (A2)-(A7), half gap in (A6)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, inf_ratio, true, false, "Willett's range, Gladkyy2014 section 2.3 (none printed for Weigert)" };
	static constexpr bool   monotone = true, own_rupture = false, needs_linear = false;
	double R, gamma, theta;
	double vk; // V / (0.12 (2R)^3 C_theta) [-], (A2) at a = 0, with (A1), (A4)
	static Weigert make(const BridgeSpec&, const Pair&, double& rupture);
	double         force0() const { return force(0); }
	double         force(double a) const;
};

struct WillettFull { // Gladkyy2014 eq. (6), (7), (B1)-(B4); Willett et al. 2000
	static constexpr const char* reference = "Gladkyy2014 eq. (6), (7), (B1)-(B4)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, inf_ratio, true, false, "Gladkyy2014 section 2.3 (Willett2000): theta < 50 deg, V* < 0.1" };
	static constexpr bool   monotone = true, own_rupture = false, needs_linear = false;
	double f1, f2, f3, f4; // (B1)-(B4)
	double inv_s;          // 1 / (2 sqrt(V/R)) [1/m], S+ = a inv_s (6)
	double scale;          // 2 pi R gamma [N]
	static WillettFull make(const BridgeSpec&, const Pair&, double& rupture);
	// a -> 0: f3 ln S + f4 ln^2 S -> -inf as f4 < 0, so F(0) = 2 pi R gamma e^f1.
	double force0() const { return scale * std::exp(f1); }
	double force(double a) const
	{
		const double lnS = std::log(a * inv_s);                             // (6)
		return scale * std::exp(f1 - f2 * std::exp(f3 * lnS + f4 * lnS * lnS)); // (7)
	}
};

struct WillettReduced { // Gladkyy2014 eq. (6), (8); Willett et al. 2000 eq. (12)
	static constexpr const char* reference = "Gladkyy2014 eq. (6), (8)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, inf_ratio, true, false, "Gladkyy2014 section 2.3 (Willett2000): theta < 50 deg, V* < 0.1" };
	static constexpr bool   monotone = true, own_rupture = false, needs_linear = false;
	double inv_s; // 1 / (2 sqrt(V/R)) [1/m]
	double scale; // 2 pi R gamma cos(theta) [N]
	static WillettReduced make(const BridgeSpec&, const Pair&, double& rupture);
	double                force0() const { return scale; }
	double                force(double a) const
	{
		const double S = a * inv_s;               // (6)
		return scale / (1 + 2.1 * S + 10 * S * S); // (8)
	}
};

// Rabinovich's immersion distance, shared by both variants. With c = 2V/(pi R):
// a/(2 d_sp) = a (a + sqrt(a^2 + c)) / c, the form of eq. (10) that stays finite at a = 0.
struct RabinovichLambert { // Gladkyy2014 eq. (9), (10), (12); Lambert et al. 2008
	static constexpr const char* reference = "Gladkyy2014 eq. (9), (10), (12)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, inf_ratio, true, false, "Willett's range, Gladkyy2014 section 2.3 (none printed for Rabinovich)" };
	static constexpr bool   monotone = true, own_rupture = false, needs_linear = false;
	double c;     // 2V / (pi R) [m^2]
	double scale; // 2 pi R gamma cos(theta) [N]
	static RabinovichLambert make(const BridgeSpec&, const Pair&, double& rupture);
	double                   force0() const { return scale; }
	double                   force(double a) const { return scale / (1 + a * (a + std::sqrt(a * a + c)) / c); } // (12)
};

struct Rabinovich { // Gladkyy2014 eq. (9)-(11), with the sine term; Rabinovich et al. 2005
	static constexpr const char* reference = "Gladkyy2014 eq. (9)-(11)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, inf_ratio, true, false, "Willett's range, Gladkyy2014 section 2.3 (none printed for Rabinovich)" };
	static constexpr bool   monotone = false, own_rupture = false, needs_linear = false;
	RabinovichLambert lambert;
	double            R, theta;
	double            scale; // 2 pi R gamma [N]
	static Rabinovich make(const BridgeSpec&, const Pair&, double& rupture);
	double            force0() const { return force(0); }
	double            force(double a) const
	{
		// alpha = sqrt(c / (R (sqrt(a^2 + c) + a))): eq. (9) without the 0 * inf at a = 0.
		const double alpha = std::sqrt(lambert.c / (R * (std::sqrt(a * a + lambert.c) + a)));
		return lambert.force(a) + scale * std::sin(alpha) * std::sin(theta + alpha); // (11), attractive
	}
};

struct Richefeu { // Richefeu2008 eq. (4), (5), (7), (10), (11)
	static constexpr const char* reference = "Richefeu2008 eq. (4), (5), (10), (11)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, 4, true, false, "Willett's range, Gladkyy2014 section 2.3; ratio <= 4 checked here (none printed in Richefeu2008)" };
	static constexpr bool   monotone = true, own_rupture = false, needs_linear = false;
	double scale;      // kappa sqrt(R1 R2) [N], eq. (4), (5)
	double inv_lambda; // 1 / lambda [1/m], eq. (11)
	static Richefeu make(const BridgeSpec&, const Pair&, double& rupture);
	double          force0() const { return scale; }
	double          force(double a) const { return scale * std::exp(-a * inv_lambda); } // (10)
};

struct Soulie { // Soulie et al. 2006, coefficients as printed there (see models.cpp)
	static constexpr const char* reference = "Soulie2006 (coefficients as printed there)";
	static constexpr Domain domain    = { 1e-5, 0.1, theta_50deg, 4, true, false, "Willett's range, Gladkyy2014 section 2.3; ratio <= 4 checked here (none printed)" };
	static constexpr bool   monotone = true, own_rupture = false, needs_linear = false;
	double A;     // -1.1 V*^-0.53 / R_large [1/m]
	double B, C;  // [-]
	double scale; // pi gamma sqrt(R1 R2) [N]
	static Soulie make(const BridgeSpec&, const Pair&, double& rupture);
	double        force0() const { return force(0); }
	double        force(double a) const { return scale * (C + std::exp(A * a + B)); }
};

struct LinearIrreversible { // Roy et al. eq. (16), (17), calibration of their section 4.2
	static constexpr const char* reference = "Roy eq. (16), (17), section 4.2";
	// The linear law has no range of its own; calibrated, it inherits its reference model's.
	static constexpr Domain domain    = { 0, Plausible::vstar_max, pi / 2, inf_ratio, true, false,
                                           "none (calibrated: the reference model's)" };
	static constexpr bool   monotone = true, own_rupture = true, needs_linear = true;
	double fmax; // [N]
	double kc;   // [N/m]
	static LinearIrreversible make(const BridgeSpec&, const Pair&, double& rupture);
	double                    force0() const { return fmax; }
	double                    force(double a) const { return std::max(0.0, fmax - kc * a); } // Roy (16)
};

struct YoungLaplaceTable { // exact Young-Laplace bridge, tabulated (young_laplace_table.hpp)
	static constexpr const char* reference = "Young-Laplace solver, tabulated (data/young_laplace_table.bin)";
	static constexpr Domain domain    = { 1e-5, 0.5, yltable::theta_max, 4, true, false, "the table's nodes (young_laplace_table.hpp)" };
	// Not monotone: at large contact angles the exact force first grows slightly with the gap.
	static constexpr bool monotone = false, own_rupture = true, needs_linear = false;
	using Coefficients            = std::array<double, yltable::n_coefficients>;
	std::shared_ptr<const Coefficients> k; // the bridge's Hermite segments of 1/F (shared by copies)
	static YoungLaplaceTable make(const BridgeSpec&, const Pair&, double& rupture);
	double                   force0() const { return 1 / (*k)[1]; } // the first segment at x = 0: 1/F(0)
	double                   force(double a) const { return yltable::force(k->data(), a); }
};

// Extrapolation (BridgeSpec::extrapolate): the model M of the nearest in-domain bridge (V*,
// contact angles and size ratio clamped to M::domain), with its gap range stretched to the
// actual bridge's rupture distance and its force scaled by R cos(theta) / (R_c cos(theta_c)),
// the Derjaguin scaling of the force at contact. The result is finite, non-negative, zero beyond
// rupture and monotone where M is, because the in-domain bridge is (the contract suite).
template <class M> struct Extrapolated {
	M      m;
	double gap_scale;   // rupture of the in-domain bridge / actual rupture [-]
	double force_scale; // [-]
	double force0() const { return force_scale * m.force0(); }
	double force(double a) const { return force_scale * m.force(a * gap_scale); }
};

template <class... M> struct ModelSet;
template <class... M> struct ModelSet<void, M...> {
	// Index 0: no bridge; 1..n: the models in the order of CAPILLARY_MODELS; n+1..2n: extrapolated.
	using Variant                   = std::variant<std::monostate, M..., Extrapolated<M>...>;
	static constexpr std::size_t n = sizeof...(M);
};
#define CAPILLARY_TYPE_(name, Type) , Type
using Models = ModelSet<void CAPILLARY_MODELS(CAPILLARY_TYPE_)>;
#undef CAPILLARY_TYPE_

// One bridge: its model (the variant's index) and that model's invariants only.
struct Bridge {
	Models::Variant m;
	double          rupture = 0; // [m] gap at which the bridge breaks
	double          force0  = 0; // [N] force at contact, F(a <= 0)
	double          force_rupture = 0; // [N] force at the rupture distance: the cap of the continued force
	Model           model() const // throws std::logic_error for a default Bridge (no model)
	{
		if (m.index() == 0) throw std::logic_error("capillary::Bridge: no model (default-constructed bridge)");
		return Model((m.index() - 1) % Models::n);
	}
	bool            extrapolated() const { return m.index() > Models::n; }
};

// Validates (std::invalid_argument naming the parameter, its value and its allowed range) and
// computes the invariants.
Bridge make_bridge(const BridgeSpec& spec);

// The force of the bridge's model at a > 0 (0 without a model). By index rather than std::visit, which
// libstdc++ makes an indirect call through a table per bridge-step: a chain of compares on the index
// lets the compiler inline the force of each model.
template <std::size_t... I> inline double force_by_index(const Models::Variant& m, double a, std::index_sequence<I...>)
{
	double f = 0;
	(void)((m.index() == I + 1 && (f = std::get_if<I + 1>(&m)->force(a), true)) || ...);
	return f;
}

// Capillary force [N] at gap a [m] of a bridge that lasts up to the gap `range` [m]: 0 for a > range
// (and a NaN gap), F(0) for a <= 0. range = b.rupture is the static bridge (bridge_force). A longer
// range is the dynamic rupture rule (Elskamp2018 eq. 33): between the static rupture distance and
// range each model's formula is continued (Elskamp evaluates the closed-form models up to
// S_rup,dyn), floored at 0 and capped at the force at the static rupture distance: Soulie's
// constant C may turn the continued formula negative, Weigert's has a pole (its neck radius, eq.
// A7, reaches 0 at 2-4 S_rup), and the tabulated exact bridge, which has no static solution there,
// keeps its force at the static rupture distance.
inline double bridge_force_within(const Bridge& b, double a, double range)
{
	if (!(a <= range)) return 0;
	if (a <= 0) return b.force0;
	const double f = force_by_index(b.m, a, std::make_index_sequence<std::variant_size_v<Models::Variant> - 1>());
	return a <= b.rupture ? f : std::min(std::max(f, 0.0), b.force_rupture);
}
// Capillary force [N] at gap a [m]: 0 for a > rupture (and a NaN gap), F(0) for a <= 0.
inline double bridge_force(const Bridge& b, double a) { return bridge_force_within(b, a, b.rupture); }

// One-shot convenience: make_bridge() + bridge_force().
double force(const BridgeSpec& spec, double a);

// Adhesive energy [J] of a bridge: the integral of F over [0, rupture]. Bounded cost: throws
// std::runtime_error if the quadrature does not converge within its budget of evaluations.
double adhesive_energy(const Bridge& b);

// The model table, derived from CAPILLARY_MODELS.
struct ModelInfo {
	Model       model;
	const char* name;
	const char* reference;
	bool        monotone; // force non-increasing in the gap over the whole bridge
	bool        own_rupture;
	bool        needs_linear;
	Domain      domain;
};
struct RuptureInfo {
	Rupture     rule;
	const char* name;
	const char* reference;
};
const std::vector<ModelInfo>&   models();
const std::vector<RuptureInfo>& rupture_rules();
const ModelInfo&                info(Model m);
Model                           model_from_name(const std::string& name);   // throws std::invalid_argument
Rupture                         rupture_from_name(const std::string& name); // throws std::invalid_argument
const char*                     name_of(Model m);
const char*                     name_of(Rupture r);
std::string                     model_names(); // "weigert, willett_full, ..." for error messages
std::string                     rupture_names();

} // namespace capillary
