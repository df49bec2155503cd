// Conventions shared by every capillary kernel, in one place: pi, the wall as a sphere of
// infinite radius and its Derjaguin-equivalent pair, the harmonic mean radius, the limits of
// physically meaningful input, and the wording of out-of-range errors.
#pragma once

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace capillary {

constexpr double pi = 3.14159265358979323846;

// A wall or facet is a sphere of infinite radius (R2 = wall_radius).
constexpr double wall_radius = std::numeric_limits<double>::infinity();
inline bool      is_wall(double R) { return std::isinf(R) && R > 0; }

// Gladkyy2014 eq. (1): effective radius of two spheres.
inline double harmonic_mean_radius(double r1, double r2) { return 2 * r1 * r2 / (r1 + r2); }

// Two contact angles as one, for the force models: the angle whose cosine is the mean of the
// cosines, acos((cos theta1 + cos theta2)/2) [rad] (Elskamp2018 eq. 14-15). It is the exact
// small-volume limit (a sphere-plane bridge tends to F(0) = 2 pi R1 gamma (cos theta1 + cos theta2));
// against the exact solver for glass-steel (15/45 deg) and POM-PVC (40/50 deg) it is closer than the
// cosine of the mean angle, which over-predicts F(0) by 3.5-4.9 % for glass-steel
// (scripts/mixed_angles.py, docs/models.md). Equal angles are returned unchanged.
inline double equivalent_angle(double theta1, double theta2)
{
	return theta1 == theta2 ? theta1 : std::acos((std::cos(theta1) + std::cos(theta2)) / 2);
}

// Volume of a sphere of radius r between two planes at distances d1 <= d2 from its centre (clamped
// to the sphere) [m^3]: pi (r^2 (d2 - d1) - (d2^3 - d1^3)/3). Splits a bridge's liquid at its neck.
inline double sphere_slab_volume(double r, double d1, double d2)
{
	d1 = std::fmin(std::fmax(d1, -r), r), d2 = std::fmin(std::fmax(d2, -r), r);
	return pi * (r * r * (d2 - d1) - (d2 * d2 * d2 - d1 * d1 * d1) / 3);
}

// Derjaguin: a sphere R1 against a plane is equivalent to two equal spheres of radius 2 R1, whose
// harmonic and geometric means are both 2 R1, so that every model gives the sphere-plane limit
// F(0) = 4 pi R1 gamma cos(theta).
inline void equivalent_pair(double R1, double R2, double& r1, double& r2)
{
	if (is_wall(R2)) r1 = r2 = 2 * R1;
	else {
		r1 = R1;
		r2 = R2;
	}
}

// Physically meaningful input, whatever the model: outside these limits a value is a mistake
// (a unit error, an uninitialised variable), not a bridge. Radii from a nanometre to a kilometre;
// surface tensions from ultra-low interfacial tensions (~1e-6 N/m) to molten metals (~2 N/m);
// a pendular bridge holds less liquid than the particles (V* = V/R^3 <= 1, R the harmonic mean).
struct Plausible {
	static constexpr double radius_min = 1e-9, radius_max = 1e3;   // [m]
	static constexpr double gamma_min = 1e-7, gamma_max = 10;      // [N/m]
	static constexpr double vstar_min = 1e-15, vstar_max = 1;      // [-]
	static constexpr double force_max = 1e6;                       // [N], 2 pi R gamma of a 1 km grain at 10 N/m: 6e4 N
	static constexpr double range_max = 10;                        // bridge range / effective radius [-]
};

// The shortest text (from 15 significant digits up) that reads back as x, so that a message shows
// exactly what was given: 1e-07, not 0.000000 (std::to_string) or 9.9999999999999995e-08.
inline std::string format_value(double x)
{
	std::ostringstream out;
	for (int digits = std::numeric_limits<double>::digits10;; ++digits) {
		out.str("");
		out.precision(digits);
		out << x;
		if (!std::isfinite(x) || digits >= std::numeric_limits<double>::max_digits10) return out.str();
		std::istringstream in(out.str());
		double             back = 0;
		in >> back;
		if (back == x) return out.str();
	}
}

// The one wording of out-of-range errors: "<name> = <value> <unit> is outside the allowed range
// <range>[; <hint>]". Callers (Python bindings, the YADE layer) report it as ValueError.
[[noreturn]] inline void out_of_range(const std::string& name, double value, const std::string& range, const std::string& unit,
                                      const std::string& hint = "")
{
	throw std::invalid_argument(name + " = " + format_value(value) + (unit.empty() ? "" : " " + unit) + " is outside the allowed range " + range
	                            + (hint.empty() ? "" : "; " + hint));
}

// The names of a table of named rules (models, rupture rules, viscous laws, transfer rules), as
// listed in errors and docstrings: "a, b, c".
template <class Table> std::string join_names(const Table& table)
{
	std::string s;
	for (const auto& row : table) s += (s.empty() ? "" : ", ") + std::string(row.name);
	return s;
}

// The radii of a pair (R2 may be a wall), checked against Plausible: the one check of every kernel.
// The message is built only when a check fails: a bridge's formation calls this several times.
inline void check_radii(double R1, double R2)
{
	const auto radii = [] { return "[" + format_value(Plausible::radius_min) + ", " + format_value(Plausible::radius_max) + "]"; };
	if (!(R1 >= Plausible::radius_min && R1 <= Plausible::radius_max)) out_of_range("R1", R1, radii(), "m");
	if (!((R2 >= Plausible::radius_min && R2 <= Plausible::radius_max) || is_wall(R2))) out_of_range("R2", R2, radii() + " or inf (a wall)", "m");
}

} // namespace capillary
