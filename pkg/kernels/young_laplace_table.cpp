#include "young_laplace_table.hpp"

#include "conventions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace capillary {
namespace yltable {

	namespace {

		constexpr int    row_len = 4 + n_w; // ln_vstar, theta, rho, ln(a_r/Rh), ln(F/(2 pi Rh gamma)) at the tau nodes

		const double table[] = {
#include "young_laplace_table_data.inc"
		};
		static_assert(sizeof(table) / sizeof(double) == size_t(n_lnv) * n_theta * n_rho * row_len,
		              "data/young_laplace_table.csv does not match the axes: regenerate it (tools/generate_young_laplace_table.cpp)");

		const double* row(int i, int j, int k) { return node_row(table, row_len, i, j, k); }

		// 4-point Lagrange weights for x on the nodes xs[0..3].
		void lagrange(const double* xs, double x, double* w)
		{
			for (int a = 0; a < 4; ++a) {
				w[a] = 1;
				for (int b = 0; b < 4; ++b)
					if (b != a) w[a] *= (x - xs[b]) / (xs[a] - xs[b]);
			}
		}
		// First of the 4 nodes around x on nodes [first, first + count).
		int stencil(const double* nodes, int first, int count, double x)
		{
			int i = first;
			while (i + 1 < first + count && nodes[i + 1] <= x) ++i;
			return std::clamp(i - 1, first, first + count - 4);
		}

	} // namespace

	void check_nodes(const double* table, int row_len, const char* file)
	{
		for (int i = 0; i < n_lnv; ++i)
			for (int j = 0; j < n_theta; ++j)
				for (int k = 0; k < n_rho; ++k) {
					const double* r = node_row(table, row_len, i, j, k);
					if (std::abs(r[0] - lnv_node(i)) > 1e-12 || std::abs(r[1] - theta_node(j)) > 1e-12 || std::abs(r[2] - rho_nodes[k]) > 1e-12)
						throw std::logic_error(std::string(file) + ": node mismatch; regenerate the table");
				}
	}

	Stencil locate(const char* table, double R1, double R2, double volume, double theta1, double theta2)
	{
		const auto outside = [table](const std::string& what) {
			throw std::invalid_argument(std::string(table) + ": " + what + "; the exact solver (YoungLaplaceBridge) has no such limit");
		};
		const bool   plane = is_wall(R2);
		const double rs = plane ? R1 : std::min(R1, R2), rl = plane ? R1 : std::max(R1, R2);
		const double rho = plane ? 0 : rs / rl;
		double       r1, r2;
		equivalent_pair(R1, R2, r1, r2);
		Stencil s;
		s.Rh              = harmonic_mean_radius(r1, r2);
		s.small_first     = plane || R1 <= R2;
		const double lnv = std::log(volume / (s.Rh * s.Rh * s.Rh));
		if (!(std::abs(theta1 - theta2) <= 1e-12)) outside("theta1 = " + format_value(theta1) + " and theta2 = " + format_value(theta2) + " rad differ; the table holds equal contact angles");
		if (!(lnv >= lnv_min - 1e-12 && lnv <= lnv_max + 1e-12))
			outside("V* = V/Rh^3 = " + format_value(std::exp(lnv)) + " is outside the table's range [1e-5, 0.1]");
		if (!(theta1 >= 0 && theta1 <= theta_max + 1e-12)) outside("theta = " + format_value(theta1) + " rad is outside the table's range [0, " + format_value(theta_max) + "] rad (50 deg)");
		if (!(plane || rho >= rho_nodes[1] - 1e-12))
			outside("R_small/R_large = " + format_value(rho) + " is outside the table's range [1/4, 1] (or a plane)");

		std::array<double, n_lnv>   lnvs;
		std::array<double, n_theta> thetas;
		for (int i = 0; i < n_lnv; ++i) lnvs[i] = lnv_node(i);
		for (int i = 0; i < n_theta; ++i) thetas[i] = theta_node(i);
		s.i0 = stencil(lnvs.data(), 0, n_lnv, lnv), s.j0 = stencil(thetas.data(), 0, n_theta, theta1);
		lagrange(&lnvs[s.i0], lnv, s.wv);
		lagrange(&thetas[s.j0], theta1, s.wt);
		// A plane uses its own slice; spheres interpolate over rho in [1/4, 1], in sqrt(1 - rho).
		if (!plane) {
			double xs[4];
			s.k0 = stencil(rho_nodes.data(), 1, n_rho - 1, rho), s.nk = 4;
			for (int c = 0; c < 4; ++c) xs[c] = std::sqrt(1 - rho_nodes[s.k0 + c]);
			lagrange(xs, std::sqrt(std::max(0.0, 1 - rho)), s.wr);
		}
		return s;
	}

