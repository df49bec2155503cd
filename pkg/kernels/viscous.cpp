// Viscous bridge forces and the dynamic rupture distance (Elskamp2018 section 2.2.3, eq. 25-29, 33).
#include "viscous.hpp"

#include <algorithm>
#include <cmath>

namespace capillary {

namespace {

	const std::vector<NormalViscousInfo> normal_table = {
		{ NormalViscous::pitois, "pitois", "Elskamp2018 eq. (26), Pitois et al. 2000" },
		{ NormalViscous::adams_perchard, "adams_perchard", "Elskamp2018 eq. (25), Adams & Perchard 1985" },
	};

	void check_eta(double eta)
	{
		if (!(eta >= 0 && eta <= viscous_limits::eta_max))
			out_of_range("eta", eta, "[0, " + format_value(viscous_limits::eta_max) + "]", "Pa s");
	}
	// Velocities [m/s] and angular velocities [rad/s]: finite and at most velocity_max in magnitude.
	void check_finite(const char* name, double x, const char* unit)
	{
		if (!(std::abs(x) <= viscous_limits::velocity_max))
			out_of_range(name, x, "[-" + format_value(viscous_limits::velocity_max) + ", " + format_value(viscous_limits::velocity_max) + "]", unit);
	}
	void check_finite(const char* name, const Vec3& v, const char* unit)
	{
		for (int k = 0; k < 3; ++k) check_finite((std::string(name) + "[" + std::to_string(k) + "]").c_str(), v[k], unit);
	}
	// Validates S, R1, R2, eta, S_min_factor and returns S_eff.
	double checked_separation(double S, double R1, double R2, double eta, double S_min_factor)
	{
		check_radii(R1, R2);
		check_eta(eta);
		if (!std::isfinite(S)) out_of_range("S", S, "(-inf, inf) (finite)", "m");
		if (!(S_min_factor >= viscous_limits::s_min_factor_min && S_min_factor <= viscous_limits::s_min_factor_max))
			out_of_range("S_min_factor", S_min_factor,
			             "[" + format_value(viscous_limits::s_min_factor_min) + ", " + format_value(viscous_limits::s_min_factor_max) + "]", "");
		return std::max(S, 0.0) + S_min_factor * reduced_radius(R1, R2);
	}

	Vec3 cross(const Vec3& a, const Vec3& b) { return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] }; }
	double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

} // namespace

const std::vector<NormalViscousInfo>& normal_viscous_laws() { return normal_table; }
std::string                           normal_viscous_names() { return join_names(normal_table); }
NormalViscous normal_viscous_from_name(const std::string& name)
{
	for (const auto& i : normal_table)
		if (name == i.name) return i.law;
	throw std::invalid_argument("normal viscous law = '" + name + "' is unknown; allowed: " + normal_viscous_names());
}
const char* name_of(NormalViscous law)
{
	for (const auto& i : normal_table)
		if (i.law == law) return i.name;
	throw std::invalid_argument("unknown NormalViscous value " + std::to_string(int(law)));
}

ViscousBridge make_viscous(NormalViscous law, double R1, double R2, double eta, double volume, double gamma, double S_min_factor)
{
	checked_separation(0, R1, R2, eta, S_min_factor);
	if (!(volume >= 0 && std::isfinite(volume))) out_of_range("volume", volume, "[0, inf) (finite)", "m^3");
	if (law == NormalViscous::pitois) {
		double r1, r2;
		equivalent_pair(R1, R2, r1, r2);
		const double R = harmonic_mean_radius(r1, r2), vstar = volume / (R * R * R);
		if (!(vstar >= Plausible::vstar_min && vstar <= Plausible::vstar_max))
			out_of_range("V* = V/R^3", vstar, "[" + format_value(Plausible::vstar_min) + ", " + format_value(Plausible::vstar_max) + "]", "",
			             "volume = " + format_value(volume) + " m^3 (required by the pitois law)");
	} else if (law != NormalViscous::adams_perchard)
		throw std::invalid_argument("unknown NormalViscous value " + std::to_string(int(law)));
	if (!(gamma == 0 || (gamma >= Plausible::gamma_min && gamma <= Plausible::gamma_max)))
		out_of_range("gamma", gamma, "{0} or [" + format_value(Plausible::gamma_min) + ", " + format_value(Plausible::gamma_max) + "]", "N/m");
	ViscousBridge b;
	b.law   = law;
	b.rs    = reduced_radius(R1, R2);
	b.s_min = S_min_factor * b.rs;
	b.cn0   = 6 * pi * eta * b.rs * b.rs; // eq. (25), (26)
	b.ct0   = 6 * pi * eta * b.rs;        // eq. (28), (29)
	b.x0    = volume / (pi * b.rs);       // eq. (26)
	b.ca    = gamma > 0 ? std::sqrt(eta / gamma) : 0; // eq. (33)
	return b;
}

