// Transfer ratio of a breaking bridge: Elskamp2018's parabolic bridge (eq. 35-43) and Richefeu2008's
// split in proportion to the diameters; see transfer.hpp.
#include "transfer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace capillary {

namespace {

	// pi times the integral of (a x^2 + b x + c)^2 over [0, x] [m^3].
	double parabola_volume(double a, double b, double c, double x)
	{
		const double x2 = x * x, x3 = x2 * x;
		return pi * (a * a * x3 * x2 / 5 + a * b * x2 * x2 / 2 + (b * b + 2 * a * c) * x3 / 3 + b * c * x2 + c * c * x);
	}
	// Spherical cap of height d and base radius y: pi d (3 y^2 + d^2)/6 [m^3] (Elskamp2018 eq. 42-43).
	double cap(double d, double y) { return pi * d * (3 * y * y + d * d) / 6; }

	// Bisection for the root of a monotone f on [lo, hi] (f(lo), f(hi) of opposite signs).
	template <class F> double bisect(double lo, double hi, F f)
	{
		const bool rising = f(hi) > f(lo);
		for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
			const double m = (lo + hi) / 2;
			((f(m) > 0) == rising ? hi : lo) = m;
		}
		return (lo + hi) / 2;
	}

	// The parabola through the contact line on solid 1 (filling angle beta1) meeting it at theta1
	// (eq. 36, 39): c = y(0) = R1 sin(beta1), atan(Y'(0)) = theta1 - pi/2 + beta1.
	struct Left {
		double d, y, b;
	};
	Left left(double R1, double beta1, double theta1) { return { R1 * (1 - std::cos(beta1)), R1 * std::sin(beta1), std::tan(theta1 - pi / 2 + beta1) }; }

} // namespace

double diameter_transfer(double R1, double R2)
{
	check_radii(R1, R2);
	return is_wall(R2) ? 1.0 : R1 / (R1 + R2);
}

