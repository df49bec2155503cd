// young_laplace_table: the exact Young-Laplace bridge force at the cost of a closed-form model.
// Forces of the solver (young_laplace.hpp) tabulated in dimensionless variables
//   ln V*  (V* = V / Rh^3, Rh = 2 R1 R2 / (R1 + R2)),  theta,  rho = R_small / R_large (0: plane),
//   tau = 1 - sqrt(1 - w), w = sqrt(1 - a / a_rupture): F is smooth in w at the fold, where F(a)
//   has a square-root singularity, and tau clusters the nodes near contact, where F(a) is steep,
// as ln(F / (2 pi Rh gamma)) and ln(a_rupture / Rh). A bridge interpolates its own curve F(tau)
// once (cubic Lagrange in ln V*, theta, sqrt(1 - rho)) and turns it into the form it evaluates every step:
// 1/F as a cubic Hermite spline on fixed nodes, in u = a / a_rupture up to u = 63/64 and in
// w = sqrt(1 - u) beyond (one square root, only there: 1/64 of the range, so that the branch is
// rarely mispredicted; a mispredicted branch cost about 30 % with the split at u = 15/16). 1/F is
// nearly polynomial in u where F falls steeply (for Willett's reduced model it is a quadratic), so
// 13 segments suffice (0.2 % of the solver) and a force costs a table lookup, a cubic and one division.
// The table is data/young_laplace_table.csv, written by tools/generate_young_laplace_table.cpp and
// compiled into the library.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace capillary {
namespace yltable {

	constexpr int n_lnv = 17, n_theta = 21, n_rho = 9, n_w = 25;
	constexpr double lnv_min = -11.512925464970229, lnv_max = -2.302585092994046; // ln 1e-5, ln 0.1 (all of Gladkyy Table 1)
	constexpr double theta_max = 0.8726646259971648;                                // 50 degrees
	// rho nodes: the plane (0), and R_small / R_large from 1/4 to 1 (equal spheres), interpolated in
	// sqrt(1 - rho): near equal spheres at larger contact angles the rupture gap falls like
	// sqrt(1 - rho) (the symmetry-breaking bifurcation of equal spheres unfolds into a fold).
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

	// A table on these nodes (data/young_laplace_table.csv, data/transfer_table.csv): rows of row_len
	// numbers in node order, each starting with its node (ln V*, theta, rho). The row of node (i, j, k):
	inline const double* node_row(const double* table, int row_len, int i, int j, int k)
	{
		return table + ((size_t(i) * n_theta + j) * n_rho + k) * row_len;
	}
	// Throws std::logic_error naming `file` if a row's node differs from the axes (a stale table).
	void check_nodes(const double* table, int row_len, const char* file);

	// Where a bridge lies among the nodes: cubic Lagrange stencils in ln V*, theta and sqrt(1 - rho)
	// (a plane has its own slice, nk = 1). Shared by the force table and the exact transfer table
	// (transfer_table.cpp), which have the same nodes.
	struct Stencil {
		int    i0 = 0, j0 = 0, k0 = 0, nk = 1; // first node of each stencil; nodes in rho
		double wv[4] {}, wt[4] {}, wr[4] = { 1, 0, 0, 0 };
		double Rh = 0;            // harmonic mean radius of the pair (2 R1 against a plane) [m]
		bool   small_first = true; // solid 1 is the smaller sphere (or the sphere against a plane)
	};
	// Throws std::invalid_argument, worded "<table>: <variable> ... is outside the table's range ...",
	// for a bridge outside the nodes (V*, theta, rho) or with unequal contact angles.
	Stencil locate(const char* table, double R1, double R2, double volume, double theta1, double theta2);
	// f(weight, i, j, k) for every node of the stencil.
	template <class F> void for_each_node(const Stencil& s, const F& f)
	{
		for (int a = 0; a < 4; ++a)
			for (int b = 0; b < 4; ++b)
				for (int c = 0; c < s.nk; ++c) f(s.wv[a] * s.wt[b] * s.wr[c], s.i0 + a, s.j0 + b, s.k0 + c);
	}

	// Interpolated curve of one bridge: force [N] at the tau nodes and the rupture gap [m].
	struct Curve {
		std::array<double, n_w> force;
		double                  rupture;
	};
	// Throws std::invalid_argument naming the variable outside the table's domain.
	Curve curve(double R1, double R2, double volume, double gamma, double theta1, double theta2);
	// Force [N] at gap a in [0, rupture] from the curve: cubic Lagrange in tau.
	double curve_force(const Curve& c, double a);

	// The evaluated form: 1/F as a cubic Hermite spline through fixed nodes, in x = u_cells * u up to
	// u = 63/64 and in x = w_cells * w beyond (w = sqrt(1 - u) falls from 1/8 to 0 at rupture). Each
	// segment is stored as a cubic in x itself, so a force is: x, a lookup of the segment, a cubic
	// and one division (and one square root beyond u = 63/64).
	// Coefficients of one bridge: k[0] = u_cells / rupture [1/m], then c0..c3 of each segment.
	constexpr int                      n_u = 13, n_wn = 2, n_segments = n_u - 1 + n_wn - 1;
	constexpr int                      n_coefficients = 1 + 4 * n_segments;
	constexpr std::array<double, n_u> u_nodes = { 0, 5 / 128., 10 / 128., 16 / 128., 26 / 128., 38 / 128., 64 / 128., 96 / 128., 109 / 128., 115 / 128., 120 / 128., 124 / 128., 126 / 128. };
	constexpr std::array<double, n_wn> w_nodes = { 0.125, 0 }; // u_nodes[n_u - 1] = 1 - w_nodes[0]^2
	// Every node is a multiple of 1/u_cells (u) or 1/w_cells (w), so a segment is found by one lookup.
	constexpr int u_cells = 128, w_cells = 64;
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