double effective_separation(double S, double R1, double R2, double S_min_factor) { return checked_separation(S, R1, R2, 0, S_min_factor); }

double normal_viscous_coefficient(NormalViscous law, double S, double R1, double R2, double eta, double volume, double S_min_factor)
{
	checked_separation(S, R1, R2, eta, S_min_factor);
	return make_viscous(law, R1, R2, eta, volume, 0, S_min_factor).normal_coefficient(S);
}

double normal_viscous_force(NormalViscous law, double S, double v_n, double R1, double R2, double eta, double volume, double S_min_factor)
{
	const double c = normal_viscous_coefficient(law, S, R1, R2, eta, volume, S_min_factor);
	check_finite("v_n", v_n, "m/s");
	if (c == 0) return 0;
	return -c * v_n;
}

void tangential_viscous_coefficients(double S, double R1, double R2, double eta, double S_min_factor, double& c_t, double& c_r, bool& near)
{
	checked_separation(S, R1, R2, eta, S_min_factor);
	make_viscous(NormalViscous::adams_perchard, R1, R2, eta, 0, 0, S_min_factor).tangential_coefficients(S, c_t, c_r, near);
}

TangentialViscous tangential_viscous(double S, const Vec3& n, const Vec3& v_rel, const Vec3& omega1, const Vec3& omega2, double R1, double R2,
                                     double eta, double S_min_factor)
{
	TangentialViscous t;
	tangential_viscous_coefficients(S, R1, R2, eta, S_min_factor, t.c_t, t.c_r, t.near);
	check_finite("n", n, "");
	check_finite("v_rel", v_rel, "m/s");
	check_finite("omega1", omega1, "rad/s");
	check_finite("omega2", omega2, "rad/s");
	const double nn = std::sqrt(dot(n, n));
	if (!(std::abs(nn - 1) <= 1e-6)) out_of_range("|n|", nn, "[1 - 1e-6, 1 + 1e-6] (a unit vector)", "");
	const bool wall = is_wall(R2);
	if (wall && dot(omega2, omega2) != 0)
		out_of_range("|omega2|", std::sqrt(dot(omega2, omega2)), "{0} for a wall (R2 = inf)", "rad/s",
		             "pass the wall's velocity at the contact point in v_rel");
	if (eta == 0) return t; // exactly zero
	const double vn = dot(v_rel, n);
	Vec3         vt, w_r;
	for (int k = 0; k < 3; ++k) {
		vt[k]  = v_rel[k] - vn * n[k];
		w_r[k] = R1 * omega1[k] + (wall ? 0.0 : R2 * omega2[k]); // omega_r, Elskamp2018 after eq. (27)
	}
	t.force        = tangential_viscous_force(t.c_t, t.c_r, n, vt, w_r);
	const Vec3 nxF = cross(n, t.force);
	for (int k = 0; k < 3; ++k) {
		t.moment1[k] = R1 * nxF[k];
		t.moment2[k] = wall ? 0.0 : R2 * nxF[k];
	}
	return t;
}

double dynamic_rupture_distance(double static_rupture, double v_rel, double eta, double gamma)
{
	if (!(static_rupture > 0 && static_rupture <= viscous_limits::rupture_max))
		out_of_range("static_rupture", static_rupture, "(0, " + format_value(viscous_limits::rupture_max) + "]", "m");
	check_finite("v_rel", v_rel, "m/s");
	check_eta(eta);
	if (!(gamma >= Plausible::gamma_min && gamma <= Plausible::gamma_max))
		out_of_range("gamma", gamma, "[" + format_value(Plausible::gamma_min) + ", " + format_value(Plausible::gamma_max) + "]", "N/m");
	return static_rupture * (1 + std::sqrt(std::abs(v_rel) * eta / gamma)); // eq. (33)
}

} // namespace capillary