	Curve curve(double R1, double R2, double volume, double gamma, double theta1, double theta2)
	{
		static const bool nodes_ok = (check_nodes(table, row_len, "data/young_laplace_table.csv"), true); // once
		(void)nodes_ok;
		const Stencil               s = locate("young_laplace_table", R1, R2, volume, theta1, theta2);
		std::array<double, row_len> v {};
		for_each_node(s, [&v](double weight, int i, int j, int k) {
			const double* r = row(i, j, k);
			for (int m = 3; m < row_len; ++m) v[m] += weight * r[m];
		});
		Curve out;
		out.rupture = s.Rh * std::exp(v[3]);
		for (int m = 0; m < n_w; ++m) out.force[m] = 2 * pi * s.Rh * gamma * std::exp(v[4 + m]);
		return out;
	}

	double curve_force(const Curve& c, double a)
	{
		const double* f  = c.force.data();
		const double  t  = (1 - std::sqrt(1 - std::sqrt(std::max(0.0, 1 - a / c.rupture)))) * (n_w - 1);
		const int    i0 = std::clamp(int(t) - 1, 0, n_w - 4);
		const double s  = t - i0;
		const double s1 = s - 1, s2 = s - 2, s3 = s - 3;
		return (-s1 * s2 * s3 * f[i0] + 3 * s * s2 * s3 * f[i0 + 1] - 3 * s * s1 * s3 * f[i0 + 2] + s * s1 * s2 * f[i0 + 3]) / 6;
	}

	void coefficients(const Curve& c, double* k)
	{
		// 1/F at gap fraction u, and as a function of w = sqrt(1 - u).
		const auto g_u = [&](double u) { return 1 / curve_force(c, std::clamp(u, 0.0, 1.0) * c.rupture); };
		const auto g_w = [&](double w) { return g_u(1 - w * w); };
		// Derivative at a node by central differences over 0.15 of the neighbouring segment; one-sided
		// (second order) at u = 0 and w = 0: the Lagrange curve in tau is not differentiable in u at
		// contact (tau ~ sqrt(u)), so a smaller step would pick up that artefact.
		const auto slope = [](const auto& g, const double* x, int n, int j) {
			const double step = 0.15 * std::abs(j + 1 < n ? x[j + 1] - x[j] : x[j] - x[j - 1]);
			if (x[j] == 0) return (-3 * g(0.0) + 4 * g(step) - g(2 * step)) / (2 * step);
			return (g(x[j] + step) - g(x[j] - step)) / (2 * step);
		};
		// One segment from the Hermite data at its ends (x in cells, g and dg/dx), as a cubic in x.
		const auto segment = [](double* out, double xa, double xb, double ya, double yb, double da, double db) {
			const double h = xb - xa;
			const double a[4] = { ya, h * da, 3 * (yb - ya) - h * (2 * da + db), 2 * (ya - yb) + h * (da + db) }; // in s = (x - xa)/h
			const double binomial[4][4] = { { 1 }, { 1, 1 }, { 1, 2, 1 }, { 1, 3, 3, 1 } };
			for (int m = 0; m < 4; ++m) out[m] = 0;
			for (int j = 0; j < 4; ++j)
				for (int m = 0; m <= j; ++m) out[m] += a[j] * std::pow(1 / h, j) * binomial[j][m] * std::pow(-xa, j - m);
		};
		k[0] = u_cells / c.rupture;
		double gu[n_u], du[n_u], gw[n_wn], dw[n_wn];
		for (int j = 0; j < n_u; ++j) gu[j] = g_u(u_nodes[j]), du[j] = slope(g_u, u_nodes.data(), n_u, j) / u_cells;
		for (int j = 0; j < n_wn; ++j) gw[j] = g_w(w_nodes[j]), dw[j] = slope(g_w, w_nodes.data(), n_wn, j) / w_cells;
		for (int i = 0; i < n_u - 1; ++i)
			segment(k + 1 + 4 * i, u_cells * u_nodes[i], u_cells * u_nodes[i + 1], gu[i], gu[i + 1], du[i], du[i + 1]);
		for (int i = 0; i < n_wn - 1; ++i)
			segment(k + 1 + 4 * (n_u - 1 + i), w_cells * w_nodes[i], w_cells * w_nodes[i + 1], gw[i], gw[i + 1], dw[i], dw[i + 1]);
	}

} // namespace yltable
} // namespace capillary
