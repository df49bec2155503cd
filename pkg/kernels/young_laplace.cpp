// Young-Laplace pendular bridge solver; see young_laplace.hpp for the equations.
// Internally all lengths are scaled by R1 (sphere 1 has radius 1); P is scaled by 1/R1.
#include "young_laplace.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace capillary {
namespace yl {

	namespace {

		constexpr double pi  = 3.14159265358979323846;
		const double     inf = std::numeric_limits<double>::infinity();

		using State = std::array<double, 4>; // x, y, phi, W = integral of pi y^2 dx

		State deriv(const State& s, double P)
		{
			const double c = std::cos(s[2]);
			return { c, std::sin(s[2]), c / s[1] - P, pi * s[1] * s[1] * c };
		}

		// One Dormand-Prince 5(4) step; returns the 5th-order state and sets err (max-norm estimate).
		State dopri_step(const State& s, double P, double h, double& err)
		{
			static const double a21 = 1. / 5, a31 = 3. / 40, a32 = 9. / 40, a41 = 44. / 45, a42 = -56. / 15, a43 = 32. / 9,
			                    a51 = 19372. / 6561, a52 = -25360. / 2187, a53 = 64448. / 6561, a54 = -212. / 729,
			                    a61 = 9017. / 3168, a62 = -355. / 33, a63 = 46732. / 5247, a64 = 49. / 176, a65 = -5103. / 18656,
			                    b1 = 35. / 384, b3 = 500. / 1113, b4 = 125. / 192, b5 = -2187. / 6784, b6 = 11. / 84,
			                    e1 = 71. / 57600, e3 = -71. / 16695, e4 = 71. / 1920, e5 = -17253. / 339200, e6 = 22. / 525, e7 = -1. / 40;
			auto add = [&](std::initializer_list<std::pair<double, const State*>> terms) {
				State r = s;
				for (const auto& t : terms)
					for (int i = 0; i < 4; ++i) r[i] += h * t.first * (*t.second)[i];
				return r;
			};
			const State k1 = deriv(s, P);
			const State k2 = deriv(add({ { a21, &k1 } }), P);
			const State k3 = deriv(add({ { a31, &k1 }, { a32, &k2 } }), P);
			const State k4 = deriv(add({ { a41, &k1 }, { a42, &k2 }, { a43, &k3 } }), P);
			const State k5 = deriv(add({ { a51, &k1 }, { a52, &k2 }, { a53, &k3 }, { a54, &k4 } }), P);
			const State k6 = deriv(add({ { a61, &k1 }, { a62, &k2 }, { a63, &k3 }, { a64, &k4 }, { a65, &k5 } }), P);
			const State y5 = add({ { b1, &k1 }, { b3, &k3 }, { b4, &k4 }, { b5, &k5 }, { b6, &k6 } });
			const State k7 = deriv(y5, P);
			err            = 0;
			for (int i = 0; i < 4; ++i) {
				const double e = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
				err            = std::max(err, std::abs(e) / (1 + std::abs(y5[i])));
			}
			return y5;
		}

		struct Shot {
			bool   ok = false;
			double angle_residual = 0, volume = 0, beta2 = 0, y_end = 0, phi_end = 0;
			double neck_y = inf, neck_phi = 0;
		};

