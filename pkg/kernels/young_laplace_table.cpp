#include "young_laplace_table.hpp"

#include "conventions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

// The tables: data/young_laplace_table_rows.csv (compiled in as text) and data/young_laplace_table.bin
// (float32, embedded by young_laplace_table_data.S).
extern "C" const float capillary_yltable_values[];
extern "C" const char  capillary_yltable_values_end[];

namespace capillary {
namespace yltable {

	namespace {

		constexpr int row_meta_len = 5; // ln_vstar, rho, theta_s_rad, ridge_rad, center_rad
		const double  rows_meta[] = {
#include "young_laplace_table_rows.inc"
		};
		static_assert(sizeof(rows_meta) / sizeof(double) == size_t(n_rows) * row_meta_len,
		              "data/young_laplace_table_rows.csv does not match the axes: regenerate it (tools/generate_young_laplace_table.cpp)");
		constexpr size_t row_floats = size_t(n_tl) * n_values;

		// Once: the rows' nodes against the axes, and the size of the values.
		void check_tables()
		{
			const char* file = "data/young_laplace_table_rows.csv";
			for (int i = 0; i < n_lnv; ++i)
				for (int k = 0; k < n_rho; ++k)
					for (int j = 0; j < n_ts; ++j) {
						const double* r = rows_meta + size_t(row_index(i, k, j)) * row_meta_len;
						if (std::abs(r[0] - lnv_node(i)) > 1e-12 || std::abs(r[1] - rho_nodes[k]) > 1e-12 || std::abs(r[2] - theta_s_node(j)) > 1e-12
						    || std::abs(r[4] - center_of(r[3])) > 1e-12)
							throw std::logic_error(std::string(file) + ": node mismatch; regenerate the table");
					}
			const size_t bytes = size_t(capillary_yltable_values_end - reinterpret_cast<const char*>(capillary_yltable_values));
			if (bytes != n_rows * row_floats * sizeof(float))
				throw std::logic_error("data/young_laplace_table.bin holds " + std::to_string(bytes) + " bytes, not "
				                       + std::to_string(n_rows * row_floats * sizeof(float)) + "; regenerate the table");
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
		// Barycentric weights of the n Chebyshev-Lobatto points on [0, 1] at x (Berrut & Trefethen 2004).
		template <int n> std::array<double, n> lobatto_weights(double x)
		{
			std::array<double, n> w {};
			double                sum = 0;
			for (int m = 0; m < n; ++m) {
				const double d = x - lobatto(m, n);
				if (d == 0) {
					w.fill(0), w[m] = 1;
					return w;
				}
				w[m] = ((m % 2) ? -1.0 : 1.0) * ((m == 0 || m == n - 1) ? 0.5 : 1.0) / d;
				sum += w[m];
			}
			for (double& v : w) v /= sum;
			return w;
		}

	} // namespace

	namespace {
		// The values [q0, q1) of one bridge's node vector, interpolated; Rh [m] and which solid is "small".
		struct Interpolated {
			std::array<double, n_values> v {};
			double                       Rh = 0;
			bool                         small_first = true;
			// The share of solid 1 from v[1], the small solid's (the interpolation stays well inside (0, 1)).
			double transfer1() const
			{
				const double small = std::fmin(1.0, std::fmax(0.0, v[1]));
				return small_first ? small : 1 - small;
			}
		};
		// The transfer column alone, row after row (n_tl floats a row): read by every film bridge that
		// breaks, so a call touches 240 short rows instead of 240 x 25 strided values.
		const float* transfer_column()
		{
			static const std::vector<float> column = [] {
				std::vector<float> c(size_t(n_rows) * n_tl);
				for (size_t r = 0; r < size_t(n_rows); ++r)
					for (int m = 0; m < n_tl; ++m) c[r * n_tl + m] = capillary_yltable_values[r * row_floats + size_t(m) * n_values + 1];
				return c;
			}();
			return column.data();
		}

