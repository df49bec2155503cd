// young_laplace_table: the exact Young-Laplace bridge force at the cost of a closed-form model.
// Forces of the solver (young_laplace.hpp) tabulated in dimensionless variables
//   ln V*  (V* = V / Rh^3, Rh = 2 R1 R2 / (R1 + R2), 2 R1 against a plane),
//   rho = R_small / R_large (0: a plane),
//   theta_s, the contact angle on the smaller sphere (on the sphere against a plane),
//   theta_l, the contact angle on the other solid,
//   tau = 1 - sqrt(1 - w), w = sqrt(1 - a / a_rupture): F is smooth in w at the fold, where F(a)
//   has a square-root singularity, and tau clusters the nodes near contact, where F(a) is steep,
// as asinh(F / (2 pi Rh gamma delta)) (delta = force_delta: like ln F where F is large, and smooth through
// 0 where the exact force turns repulsive, at V* > 0.3 with both angles near 70 deg), ln(a_rupture / Rh)
// and the share of the liquid on the small solid's side of the neck at rupture (the exact transfer
// ratio, transfer.hpp).
//
// The rupture gap has a ridge across the angles: at fixed (V*, rho, theta_s) it peaks at one
// theta_l = c, where the stable branch ends in a symmetry-breaking bifurcation (the two contact
// lines mirror each other about the neck; for equal spheres c = theta_s above about 20 deg), and
// falls like |theta_l - c|^(2/3) on both sides, an imperfect pitchfork (measured: 0.5 |delta|^(2/3)
// relative, delta in rad, from 1e-4 to 0.3 rad). No polynomial in theta_l follows that cusp; in
// s = cbrt(theta_l - c) every quantity is smooth. So each (ln V*, rho, theta_s) row holds its
// ridge c and the bridge on Chebyshev-Lobatto nodes in s from theta_l = 0 to theta_top, and a
// bridge interpolates in s (barycentric, all nodes) and by cubic Lagrange in theta_s (the four
// nearest Chebyshev nodes), ln V* and rho. Where the ridge lies beyond the tabulated angles (walls and
// small ratios at large V* and theta_s) the centre is held below theta_top (center_of).
// The tables are data/young_laplace_table.bin (float32 values) and data/young_laplace_table_rows.csv
// (the rows' ridges), written by tools/generate_young_laplace_table.cpp and compiled into the library.
// The bridge's curve F(tau) is interpolated once and turned into the form it evaluates every step:
// 1/F as a cubic Hermite spline on fixed nodes, in u = a / a_rupture up to u = 63/64 and in
// w = sqrt(1 - u) beyond (one square root, only there: 1/64 of the range, so that the branch is
// rarely mispredicted; a mispredicted branch cost about 30 % with the split at u = 15/16). 1/F is
// nearly polynomial in u where F falls steeply (for Willett's reduced model it is a quadratic), so
// a force costs a table lookup, a cubic and one division.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace capillary {
namespace yltable {

	constexpr int    n_lnv = 16, n_rho = 9, n_ts = 15, n_tl = 25, n_w = 25;
	constexpr double lnv_min = -11.512925464970229, lnv_max = -0.6931471805599453; // ln 1e-5, ln 0.5
	constexpr double theta_max = 1.2217304763960306;                                // 70 deg: the domain
	constexpr double theta_top = 1.4311699866353502;                                // 82 deg: the tabulated theta_l
	// The ridge's centre is held below ridge_cap (center_of), so that every row spans it.
	constexpr double ridge_cap = 1.361356816555577, ridge_soft = 0.06981317007977318; // 78 deg, 4 deg
	// rho nodes: the plane (0), and R_small / R_large from 1/4 to 1 (equal spheres).
	constexpr std::array<double, n_rho> rho_nodes = { 0.0, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.95, 1.0 };
	inline double lnv_node(int i) { return lnv_min + (lnv_max - lnv_min) * i / (n_lnv - 1); }
	// Chebyshev-Lobatto points on [0, 1], increasing.
	inline double lobatto(int m, int n) { return 0.5 - 0.5 * std::cos(3.141592653589793 * m / (n - 1)); }
	inline double theta_s_node(int j) { return theta_max * lobatto(j, n_ts); }
	inline double tau_node(int i) { return double(i) / (n_w - 1); }
	// Gap fraction a / a_rupture at a tau node: w = 1 - (1 - tau)^2, a / a_rupture = 1 - w^2.
	inline double gap_fraction(double tau)
	{
		const double w = 1 - (1 - tau) * (1 - tau);
		return 1 - w * w;
	}
	// The centre of a row's s coordinate from its ridge c [rad]: c up to ridge_cap - ridge_soft, then
	// smoothly (C1) towards ridge_cap.
	inline double center_of(double ridge)
	{
		const double knee = ridge_cap - ridge_soft;
		return ridge <= knee ? ridge : ridge_cap - ridge_soft * std::exp(-(ridge - knee) / ridge_soft);
	}
	// theta_l <-> x in [0, 1] on a row of centre c: s = cbrt(theta_l - c) from -cbrt(c) to cbrt(theta_top - c).
	inline double theta_l_at(double x, double c)
	{
		const double lo = -std::cbrt(c), hi = std::cbrt(theta_top - c), s = lo + x * (hi - lo);
		return std::clamp(c + s * s * s, 0.0, theta_top);
	}
	inline double x_of(double theta_l, double c)
	{
		const double lo = -std::cbrt(c), hi = std::cbrt(theta_top - c);
		return (std::cbrt(theta_l - c) - lo) / (hi - lo);
	}
	constexpr double force_delta = 0.01; // F / (2 pi Rh gamma) is tabulated as asinh(F / (2 pi Rh gamma force_delta))
	// Values per node: ln(a_rupture / Rh), the transfer share of the small solid, asinh(F / (2 pi Rh gamma force_delta)) at the tau nodes.
	constexpr int n_values = 2 + n_w;
	constexpr int n_rows = n_lnv * n_rho * n_ts;
	// Row index of node (i in ln V*, k in rho, j in theta_s).
	inline int row_index(int i, int k, int j) { return (i * n_rho + k) * n_ts + j; }