		// Integrate the meniscus from the contact line on sphere 1 (filling angle beta1) to sphere 2
		// (radius R2, or a plane if R2 = inf), for pressure P and gap a (all scaled by R1).
		Shot shoot(double beta1, double P, double a, double R2, double t1, double t2)
		{
			const double tol = 1e-12;
			const bool   plane = std::isinf(R2);
			const double c1 = -(a / 2 + 1), c2 = plane ? 0 : a / 2 + R2;
			auto         g = [&](const State& s) { return plane ? a / 2 - s[0] : (s[0] - c2) * (s[0] - c2) + s[1] * s[1] - R2 * R2; };
			Shot         out;
			State        s = { c1 + std::cos(beta1), std::sin(beta1), beta1 + t1 - pi / 2, 0 };
			if (!(s[1] > 0) || g(s) <= 0) return out;
			// The neck: y is smallest where phi crosses zero from below.
			out.neck_y   = s[1];
			out.neck_phi = s[2];
			double h = 0.01, length = 0;
			for (int step = 0; step < 200000 && length < 100; ++step) {
				double      err;
				const State n = dopri_step(s, P, h, err);
				if (!(err <= tol) || !(n[1] > 0)) {
					if (!(n[1] > 0) && err <= tol && h < 1e-14) return out;
					h *= std::max(0.1, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
					if (h < 1e-14) return out;
					continue;
				}
				auto refine = [&](auto fn) { // h* in (0, h] with fn(step(s, h*)) = 0, by the Illinois method
					double lo = 0, hi = h, flo = fn(s), fhi = fn(n), e;
					int    side = 0;
					State  m     = n;
					for (int it = 0; it < 100 && hi - lo > 1e-15 * (1 + hi); ++it) {
						const double mid = (lo * fhi - hi * flo) / (fhi - flo);
						m                = dopri_step(s, P, mid, e);
						const double fm  = fn(m);
						if (fm == 0) return m;
						if ((fm > 0) == (flo > 0)) {
							lo = mid, flo = fm;
							if (side == -1) fhi /= 2;
							side = -1;
						} else {
							hi = mid, fhi = fm;
							if (side == 1) flo /= 2;
							side = 1;
						}
					}
					return m;
				};
				if (s[2] < 0 && n[2] >= 0) { // interior neck
					const State m = refine([](const State& q) { return q[2]; });
					out.neck_y = m[1], out.neck_phi = m[2];
				}
				if (g(n) <= 0) { // reached sphere 2 (or the plane)
					const State e = refine(g);
					out.y_end     = e[1];
					out.phi_end   = e[2];
					double cap2   = 0;
					if (plane) {
						out.beta2          = 0;
						out.angle_residual = e[2] - (pi / 2 - t2);
					} else {
						out.beta2             = std::atan2(e[1], c2 - e[0]);
						const double h2       = 2 * R2 * std::pow(std::sin(out.beta2 / 2), 2);
						cap2                  = pi * h2 * h2 * (3 * R2 - h2) / 3;
						out.angle_residual    = e[2] - (pi / 2 - out.beta2 - t2);
					}
					const double h1 = 2 * std::pow(std::sin(beta1 / 2), 2);
					out.volume      = e[3] - pi * h1 * h1 * (3 - h1) / 3 - cap2;
					if (e[1] < out.neck_y) out.neck_y = e[1], out.neck_phi = e[2];
					out.ok = std::isfinite(out.volume) && std::abs(e[2]) < pi;
					return out;
				}
				if (std::abs(n[2]) > pi) return out; // the profile turned back: not a pendular bridge
				length += h;
				s = n;
				h *= std::min(5.0, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
			}
			return out;
		}

		// Damped Newton on two unknowns with a finite-difference Jacobian. `res` returns false if the
		// residual cannot be evaluated (no bridge for these values).
		template <class F> bool newton2(std::array<double, 2>& u, const std::array<double, 2>& scale, F res)
		{
			std::array<double, 2> r;
			if (!res(u, r)) return false;
			for (int it = 0; it < 60; ++it) {
				const double norm = std::hypot(r[0], r[1]);
				if (norm < 1e-12) return true;
				double J[2][2];
				for (int j = 0; j < 2; ++j) {
					std::array<double, 2> up = u, rp;
					const double          du = 1e-7 * scale[j];
					up[j] += du;
					if (!res(up, rp)) {
						up[j] -= 2 * du;
						if (!res(up, rp)) return false;
						J[0][j] = (r[0] - rp[0]) / du, J[1][j] = (r[1] - rp[1]) / du;
					} else J[0][j] = (rp[0] - r[0]) / du, J[1][j] = (rp[1] - r[1]) / du;
				}
				const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
				if (!(std::abs(det) > 0)) return false;
				const double d0 = -(J[1][1] * r[0] - J[0][1] * r[1]) / det, d1 = -(-J[1][0] * r[0] + J[0][0] * r[1]) / det;
				bool         improved = false;
				for (double lambda = 1; lambda > 1e-6; lambda /= 2) {
					std::array<double, 2> un = { u[0] + lambda * d0, u[1] + lambda * d1 }, rn;
					if (res(un, rn) && std::hypot(rn[0], rn[1]) < norm) {
						u = un, r = rn, improved = true;
						break;
					}
				}
				if (!improved) return norm < 1e-9;
			}
			return std::hypot(r[0], r[1]) < 1e-9;
		}

	} // namespace

	Bridge::Bridge(double R1, double R2, double volume, double theta1, double theta2)
	{
		if (theta2 < 0) theta2 = theta1;
		if (!(R1 > 0 && std::isfinite(R1))) throw std::invalid_argument("R1 = " + std::to_string(R1) + " m is outside the allowed range (0, inf)");
		if (!(R2 > 0)) throw std::invalid_argument("R2 = " + std::to_string(R2) + " m is outside the allowed range (0, inf] (inf: plane)");
		if (!(volume > 0 && std::isfinite(volume))) throw std::invalid_argument("volume = " + std::to_string(volume) + " m^3 is outside the allowed range (0, inf)");
		for (double t : { theta1, theta2 })
			if (!(t >= 0 && t < pi / 2)) throw std::invalid_argument("theta = " + std::to_string(t) + " rad is outside the allowed range [0, pi/2)");
		R1_ = R1, R2_ = R2 / R1, V_ = volume / (R1 * R1 * R1), t1_ = theta1, t2_ = theta2;

		// Contact (a = 0): unknowns beta1, P. Guess from the thin-film volume pi rho^4 / (2 Rh).
		const double Rh   = std::isinf(R2_) ? 2 : 2 * R2_ / (1 + R2_);
		const double rho  = std::pow(2 * V_ * Rh / pi, 0.25);
		const double b1   = std::asin(std::min(0.9, rho));
		const double gap  = rho * rho / Rh;
		const double rm   = gap / (std::cos(b1 + t1_) + std::cos(std::asin(std::min(0.9, rho / (std::isinf(R2_) ? 1e300 : R2_))) + t2_));
		const double rneck = std::max(0.5 * rho, rho - rm * (1 - std::sin(b1 + t1_)));
		std::array<double, 2> u = { b1, 1 / rneck - 1 / rm };
		auto at_contact = [&](const std::array<double, 2>& v, std::array<double, 2>& r) {
			if (!(v[0] > 0 && v[0] < pi / 2)) return false;
			const Shot s = shoot(v[0], v[1], 0, R2_, t1_, t2_);
			if (!s.ok) return false;
			r = { s.angle_residual, s.volume / V_ - 1 };
			return true;
		};
		if (!newton2(u, { b1, std::max(1.0, std::abs(u[1])) }, at_contact))
			throw std::runtime_error("Young-Laplace: no pendular bridge at contact for V* = V/R1^3 = " + std::to_string(V_) + ", theta = "
			                         + std::to_string(theta1) + " rad");
		branch_.push_back({ u[0], u[1], 0 });

		// Continuation in beta1 towards smaller filling angles: the gap grows to a maximum (the fold,
		// rupture) and decreases on the unstable branch beyond it.
		double dbeta = 0.02 * branch_[0].beta1;
		while (true) {
			const Point& last = branch_.back();
			Point        guess = last;
			if (branch_.size() > 1) {
				const Point& prev = branch_[branch_.size() - 2];
				const double f    = dbeta / (prev.beta1 - last.beta1);
				guess.P += f * (last.P - prev.P), guess.a += f * (last.a - prev.a);
			}
			guess.beta1 = last.beta1 - dbeta;
			Point next;
			try {
				next = solve_at_beta(guess.beta1, guess);
			} catch (const std::runtime_error&) {
				dbeta /= 2;
				if (dbeta < 1e-9 * branch_[0].beta1) throw;
				continue;
			}
			if (next.a < last.a) { // passed the fold: maximise a(beta1) between the last two points and next
				double lo = next.beta1, hi = branch_.size() > 1 ? branch_[branch_.size() - 2].beta1 : last.beta1;
				const double gr = (std::sqrt(5.0) - 1) / 2;
				Point        m1 = solve_at_beta(hi - gr * (hi - lo), last), m2 = solve_at_beta(lo + gr * (hi - lo), last);
				while (hi - lo > 1e-9 * branch_[0].beta1) {
					if (m1.a > m2.a) {
						lo = m2.beta1, m2 = m1;
						m1 = solve_at_beta(hi - gr * (hi - lo), m2);
					} else {
						hi = m1.beta1, m1 = m2;
						m2 = solve_at_beta(lo + gr * (hi - lo), m1);
					}
				}
				const Point top = m1.a > m2.a ? m1 : m2;
				while (branch_.size() > 1 && branch_.back().beta1 <= top.beta1) branch_.pop_back();
				branch_.push_back(top);
				break;
			}
			branch_.push_back(next);
			dbeta = std::min(dbeta * 1.5, 0.05 * branch_[0].beta1);
		}
		rupture_ = branch_.back().a * R1_;
	}

	Bridge::Point Bridge::solve_at_beta(double beta1, const Point& guess) const
	{
		std::array<double, 2> u = { guess.P, guess.a };
		auto res = [&](const std::array<double, 2>& v, std::array<double, 2>& r) {
			if (!(v[1] > -0.5)) return false;
			const Shot s = shoot(beta1, v[0], v[1], R2_, t1_, t2_);
			if (!s.ok) return false;
			r = { s.angle_residual, s.volume / V_ - 1 };
			return true;
		};
		if (!newton2(u, { std::max(1.0, std::abs(guess.P)), std::max(1e-3, std::abs(guess.a)) }, res))
			throw std::runtime_error("Young-Laplace: no converged bridge at filling angle " + std::to_string(beta1));
		return { beta1, u[0], u[1] };
	}

	Solution Bridge::solve(double gap, double gamma) const
	{
		const double a = gap / R1_;
		if (!(a >= 0 && gap <= rupture_))
			throw std::invalid_argument("gap = " + std::to_string(gap) + " m is outside the allowed range [0, rupture gap = " + std::to_string(rupture_)
			                            + " m]");
		if (!(gamma > 0)) throw std::invalid_argument("gamma = " + std::to_string(gamma) + " N/m is outside the allowed range (0, inf)");
		// Bracket on the stable branch, then solve a(beta1) = a by the Illinois method in beta1; each
		// a(beta1) is a well-conditioned solve even at the fold.
		size_t k = 0;
		while (k + 1 < branch_.size() && branch_[k + 1].a < a) ++k;
		Point p;
		if (a <= branch_[k].a) p = branch_[k];
		else if (k + 1 == branch_.size() || a >= branch_[k + 1].a) p = branch_[std::min(k + 1, branch_.size() - 1)];
		else {
			Point lo = branch_[k], hi = branch_[k + 1];
			int   side = 0;
			double flo = lo.a - a, fhi = hi.a - a;
			p = lo;
			for (int it = 0; it < 200; ++it) {
				const double b = (lo.beta1 * fhi - hi.beta1 * flo) / (fhi - flo);
				Point        g = lo;
				const double f = (b - lo.beta1) / (hi.beta1 - lo.beta1);
				g.P += f * (hi.P - lo.P), g.a += f * (hi.a - lo.a);
				p                = solve_at_beta(b, g);
				const double fp  = p.a - a;
				if (std::abs(fp) < 1e-14 * (1 + a) || std::abs(hi.beta1 - lo.beta1) < 1e-15) break;
				if ((fp > 0) == (flo > 0)) {
					lo = p, flo = fp;
					if (side == -1) fhi /= 2;
					side = -1;
				} else {
					hi = p, fhi = fp;
					if (side == 1) flo /= 2;
					side = 1;
				}
			}
		}
		const Shot s = shoot(p.beta1, p.P, p.a, R2_, t1_, t2_);
		Solution   out;
		const double y1  = std::sin(p.beta1), phi1 = p.beta1 + t1_ - pi / 2;
		out.gap           = p.a * R1_;
		out.beta1         = p.beta1;
		out.beta2         = s.beta2;
		out.contact_radius1 = y1 * R1_;
		out.contact_radius2 = s.y_end * R1_;
		out.neck_radius   = s.neck_y * R1_;
		out.pressure      = gamma * p.P / R1_;
		out.force_neck    = pi * gamma * R1_ * (2 * s.neck_y * std::cos(s.neck_phi) - p.P * s.neck_y * s.neck_y);
		out.force_contact = pi * gamma * R1_ * (2 * y1 * std::cos(phi1) - p.P * y1 * y1);
		out.volume        = s.volume * R1_ * R1_ * R1_;
		return out;
	}

} // namespace yl
} // namespace capillary
