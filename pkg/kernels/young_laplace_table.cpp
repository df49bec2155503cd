#include "young_laplace_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace capillary {
namespace yltable {

	namespace {

		constexpr double pi      = 3.14159265358979323846;
		constexpr int    row_len = 4 + n_w; // ln_vstar, theta, rho, ln(a_r/Rh), ln(F/(2 pi Rh gamma)) at the tau nodes

		const double table[] = {
#include "young_laplace_table_data.inc"
		};
		static_assert(sizeof(table) / sizeof(double) == size_t(n_lnv) * n_theta * n_rho * row_len,
		              "data/young_laplace_table.csv does not match the axes: regenerate it (tools/generate_young_laplace_table.cpp)");

		const double* row(int i, int j, int k) { return table + ((size_t(i) * n_theta + j) * n_rho + k) * row_len; }

		// The rows carry their node coordinates: check them once against the axes.
		bool checked_nodes()
		{
			for (int i = 0; i < n_lnv; ++i)
				for (int j = 0; j < n_theta; ++j)
					for (int k = 0; k < n_rho; ++k) {
						const double* r = row(i, j, k);
						if (std::abs(r[0] - lnv_node(i)) > 1e-12 || std::abs(r[1] - theta_node(j)) > 1e-12 || std::abs(r[2] - rho_nodes[k]) > 1e-12)
							throw std::logic_error("data/young_laplace_table.csv: node mismatch; regenerate the table");
					}
			return true;
		}

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

		[[noreturn]] void outside(const std::string& what) { throw std::invalid_argument("young_laplace_table: " + what + "; the exact solver (YoungLaplaceBridge) has no such limit"); }

	} // namespace

	Curve curve(double R1, double R2, double volume, double gamma, double theta1, double theta2)
	{
		static const bool nodes_ok = checked_nodes();
		(void)nodes_ok;
		const bool   plane = std::isinf(R2);
		const double rs = plane ? R1 : std::min(R1, R2), rl = plane ? R1 : std::max(R1, R2);
		const double rho = plane ? 0 : rs / rl;
		const double Rh  = plane ? 2 * R1 : 2 * R1 * R2 / (R1 + R2);
		const double lnv = std::log(volume / (Rh * Rh * Rh));
		if (!(std::abs(theta1 - theta2) <= 1e-12)) outside("theta1 = " + std::to_string(theta1) + " and theta2 = " + std::to_string(theta2) + " rad differ; the table holds equal contact angles");
		if (!(lnv >= lnv_min - 1e-12 && lnv <= lnv_max + 1e-12))
			outside("V* = V/Rh^3 = " + std::to_string(std::exp(lnv)) + " is outside the table's range [1e-5, 0.1]");
		if (!(theta1 >= 0 && theta1 <= theta_max + 1e-12)) outside("theta = " + std::to_string(theta1) + " rad is outside the table's range [0, 50 deg]");
		if (!(plane || rho >= rho_nodes[1] - 1e-12))
			outside("R_small/R_large = " + std::to_string(rho) + " is outside the table's range [1/4, 1] (or a plane)");

		double xs[4], wv[4], wt[4], wr[4] = { 1, 0, 0, 0 };
		std::array<double, n_lnv>   lnvs;
		std::array<double, n_theta> thetas;
		for (int i = 0; i < n_lnv; ++i) lnvs[i] = lnv_node(i);
		for (int i = 0; i < n_theta; ++i) thetas[i] = theta_node(i);
		const int i0 = stencil(lnvs.data(), 0, n_lnv, lnv), j0 = stencil(thetas.data(), 0, n_theta, theta1);
		lagrange(&lnvs[i0], lnv, wv);
		lagrange(&thetas[j0], theta1, wt);
		// A plane and equal spheres use their own slices; other pairs interpolate over rho in [1/4, 0.95].
		int k0 = plane ? 0 : n_rho - 1, nk = 1;
		if (!plane && rho < 1) {
			k0 = stencil(rho_nodes.data(), 1, n_rho - 2, rho), nk = 4;
			std::copy(&rho_nodes[k0], &rho_nodes[k0] + 4, xs);
			lagrange(xs, rho, wr);
		}
		std::array<double, row_len> v {};
		for (int a = 0; a < 4; ++a)
			for (int b = 0; b < 4; ++b)
				for (int c = 0; c < nk; ++c) {
					const double  weight = wv[a] * wt[b] * wr[c];
					const double* r      = row(i0 + a, j0 + b, k0 + c);
					for (int m = 3; m < row_len; ++m) v[m] += weight * r[m];
				}
		Curve out;
		out.rupture = Rh * std::exp(v[3]);
		for (int m = 0; m < n_w; ++m) out.force[m] = 2 * pi * Rh * gamma * std::exp(v[4 + m]);
		return out;
	}

	double force(const double* f, double inv_rupture, double a)
	{
		const double t  = (1 - std::sqrt(1 - std::sqrt(std::max(0.0, 1 - a * inv_rupture)))) * (n_w - 1);
		const int    i0 = std::clamp(int(t) - 1, 0, n_w - 4);
		const double s  = t - i0;
		const double s1 = s - 1, s2 = s - 2, s3 = s - 3;
		return (-s1 * s2 * s3 * f[i0] + 3 * s * s2 * s3 * f[i0 + 1] - 3 * s * s1 * s3 * f[i0 + 2] + s * s1 * s2 * f[i0 + 3]) / 6;
	}

} // namespace yltable
} // namespace capillary