	// Interpolated curve of one bridge: its force at the tau nodes (as g), the rupture gap and the transfer ratio.
	struct Curve {
		std::array<double, n_w> g;         // asinh(F / (scale force_delta)) at the tau nodes [-]
		double                  scale;     // 2 pi Rh gamma [N]
		double                  rupture;   // [m]
		double                  transfer1; // share of the liquid on solid 1's side of the neck at rupture [-]
	};
	// Throws std::invalid_argument, worded "<who>: <variable> ... is outside the table's range ...",
	// for a bridge outside the domain (V*, either angle, rho).
	Curve curve(double R1, double R2, double volume, double gamma, double theta1, double theta2, const char* who = "young_laplace_table");
	// Only the curve's transfer1 (the exact transfer ratio at rupture), at a 27th of the cost.
	double transfer1(double R1, double R2, double volume, double theta1, double theta2, const char* who);
	// Force [N] at gap a in [0, rupture] from the curve: 6-point Lagrange in tau of g (of ln F, 4 points
	// left 3.6e-4 of the solver near contact at V* ~ 1e-5, 6 points 6e-5).
	double curve_force(const Curve& c, double a);

	// The evaluated form: 1/F as a cubic Hermite spline through fixed nodes, in x = u_cells * u up to
	// u = 63/64 and in x = w_cells * w beyond (w = sqrt(1 - u) falls from 1/8 to 0 at rupture). Each
	// segment is stored as a cubic in x itself, so a force is: x, a lookup of the segment, a cubic
	// and one division (and one square root beyond u = 63/64).
	// Coefficients of one bridge: k[0] = u_cells / rupture [1/m], then c0..c3 of each segment.
	constexpr int                      n_u = 25, n_wn = 3, n_segments = n_u - 1 + n_wn - 1;
	constexpr int                      n_coefficients = 1 + 4 * n_segments;
	// 25 nodes in u and 2 segments in w keep the form within 1.3e-4 of the solver's curve (13 and 1: 1.5e-3).
	constexpr std::array<double, n_u> u_nodes = { 0, 5 / 256., 10 / 256., 15 / 256., 20 / 256., 26 / 256., 32 / 256., 42 / 256., 52 / 256.,
		                                          64 / 256., 76 / 256., 102 / 256., 128 / 256., 160 / 256., 192 / 256., 205 / 256., 218 / 256.,
		                                          224 / 256., 230 / 256., 235 / 256., 240 / 256., 244 / 256., 248 / 256., 250 / 256., 252 / 256. };
	constexpr std::array<double, n_wn> w_nodes = { 0.125, 0.0625, 0 }; // u_nodes[n_u - 1] = 1 - w_nodes[0]^2
	// Every node is a multiple of 1/u_cells (u) or 1/w_cells (w), so a segment is found by one lookup.
	constexpr int u_cells = 256, w_cells = 64;
	constexpr double u_split = 126 / 128., w_split = 0.125;

	namespace detail {
		struct SegmentOf {
			std::array<std::uint8_t, u_cells + 1>     u {}; // cell int(x) -> segment, u < u_split
			std::array<std::uint8_t, int(w_split * w_cells) + 1> w {}; // cell int(x) -> segment, u >= u_split
		};
		constexpr bool on_grid(double x, int cells)
		{
			const double c = x * cells;
			return c - int(c + 0.5) < 1e-9 && int(c + 0.5) - c < 1e-9;
		}
		constexpr SegmentOf segment_of()
		{
			for (double u : u_nodes)
				if (!on_grid(u, u_cells)) throw "u_nodes must be multiples of 1/u_cells"; // a compile error
			for (double w : w_nodes)
				if (!on_grid(w, w_cells)) throw "w_nodes must be multiples of 1/w_cells";
			SegmentOf s;
			for (int c = 0; c <= u_cells; ++c) {
				int i = 0;
				while (i < n_u - 2 && u_nodes[i + 1] * u_cells < c + 0.5) ++i;
				s.u[c] = std::uint8_t(i);
			}
			for (int c = 0; c <= int(w_split * w_cells); ++c) {
				int i = n_segments - 1;
				while (i > n_u - 1 && w_nodes[i - n_u + 1] * w_cells < c + 0.5) --i;
				s.w[c] = std::uint8_t(i);
			}
			return s;
		}
		inline constexpr SegmentOf segment = segment_of();
		static_assert(u_nodes[n_u - 1] == u_split && w_nodes[0] == w_split && w_split * w_split == 1 - u_split, "the u and w nodes must join at u_split");
	} // namespace detail

	// Fills k[0 .. n_coefficients) from the curve.
	void coefficients(const Curve& c, double* k);

	// Force [N] at gap a in (0, rupture].
	inline double force(const double* k, double a)
	{
		double x = a * k[0]; // u_cells * u
		int    i;
		if (x < u_split * u_cells) {
			i = detail::segment.u[int(x)];
		} else { // w_cells * sqrt(1 - u)
			x = std::sqrt(std::max(0.0, double(w_cells * w_cells) - x * (double(w_cells * w_cells) / u_cells)));
			i = detail::segment.w[int(x)];
		}
		const double* c = k + 1 + 4 * i;
		return 1 / (c[0] + x * (c[1] + x * (c[2] + x * c[3])));
	}

} // namespace yltable
} // namespace capillary