ParabolicBridge parabolic_transfer(double R1, double R2, double volume, double S, double theta1, double theta2)
{
	check_radii(R1, R2);
	if (!(volume > 0 && std::isfinite(volume))) out_of_range("volume", volume, "(0, inf)", "m^3");
	if (!(S >= 0 && std::isfinite(S))) out_of_range("S", S, "[0, inf)", "m");
	if (!(theta1 >= 0 && theta1 < pi / 2)) out_of_range("theta1", theta1, "[0, pi/2)", "rad");
	const bool wall = is_wall(R2);
	// A parabola cannot meet a plane tangentially: theta_w = 0 would need an infinite slope.
	if (wall && !(theta2 >= 1e-3 && theta2 < pi / 2)) out_of_range("theta2", theta2, "[0.001, pi/2) for a wall (a parabola meets a plane at a finite slope)", "rad");
	if (!wall && !(theta2 >= 0 && theta2 < pi / 2)) out_of_range("theta2", theta2, "[0, pi/2)", "rad");

	ParabolicBridge p;
	// Given beta1 (and beta2 for a sphere), the parabola and its liquid volume (eq. 35-41).
	auto build = [&](double beta1, double beta2) {
		const Left l = left(R1, beta1, theta1);
		p.d1 = l.d, p.c = l.y, p.b = l.b;
		if (wall) {
			p.d2     = 0;
			p.length = l.d + S;
			p.a      = (1 / std::tan(theta2) - p.b) / (2 * p.length); // theta_w = pi/2 - atan(Y'(d_lb))
		} else {
			p.d2           = R2 * (1 - std::cos(beta2));
			const double y2 = R2 * std::sin(beta2);
			p.length       = l.d + p.d2 + S;                                            // eq. (38)
			p.a            = (y2 - p.c - p.b * p.length) / (p.length * p.length);       // eq. (37)
		}
		const double yL = p.a * p.length * p.length + p.b * p.length + p.c;
		return parabola_volume(p.a, p.b, p.c, p.length) - cap(p.d1, p.c) - (wall ? 0.0 : cap(p.d2, yL)); // eq. (41)-(43)
	};
	const double top = pi / 2 - 1e-9;
	auto         solveBeta2 = [&](double beta1) { // eq. (40), corrected: theta2 = pi/2 - atan(Y'(d_lb)) - beta2
                auto r = [&](double beta2) {
                        build(beta1, beta2);
                        return pi / 2 - std::atan(2 * p.a * p.length + p.b) - beta2 - theta2;
                };
                if (!(r(1e-9) > 0 && r(top - theta2) < 0)) return -1.0;
                return bisect(1e-9, top - theta2, r);
	};
	auto volumeAt = [&](double beta1) {
		if (wall) return build(beta1, 0);
		const double beta2 = solveBeta2(beta1);
		return beta2 < 0 ? std::numeric_limits<double>::quiet_NaN() : build(beta1, beta2);
	};
	// beta1 from the volume: on the branch of concave menisci (a > 0, narrowest between the contact
	// lines, as a pendular bridge near rupture; small filling angles also give bulging parabolas that
	// hold the volume, which are not bridges) the volume grows with the contact line. Bracketed by
	// stepping up from a small filling angle, then bisection.
	double lo = -1, hi = 1e-4;
	bool   found = false;
	for (; hi < top - theta1; hi *= 1.1) {
		const double v = volumeAt(hi);
		if (!std::isnan(v) && p.a > 0) {
			if (v >= volume && lo > 0) {
				found = true;
				break;
			}
			if (v < volume) lo = hi;
		} else if (lo > 0) break; // past the concave branch
	}
	if (!found)
		throw std::runtime_error("parabolic_transfer: no concave parabolic bridge of volume " + format_value(volume) + " m^3 at S = " + format_value(S) + " m");
	const double beta1 = bisect(lo, hi, [&](double b1) {
		const double v = volumeAt(b1);
		return std::isnan(v) ? 1.0 : v / volume - 1;
	});
	const double v = volumeAt(beta1);
	if (!(std::abs(v / volume - 1) < 1e-9))
		throw std::runtime_error("parabolic_transfer: the parabola does not hold the volume " + format_value(volume) + " m^3 at S = " + format_value(S) + " m");
	// The narrowest section (eq. 42): the vertex of the parabola if it lies between the contact lines,
	// else the thinner end.
	const double yL = p.a * p.length * p.length + p.b * p.length + p.c;
	p.x_min         = (p.a > 0 && -p.b / (2 * p.a) > 0 && -p.b / (2 * p.a) < p.length) ? -p.b / (2 * p.a) : (p.c <= yL ? 0.0 : p.length);
	// Eq. (42) subtracts the whole cap of solid 1; if the neck lies inside the cap's extent (x_min < d1)
	// only the part of the sphere left of it is solid: the slab of sphere 1 (centre at x = d1 - R1).
	p.volume1       = parabola_volume(p.a, p.b, p.c, p.x_min) - sphere_slab_volume(R1, R1 - p.d1, p.x_min - p.d1 + R1);
	p.transfer1     = p.volume1 / volume;
	return p;
}

} // namespace capillary

namespace capillary {

namespace {
	const std::array<TransferInfo, 3> transfer_table = { {
	        { Transfer::exact, "exact", "Young-Laplace solver: the split at the neck at the exact rupture, tabulated in young_laplace_table" },
	        { Transfer::parabolic, "parabolic", "Elskamp2018 eq. 35-43 (parabolic meniscus at the rupture distance)" },
	        { Transfer::diameter, "diameter", "Richefeu2008: in proportion to the diameters" },
	} };
} // namespace

const std::array<TransferInfo, 3>& transfer_rules() { return transfer_table; }

std::string transfer_names() { return join_names(transfer_table); }

Transfer transfer_from_name(const std::string& name)
{
	for (const auto& t : transfer_table)
		if (name == t.name) return t.rule;
	throw std::invalid_argument("transfer = '" + name + "' is unknown; allowed: " + transfer_names());
}

double transfer_ratio(Transfer rule, double R1, double R2, double volume, double S, double theta1, double theta2)
{
	switch (rule) {
		case Transfer::exact: return exact_transfer(R1, R2, volume, theta1, theta2);
		case Transfer::parabolic: return parabolic_transfer(R1, R2, volume, S, theta1, theta2).transfer1;
		case Transfer::diameter: return diameter_transfer(R1, R2);
	}
	throw std::invalid_argument("transfer: unknown enumerator " + std::to_string(int(rule)));
}

} // namespace capillary