		// column: null for the whole table; else one value per node, row after row (interpolated into v[q0]).
		Interpolated interpolate(double R1, double R2, double volume, double theta1, double theta2, const char* who, int q0, int q1,
		                         const float* column = nullptr)
		{
			static const bool checked = (check_tables(), true);
			(void)checked;
			const auto outside = [who](const std::string& what) {
				throw std::invalid_argument(std::string(who) + ": " + what + "; the exact solver (YoungLaplaceBridge) has no such limit");
			};
			const bool   plane = is_wall(R2);
			const double rs = plane ? R1 : std::min(R1, R2), rl = plane ? R1 : std::max(R1, R2);
			const double rho = plane ? 0 : rs / rl;
			double       r1, r2;
			equivalent_pair(R1, R2, r1, r2);
			Interpolated out;
			out.Rh = harmonic_mean_radius(r1, r2);
			// Equal spheres: the solid of the smaller angle counts as "small", so that both orders read one point.
			out.small_first  = plane || R1 < R2 || (R1 == R2 && theta1 <= theta2);
			const double lnv = std::log(volume / (out.Rh * out.Rh * out.Rh));
			if (!(lnv >= lnv_min - 1e-12 && lnv <= lnv_max + 1e-12))
				outside("V* = V/Rh^3 = " + format_value(std::exp(lnv)) + " is outside the table's range [1e-5, 0.5]");
			for (const auto& [name, theta] : { std::pair<const char*, double> { "theta1", theta1 }, { "theta2", theta2 } })
				if (!(theta >= 0 && theta <= theta_max + 1e-12))
					outside(std::string(name) + " = " + format_value(theta) + " rad is outside the table's range [0, " + format_value(theta_max) + "] rad (70 deg)");
			if (!(plane || rho >= rho_nodes[1] - 1e-12)) outside("R_small/R_large = " + format_value(rho) + " is outside the table's range [1/4, 1] (or a plane)");
			const double ts = std::min(out.small_first ? theta1 : theta2, theta_max), tl = std::min(out.small_first ? theta2 : theta1, theta_max);

			// Stencils: cubic in ln V*, rho (a plane has its own slice) and theta_s, on the four nearest nodes.
			// (A fit in theta_s over all 15 Chebyshev nodes spread the steep rows near 70 deg, where the force
			// near contact approaches 0, over every theta_s.)
			std::array<double, n_lnv> lnvs;
			for (int i = 0; i < n_lnv; ++i) lnvs[i] = lnv_node(i);
			const int i0 = stencil(lnvs.data(), 0, n_lnv, lnv);
			double    wv[4], wr[4] = { 1, 0, 0, 0 };
			lagrange(&lnvs[i0], lnv, wv);
			int k0 = 0, nk = 1;
			if (!plane) {
				k0 = stencil(rho_nodes.data(), 1, n_rho - 1, rho), nk = 4;
				lagrange(&rho_nodes[k0], rho, wr);
			}
			std::array<double, n_ts> thetas;
			for (int j = 0; j < n_ts; ++j) thetas[j] = theta_s_node(j);
			const int j0 = stencil(thetas.data(), 0, n_ts, ts);
			double    wt[4];
			lagrange(&thetas[j0], ts, wt);
			const auto row_weight = [&](int a, int c, int b) { return wv[a] * wr[c] * wt[b]; };

			// The centre of s at this bridge, then its place among the theta_l nodes.
			double center = 0;
			for (int a = 0; a < 4; ++a)
				for (int c = 0; c < nk; ++c)
					for (int b = 0; b < 4; ++b) center += row_weight(a, c, b) * rows_meta[size_t(row_index(i0 + a, k0 + c, j0 + b)) * row_meta_len + 4];
			const auto wl = lobatto_weights<n_tl>(x_of(tl, center));

			for (int a = 0; a < 4; ++a)
				for (int c = 0; c < nk; ++c)
					for (int b = 0; b < 4; ++b) {
						const size_t                 r = size_t(row_index(i0 + a, k0 + c, j0 + b));
						std::array<double, n_values> along {}; // the row at this theta_l
						if (column)
							for (int m = 0; m < n_tl; ++m) along[q0] += wl[m] * column[r * n_tl + m];
						else
							for (int m = 0; m < n_tl; ++m)
								for (int q = q0; q < q1; ++q) along[q] += wl[m] * capillary_yltable_values[r * row_floats + size_t(m) * n_values + q];
						const double w = row_weight(a, c, b);
						for (int q = q0; q < q1; ++q) out.v[q] += w * along[q];
					}
			return out;
		}
	} // namespace

	Curve curve(double R1, double R2, double volume, double gamma, double theta1, double theta2, const char* who)
	{
		const Interpolated in = interpolate(R1, R2, volume, theta1, theta2, who, 0, n_values);
		Curve              out;
		out.rupture        = in.Rh * std::exp(in.v[0]);
		out.transfer1      = in.transfer1();
		out.scale          = 2 * pi * in.Rh * gamma;
		for (int m = 0; m < n_w; ++m) out.g[m] = in.v[2 + m];
		return out;
	}

	double transfer1(double R1, double R2, double volume, double theta1, double theta2, const char* who)
	{
		return interpolate(R1, R2, volume, theta1, theta2, who, 1, 2, transfer_column()).transfer1();
	}

	double curve_force(const Curve& c, double a)
	{
		const double t  = (1 - std::sqrt(1 - std::sqrt(std::max(0.0, 1 - a / c.rupture)))) * (n_w - 1);
		const int    i0 = std::clamp(int(t) - 2, 0, n_w - 6);
		double       g  = 0;
		for (int p = 0; p < 6; ++p) {
			double w = 1;
			for (int q = 0; q < 6; ++q)
				if (q != p) w *= (t - (i0 + q)) / double(p - q);
			g += w * c.g[i0 + p];
		}
		return c.scale * force_delta * std::sinh(g);
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
