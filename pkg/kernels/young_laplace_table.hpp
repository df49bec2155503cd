// young_laplace_table: the exact Young-Laplace bridge force at the cost of a closed-form model.
// Forces of the solver (young_laplace.hpp) tabulated in dimensionless variables
//   ln V*  (V* = V / Rh^3, Rh = 2 R1 R2 / (R1 + R2)),  theta,  rho = R_small / R_large (0: plane),
//   tau = 1 - sqrt(1 - w), w = sqrt(1 - a / a_rupture): F is smooth in w at the fold, where F(a)
//   has a square-root singularity, and tau clusters the nodes near contact, where F(a) is steep,
// as ln(F / (2 pi Rh gamma)) and ln(a_rupture / Rh). A bridge interpolates its own curve F(tau)
// once (cubic Lagrange in ln V*, theta, rho); a force is then one cubic interpolation in tau.
// The table is data/young_laplace_table.csv, written by tools/generate_young_laplace_table.py and
// compiled into the library.
#pragma once

#include <array>

namespace capillary {
namespace yltable {

	constexpr int n_lnv = 17, n_theta = 21, n_rho = 9, n_w = 25;
	constexpr double lnv_min = -11.512925464970229, lnv_max = -2.302585092994046; // ln 1e-5, ln 0.1 (all of Gladkyy Table 1)
	constexpr double theta_max = 0.8726646259971648;                                // 50 degrees
	// rho nodes: the plane (0), R_small / R_large from 1/4 to 0.95, and equal spheres (1); the domain
	// is {0} and [1/4, 1]. Equal spheres are a slice of their own: at large contact angles the
	// symmetric bridge of exactly equal spheres ruptures at a larger gap than a slightly unequal
	// pair (the symmetry-breaking bifurcation becomes an imperfect one: the rupture gap drops by up to
	// 6 % between rho = 1 and rho = 0.99 at theta = 45 deg), so it is not interpolated across; pairs
	// with rho in (0.95, 1) extrapolate from the unequal nodes.
	constexpr std::array<double, n_rho> rho_nodes = { 0.0, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.95, 1.0 };
	inline double lnv_node(int i) { return lnv_min + (lnv_max - lnv_min) * i / (n_lnv - 1); }
	inline double theta_node(int i) { return theta_max * i / (n_theta - 1); }
	inline double tau_node(int i) { return double(i) / (n_w - 1); }
	// Gap fraction a / a_rupture at a tau node: w = 1 - (1 - tau)^2, a / a_rupture = 1 - w^2.
	inline double gap_fraction(double tau)
	{
		const double w = 1 - (1 - tau) * (1 - tau);
		return 1 - w * w;
	}

	// Interpolated curve of one bridge: force [N] at the tau nodes and the rupture gap [m].
	struct Curve {
		std::array<double, n_w> force;
		double                  rupture;
	};
	// Throws std::invalid_argument naming the variable outside the table's domain.
	Curve curve(double R1, double R2, double volume, double gamma, double theta1, double theta2);
	// Force [N] at gap a in [0, rupture] from the curve: cubic Lagrange in tau.
	double force(const double* f, double inv_rupture, double a);

} // namespace yltable
} // namespace capillary
