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

		// Half of a meniscus: from its neck (x0, y0), where the profile is parallel to the axis, towards
		// +x until the profile direction is the one that the contact angle theta requires on the
		// sphere of centre c and radius R (R = inf: the plane x = c), seen from that point. The
		// residual is the signed distance of that point from the solid: zero for a bridge. (Stopping
		// where the profile meets the solid instead is singular for theta = 0, where the meniscus
		// touches the sphere tangentially.) The left half is computed in the mirror image x -> -x.
		struct Half {
			bool   ok = false;
			double distance = 0; // signed distance of the contact point from the solid surface
			double W = 0;        // integral of pi y^2 dx from the neck to the contact line
			double cap = 0;      // volume of the sphere cap beyond the contact line
			double beta = 0;     // filling angle on that sphere
			double y_end = 0;
		};

		Half half(double x0, double y0, double P, double c, double R, double theta)
		{
			const double tol   = 1e-12;
			const bool   plane = std::isinf(R);
			auto         beta  = [&](const State& q) { return plane ? 0.0 : std::atan2(q[1], c - q[0]); };
			auto         angle = [&](const State& q) { return q[2] - (pi / 2 - beta(q) - theta); };
			Half         out;
			State        s = { x0, y0, 0, 0 };
			if (!(y0 > 0) || angle(s) >= 0) return out;
			double h = 0.01 * y0, length = 0;
			for (int step = 0; step < 100000 && length < 100; ++step) {
				double      err;
				const State n = dopri_step(s, P, h, err);
				if (!(err <= tol) || !(n[1] > 0)) {
					h *= std::max(0.1, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
					if (h < 1e-15) return out;
					continue;
				}
				if (angle(n) >= 0) { // find the step h* in (0, h] that lands on the contact condition (Illinois method)
					double lo = 0, hi = h, flo = angle(s), fhi = angle(n), e;
					int    side = 0;
					State  m     = n;
					for (int it = 0; it < 100 && hi - lo > 1e-16 * (1 + hi); ++it) {
						const double mid = (lo * fhi - hi * flo) / (fhi - flo);
						m                = dopri_step(s, P, mid, e);
						const double fm  = angle(m);
						if (fm == 0) break;
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
					out.y_end    = m[1];
					out.W        = m[3];
					out.beta     = beta(m);
					out.distance = plane ? c - m[0] : std::hypot(m[0] - c, m[1]) - R;
					if (!plane) {
						const double hc = 2 * R * std::pow(std::sin(out.beta / 2), 2); // R (1 - cos beta)
						out.cap         = pi * hc * hc * (3 * R - hc) / 3;
					}
					out.ok = std::isfinite(out.W) && out.beta >= 0;
					return out;
				}
				if (std::abs(n[2]) > pi) return out; // the profile turned back: not a pendular bridge
				length += h;
				s = n;
				h *= std::min(5.0, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
			}
			return out;
		}

		struct Shot {
			bool   ok = false;
			double dist1 = 0, dist2 = 0, volume = 0, beta1 = 0, beta2 = 0, y1 = 0, y2 = 0;
		};

		// The whole meniscus for neck position xn, neck radius yn, pressure P and gap a (sphere 1 of
		// radius 1 left of the gap, sphere 2 of radius R2 right of it; scaled by R1).
		Shot shoot(double xn, double yn, double P, double a, double R2, double t1, double t2)
		{
			Shot       out;
			const Half right = half(xn, yn, P, std::isinf(R2) ? a / 2 : a / 2 + R2, R2, t2);
			if (!right.ok) return out;
			const Half left = half(-xn, yn, P, a / 2 + 1, 1, t1);
			if (!left.ok) return out;
			out.ok         = true;
			out.dist1      = left.distance;
			out.dist2      = right.distance;
			out.volume     = left.W + right.W - left.cap - right.cap;
			out.beta1      = left.beta;
			out.beta2      = right.beta;
			out.y1         = left.y_end;
			out.y2         = right.y_end;
			return out;
		}

		// Damped Newton with a finite-difference Jacobian. `res` returns false where the residual
		// cannot be evaluated (no bridge for these values); the line search stays out of there.
		template <size_t N, class F> bool newton(std::array<double, N>& u, const std::array<double, N>& scale, F res)
		{
			std::array<double, N> r;
			auto                  norm = [](const std::array<double, N>& v) {
                double s = 0;
                for (double x : v) s += x * x;
                return std::sqrt(s);
			};
			if (!res(u, r)) return false;
			for (int it = 0; it < 60; ++it) {
				if (norm(r) < 1e-12) return true;
				double J[N][N + 1];
				for (size_t j = 0; j < N; ++j) {
					std::array<double, N> up = u, rp;
					double                du = 1e-7 * scale[j];
					up[j] += du;
					if (!res(up, rp)) {
						du = -du, up[j] = u[j] + du;
						if (!res(up, rp)) return false;
					}
					for (size_t i = 0; i < N; ++i) J[i][j] = (rp[i] - r[i]) / du;
				}
				for (size_t i = 0; i < N; ++i) J[i][N] = -r[i];
				for (size_t c = 0; c < N; ++c) { // Gaussian elimination with partial pivoting
					size_t p = c;
					for (size_t i = c + 1; i < N; ++i)
						if (std::abs(J[i][c]) > std::abs(J[p][c])) p = i;
					if (!(std::abs(J[p][c]) > 0)) return false;
					for (size_t k = 0; k <= N; ++k) std::swap(J[c][k], J[p][k]);
					for (size_t i = 0; i < N; ++i)
						if (i != c) {
							const double f = J[i][c] / J[c][c];
							for (size_t k = c; k <= N; ++k) J[i][k] -= f * J[c][k];
						}
				}
				bool improved = false;
				for (double lambda = 1; lambda > 1e-6; lambda /= 2) {
					std::array<double, N> un = u, rn;
					for (size_t i = 0; i < N; ++i) un[i] += lambda * J[i][N] / J[i][i];
					if (res(un, rn) && norm(rn) < norm(r)) {
						u = un, r = rn, improved = true;
						break;
					}
				}
				if (!improved) return norm(r) < 1e-9;
			}
			return norm(r) < 1e-9;
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

		// Contact (a = 0): unknowns xn, yn, P. Guess: thin-film volume pi rho^4 / (2 Rh) for the
		// contact-line radius rho, and a toroidal meniscus for the neck and the pressure.
		const double Rh    = std::isinf(R2_) ? 2 : 2 * R2_ / (1 + R2_);
		const double rho   = std::min(0.9, std::pow(2 * V_ * Rh / pi, 0.25));
		const double b1    = std::asin(rho), b2 = std::isinf(R2_) ? 0 : std::asin(std::min(0.9, rho / R2_));
		const double rm    = rho * rho / Rh / (std::cos(b1 + t1_) + std::cos(b2 + t2_));
		L_                 = rho * rho / Rh; // gap scale of the bridge: residual distances are measured in it
		const double yn0   = std::max(0.5 * rho, rho - rm * (1 - std::sin(b1 + t1_)));
		std::array<double, 3> u = { 0, yn0, 1 / yn0 - 1 / rm };
		auto at_contact = [&](const std::array<double, 3>& v, std::array<double, 3>& r) {
			const Shot s = shoot(v[0], v[1], v[2], 0, R2_, t1_, t2_);
			if (!s.ok) return false;
			r = { s.dist1 / L_, s.dist2 / L_, s.volume / V_ - 1 };
			return true;
		};
		if (!newton(u, { yn0, yn0, std::max(1.0, std::abs(u[2])) }, at_contact))
			throw std::runtime_error("Young-Laplace: no pendular bridge at contact for V* = V/R1^3 = " + std::to_string(V_) + ", theta = "
			                         + std::to_string(theta1) + " rad");
		branch_.push_back({ u[1], u[0], u[2], 0 });

		// Continuation towards smaller necks: the gap grows to a maximum (the fold: rupture) and
		// decreases on the unstable branch beyond it.
		const double y0    = branch_[0].yn;
		double       dy    = 0.02 * y0;
		while (true) {
			const Point& last  = branch_.back();
			Point        guess = last;
			if (branch_.size() > 1) {
				const Point& prev = branch_[branch_.size() - 2];
				const double f    = dy / (prev.yn - last.yn);
				guess.xn += f * (last.xn - prev.xn), guess.P += f * (last.P - prev.P), guess.a += f * (last.a - prev.a);
			}
			Point next;
			try {
				next = solve_at_neck(last.yn - dy, guess);
			} catch (const std::runtime_error&) {
				dy /= 2;
				if (dy < 1e-9 * y0) throw;
				continue;
			}
			if (next.a < last.a) { // passed the fold: maximise a(yn) between the point before last and next
				double       lo = next.yn, hi = branch_.size() > 1 ? branch_[branch_.size() - 2].yn : last.yn;
				const double gr = (std::sqrt(5.0) - 1) / 2;
				Point        m1 = solve_at_neck(hi - gr * (hi - lo), last), m2 = solve_at_neck(lo + gr * (hi - lo), last);
				while (hi - lo > 1e-10 * y0) {
					if (m1.a > m2.a) {
						lo = m2.yn, m2 = m1;
						m1 = solve_at_neck(hi - gr * (hi - lo), m2);
					} else {
						hi = m1.yn, m1 = m2;
						m2 = solve_at_neck(lo + gr * (hi - lo), m1);
					}
				}
				const Point top = m1.a > m2.a ? m1 : m2;
				while (branch_.size() > 1 && branch_.back().yn <= top.yn) branch_.pop_back();
				branch_.push_back(top);
				break;
			}
			branch_.push_back(next);
			dy = std::min(dy * 1.5, 0.05 * y0);
			if (next.yn - dy <= 0.02 * y0) dy = 0.5 * (next.yn - 0.02 * y0);
		}
		rupture_ = branch_.back().a * R1_;
	}

	Bridge::Point Bridge::solve_at_neck(double yn, const Point& guess) const
	{
		std::array<double, 3> u = { guess.xn, guess.P, guess.a };
		auto res = [&](const std::array<double, 3>& v, std::array<double, 3>& r) {
			if (!(v[2] > -0.5)) return false;
			const Shot s = shoot(v[0], yn, v[1], v[2], R2_, t1_, t2_);
			if (!s.ok) return false;
			r = { s.dist1 / L_, s.dist2 / L_, s.volume / V_ - 1 };
			return true;
		};
		if (!newton(u, { yn, std::max(1.0, std::abs(guess.P)), std::max(yn * yn, std::abs(guess.a)) }, res))
			throw std::runtime_error("Young-Laplace: no converged bridge at neck radius " + std::to_string(yn));
		return { yn, u[0], u[1], u[2] };
	}

	Solution Bridge::solve(double gap, double gamma) const
	{
		const double a = gap / R1_;
		if (!(a >= 0 && gap <= rupture_))
			throw std::invalid_argument("gap = " + std::to_string(gap) + " m is outside the allowed range [0, rupture gap = " + std::to_string(rupture_)
			                            + " m]");
		if (!(gamma > 0)) throw std::invalid_argument("gamma = " + std::to_string(gamma) + " N/m is outside the allowed range (0, inf)");
		// Bracket on the stable branch, then solve a(yn) = a by the Illinois method in the neck
		// radius; each a(yn) is a well-conditioned solve, also at the fold.
		size_t k = 0;
		while (k + 1 < branch_.size() && branch_[k + 1].a < a) ++k;
		Point p;
		if (a <= branch_[k].a) p = branch_[k];
		else if (k + 1 == branch_.size() || a >= branch_[k + 1].a) p = branch_[std::min(k + 1, branch_.size() - 1)];
		else {
			Point  lo = branch_[k], hi = branch_[k + 1];
			int    side = 0;
			double flo = lo.a - a, fhi = hi.a - a;
			for (int it = 0; it < 200; ++it) {
				const double y = (lo.yn * fhi - hi.yn * flo) / (fhi - flo);
				Point        g = lo;
				const double f = (y - lo.yn) / (hi.yn - lo.yn);
				g.xn += f * (hi.xn - lo.xn), g.P += f * (hi.P - lo.P), g.a += f * (hi.a - lo.a);
				p               = solve_at_neck(y, g);
				const double fp = p.a - a;
				if (std::abs(fp) < 1e-14 * (1 + a) || std::abs(hi.yn - lo.yn) < 1e-15) break;
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
		const Shot   s = shoot(p.xn, p.yn, p.P, p.a, R2_, t1_, t2_);
		Solution     out;
		const double y1 = s.y1, phi1 = s.beta1 + t1_ - pi / 2;
		out.gap             = p.a * R1_;
		out.beta1           = s.beta1;
		out.beta2           = s.beta2;
		out.contact_radius1 = s.y1 * R1_;
		out.contact_radius2 = s.y2 * R1_;
		out.neck_radius     = p.yn * R1_;
		out.pressure        = gamma * p.P / R1_;
		out.force_neck      = pi * gamma * R1_ * (2 * p.yn - p.P * p.yn * p.yn);
		out.force_contact   = pi * gamma * R1_ * (2 * y1 * std::cos(phi1) - p.P * y1 * y1);
		out.volume          = s.volume * R1_ * R1_ * R1_;
		return out;
	}

} // namespace yl
} // namespace capillary
