// Young-Laplace pendular bridge solver; see young_laplace.hpp for the equations.
// Internally all lengths are scaled by R1 (sphere 1 has radius 1); P is scaled by 1/R1.
#include "young_laplace.hpp"

#include "conventions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace capillary {
namespace yl {

	namespace {

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

		// Root of f on [lo, hi], where f(lo) = flo and f(hi) = fhi have opposite signs, by the Illinois
		// variant of regula falsi; stops when |f| <= ftol or the bracket is narrower than xtol.
		template <class F> double illinois(double lo, double hi, double flo, double fhi, F f, double xtol, double ftol)
		{
			int    side = 0;
			double x    = hi;
			for (int it = 0; it < 200 && hi - lo > xtol; ++it) {
				x             = (lo * fhi - hi * flo) / (fhi - flo);
				const double fx = f(x);
				if (std::abs(fx) <= ftol) break;
				if ((fx > 0) == (flo > 0)) {
					lo = x, flo = fx;
					if (side == -1) fhi /= 2;
					side = -1;
				} else {
					hi = x, fhi = fx;
					if (side == 1) flo /= 2;
					side = 1;
				}
			}
			return x;
		}

		// One arc of the meniscus: from a contact line (x0, y0, phi0) towards +x up to the matching
		// plane x = xm (halfway between the contact lines), where the profile of the other solid (integrated in the mirror image x -> -x)
		// must continue it. Both arcs start on their contact line with the angle the contact angle
		// prescribes, so the contact conditions hold by construction: no end condition is singular,
		// including theta = 0, where the meniscus is tangent to the sphere. x increases monotonically
		// along a pendular meniscus (|phi| < pi/2).
		struct Arc {
			bool   ok = false;
			double y = 0, phi = 0, W = 0;    // at the matching plane; W = integral of pi y^2 dx
			double neck_y = 0, neck_phi = 0; // narrowest section of the arc
			double neck_x = 0, neck_W = 0;   // its position and W from the contact line to it
		};

		Arc arc(double x0, double y0, double phi0, double xm, double P, double tol)
		{
			Arc   out;
			State s = { x0, y0, phi0, 0 };
			if (!(y0 > 0) || !(std::abs(phi0) <= pi / 2) || x0 > xm) return out; // vertical start: theta = 0 on a plane
			out.neck_y = y0, out.neck_phi = phi0, out.neck_x = x0, out.neck_W = 0;
			// The step length in (0, step] from `from` that makes fn vanish.
			auto refine = [&](const State& from, const State& to, double step, auto fn) {
				State m = to;
				double e;
				illinois(0, step, fn(from), fn(to), [&](double h) { return fn(m = dopri_step(from, P, h, e)); }, 1e-16 * (1 + step), 0);
				return m;
			};
			auto   at_plane = [&](const State& q) { return q[0] - xm; };
			double h        = 0.01 * y0, length = 0;
			if (x0 == xm) {
				out.ok = true, out.y = y0, out.phi = phi0;
				return out;
			}
			for (int step = 0; step < 100000 && length < 100; ++step) {
				double      err;
				const State n = dopri_step(s, P, h, err);
				if (!(err <= tol) || !(n[1] > 0)) {
					h *= std::max(0.1, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
					if (h < 1e-15) return out;
					continue;
				}
				const bool  done = at_plane(n) >= 0;
				const State e    = done ? refine(s, n, h, at_plane) : n;
				if (s[2] < 0 && e[2] >= 0) { // interior neck
					const State m = refine(s, e, done ? h : h, [](const State& q) { return q[2]; });
					if (m[1] < out.neck_y) out.neck_y = m[1], out.neck_phi = m[2], out.neck_x = m[0], out.neck_W = m[3];
				}
				if (e[1] < out.neck_y && (done || e[2] == 0)) out.neck_y = e[1], out.neck_phi = e[2], out.neck_x = e[0], out.neck_W = e[3];
				if (done) {
					out.y = e[1], out.phi = e[2], out.W = e[3];
					out.ok = std::abs(e[2]) < pi / 2 && e[1] > 0;
					return out;
				}
				if (!(std::abs(n[2]) < pi / 2)) return out; // vertical tangent: not a pendular meniscus
				length += h;
				s = n;
				h *= std::min(5.0, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
			}
			return out;
		}

		struct Shot {
			bool   ok = false;
			double dy = 0, dphi = 0; // mismatch of the two arcs at the matching plane (dy in units of L)
			double volume = 0;       // liquid volume: both arcs minus the two sphere caps
			double neck_y = 0, neck_phi = 0;
			double y2 = 0;           // contact-line radius on solid 2
			double volume1 = 0;      // the liquid on solid 1's side of the neck (the rest is on solid 2's side)
		};


		// Sphere 1 (radius 1) left of the gap a with filling angle beta1; solid 2 right of it: a sphere
		// of radius R2 with filling angle s2, or (R2 = inf) a plane with contact-line radius s2.
		Shot shoot(double beta1, double s2, double P, double a, double R2, double t1, double t2, double tol, double L)
		{
			Shot         out;
			const bool   plane = std::isinf(R2);
			const double h1    = 2 * std::pow(std::sin(beta1 / 2), 2); // 1 - cos(beta1)
			double       h2 = 0, y2, phi2, cap2 = 0;
			if (plane) y2 = s2, phi2 = t2 - pi / 2;
			else {
				h2 = 2 * R2 * std::pow(std::sin(s2 / 2), 2);
				y2 = R2 * std::sin(s2), phi2 = s2 + t2 - pi / 2;
				cap2 = pi * h2 * h2 * (3 * R2 - h2) / 3;
			}
			// Matching plane halfway between the contact lines, where the profile is far from vertical.
			const double xm   = (h2 - h1) / 2;
			const Arc    left = arc(-(a / 2 + h1), std::sin(beta1), beta1 + t1 - pi / 2, xm, P, tol);
			if (!left.ok) return out;
			const Arc right = arc(-(a / 2 + h2), y2, phi2, -xm, P, tol);
			if (!right.ok) return out;
			out.ok       = true;
			out.dy       = (left.y - right.y) / L;
			out.dphi     = left.phi + right.phi; // the mirror image reverses the angle
			out.volume   = left.W + right.W - pi * h1 * h1 * (3 - h1) / 3 - cap2;
			const Arc& n = left.neck_y <= right.neck_y ? left : right;
			out.neck_y = n.neck_y, out.neck_phi = n.neck_phi;
			out.y2 = y2;
			// Split at the neck: the liquid between a contact line and the neck is the arc's W minus
			// the part of that solid between its contact-line plane and the neck plane (the solids'
			// centres: x = -(a/2 + 1) for sphere 1, -(a/2 + R2) for sphere 2 in its mirrored frame).
			if (&n == &left) out.volume1 = left.neck_W - sphere_slab_volume(1, 1 - h1, left.neck_x + a / 2 + 1);
			else out.volume1 = out.volume - (right.neck_W - (plane ? 0 : sphere_slab_volume(R2, R2 - h2, right.neck_x + a / 2 + R2)));
			return out;
		}

		// Forward-difference Jacobian of `res` at u (residual r there), step 1e-7 scale[j], backwards
		// where the forward point has no bridge; false if neither has. Fills columns 0..N-1 of J.
		template <size_t N, class F>
		bool fd_jacobian(const std::array<double, N>& u, const std::array<double, N>& r, const std::array<double, N>& scale, F res, double (&J)[N][N + 1])
		{
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
			return true;
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
				if (!fd_jacobian(u, r, scale, res, J)) return false;
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

		// Unit vector from `from` to `to` and their distance.
		std::array<double, 4> unit(const std::array<double, 4>& from, const std::array<double, 4>& to, double& length)
		{
			std::array<double, 4> c;
			for (int i = 0; i < 4; ++i) c[i] = to[i] - from[i];
			length = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
			for (double& x : c) x /= length;
			return c;
		}

	} // namespace

	bool Bridge::residual(double beta1, double s2, double P, double a, double V, std::array<double, 3>& r) const
	{
		const Shot s = shoot(beta1, s2, P, a, R2_, t1_, t2_, tol_, L_);
		if (!s.ok) return false;
		r = { s.dy, s.dphi, s.volume / V - 1 };
		return true;
	}

	Bridge::Bridge(double R1, double R2, double volume, double theta1, double theta2, double tolerance)
		: tol_(tolerance)
	{
		if (theta2 < 0) theta2 = theta1;
		if (!(R1 > 0 && std::isfinite(R1))) throw std::invalid_argument("R1 = " + format_value(R1) + " m is outside the allowed range (0, inf)");
		if (!(R2 > 0)) throw std::invalid_argument("R2 = " + format_value(R2) + " m is outside the allowed range (0, inf] (inf: plane)");
		if (!(volume > 0 && std::isfinite(volume))) throw std::invalid_argument("volume = " + format_value(volume) + " m^3 is outside the allowed range (0, inf)");
		for (double t : { theta1, theta2 })
			if (!(t >= 0 && t < pi / 2)) throw std::invalid_argument("theta = " + format_value(t) + " rad is outside the allowed range [0, pi/2)");
		if (!(tolerance > 0 && tolerance < 1e-3)) throw std::invalid_argument("tolerance = " + format_value(tolerance) + " is outside the allowed range (0, 1e-3)");
		R1_ = R1, R2_ = R2 / R1, V_ = volume / (R1 * R1 * R1), t1_ = theta1, t2_ = theta2;
		const bool plane = std::isinf(R2_);

		// Contact (a = 0): unknowns beta1, s2, P. Guess for a small volume: thin-film volume
		// pi rho^4 / (2 Rh) for the contact-line radius rho and a toroidal meniscus for the
		// pressure; then continuation in the volume up to V (large bridges have no good guess).
		const double Rh  = plane ? 2 : 2 * R2_ / (1 + R2_);
		double       Vt  = std::min(V_, 1e-4 * Rh * Rh * Rh);
		const double rho = std::pow(2 * Vt * Rh / pi, 0.25);
		const double b1 = std::asin(rho), b2 = plane ? 0 : std::asin(rho / R2_);
		const double rm  = rho * rho / Rh / (std::cos(b1 + t1_) + std::cos(b2 + t2_));
		const double yn0 = std::max(0.5 * rho, rho - rm * (1 - std::sin(b1 + t1_)));
		std::array<double, 3> u = { b1, plane ? rho : b2, 1 / yn0 - 1 / rm };
		L_                      = rho; // length scale of the matching residual
		auto at_contact = [&](const std::array<double, 3>& v, std::array<double, 3>& r) { return residual(v[0], v[1], v[2], 0, Vt, r); };
		auto fail = [&] {
			throw std::runtime_error("Young-Laplace: no pendular bridge at contact for V* = V/R1^3 = " + format_value(Vt) + ", theta = "
			                         + format_value(theta1) + " rad");
		};
		if (!newton(u, { b1, u[1], std::max(1.0, std::abs(u[2])) }, at_contact)) fail();
		for (double factor = 2; Vt < V_;) {
			const std::array<double, 3> last  = u;
			const double                Vlast = Vt, Llast = L_;
			Vt                                = std::min(V_, Vlast * factor);
			const double g                    = std::pow(Vt / Vlast, 0.25);
			u                                 = { last[0] * g, last[1] * g, last[2] / (g * g) };
			L_                                = Llast * g;
			if (!newton(u, { u[0], u[1], std::max(1.0, std::abs(u[2])) }, at_contact)) {
				u = last, Vt = Vlast, L_ = Llast, factor = std::sqrt(factor);
				if (factor < 1.0001) fail();
			}
		}
		branch_.push_back({ u[0], u[1], u[2], 0 });

		// Pseudo-arclength continuation from contact along the branch of solutions (no coordinate
		// need be monotone on it): the gap grows to a maximum, the fold, which is the rupture
		// distance; beyond it the bridges are unstable.
		// The bridge can lose stability (at fixed volume, to axisymmetric perturbations) only where the
		// Jacobian of the bridge equations at fixed gap is singular: at the fold, and, for equal (or
		// nearly equal) spheres at larger contact angles, where the neck starts to move towards one
		// sphere (a symmetry-breaking bifurcation; for nearly equal spheres it becomes a fold of the
		// branch from contact, close to a second branch that continues to the larger symmetric fold,
		// onto which large steps can jump). Hence the steps shrink where |det J| falls, and the branch
		// ends at the first sign change of det J.
		beta0_ = branch_[0].beta1, Lr_ = std::cbrt(V_), Pscale_ = L_; // scales of the arclength
		Vec    t  = { -1, 0, 0, 0 };
		double ds = 0.02, det_last = jacobian_det(branch_[0]);
		if (!(std::isfinite(det_last) && det_last != 0)) throw std::runtime_error("Young-Laplace: singular bridge equations at contact");
		while (true) {
			const Point& last = branch_.back();
			double       d    = 0;
			if (branch_.size() > 1) t = unit(scaled(branch_[branch_.size() - 2]), scaled(last), d);
			Point next;
			if (!on_arc(last, t, ds, last, next)) {
				ds /= 2;
				if (ds < 1e-8) throw std::runtime_error("Young-Laplace: continuation stalled at filling angle " + format_value(last.beta1));
				continue;
			}
			double     step;
			const Vec  c = unit(scaled(last), scaled(next), step);
			if (branch_.size() > 1 && ds > 1e-6 && c[0] * t[0] + c[1] * t[1] + c[2] * t[2] + c[3] * t[3] < 0.9) {
				ds /= 2; // a sharp turn means a jump to another branch: smaller steps
				continue;
			}
			if (branch_.size() == 1 && next.a < last.a && t[0] < 0) {
				// The first step must stretch the bridge. Where the filling angle on solid 1 grows as the gap opens (the less
				// wetting solid first, at large volumes), decreasing it leads to negative gaps: the other way.
				t = { 1, 0, 0, 0 };
				continue;
			}
			if (next.a < last.a && ds > 1e-3) { // passed the fold: approach it with smaller steps first
				ds /= 4;
				continue;
			}
			const double det = jacobian_det(next);
			if (!std::isfinite(det)) { // the perturbed bridges do not exist: as a failed step
				ds /= 2;
				if (ds < 1e-8) throw std::runtime_error("Young-Laplace: continuation stalled at filling angle " + format_value(last.beta1));
				continue;
			}
			if (next.a >= last.a && ds > 1e-4 && !(std::abs(det) > 0.3 * std::abs(det_last) && det * det_last > 0)) {
				ds /= 4; // near a singular point: approach it with smaller steps
				continue;
			}
			if (next.a >= last.a && !(det * det_last > 0)) {
				// Symmetry-breaking bifurcation between last and next (a still grows): bisect on the sign of det J.
				double lo = 0, hi = ds;
				Point  top = last;
				while (hi - lo > 1e-9) {
					const double mid = (lo + hi) / 2;
					Point        p;
					if (!on_arc(last, t, mid, last, p)) break;
					const double dm = jacobian_det(p);
					if (!std::isfinite(dm)) break;
					if (dm * det_last > 0) lo = mid, top = p;
					else hi = mid;
				}
				if (top.a > last.a) branch_.push_back(top);
				break;
			}
			if (next.a < last.a) {
				// Just past the fold: maximise a along the arc between the point before last and next,
				// by golden section on the arclength; the corrector stays regular at the fold.
				const Point& before = branch_.size() > 1 ? branch_[branch_.size() - 2] : last;
				double       lo = -d, hi = ds;
				const double gr = (std::sqrt(5.0) - 1) / 2;
				auto at = [&](double sa) {
					Point p;
					if (!on_arc(last, t, sa, last, p) && !on_arc(last, t, sa, sa > 0 ? next : before, p))
						throw std::runtime_error("Young-Laplace: no bridge near the fold at filling angle " + format_value(last.beta1));
					return p;
				};
				double s1 = hi - gr * (hi - lo), s2 = lo + gr * (hi - lo);
				Point  m1 = at(s1), m2 = at(s2);
				while (hi - lo > 1e-9) {
					if (m1.a > m2.a) {
						hi = s2, s2 = s1, m2 = m1;
						s1 = hi - gr * (hi - lo), m1 = at(s1);
					} else {
						lo = s1, s1 = s2, m1 = m2;
						s2 = lo + gr * (hi - lo), m2 = at(s2);
					}
				}
				const Point top = m1.a > m2.a ? m1 : m2;
				while (branch_.size() > 1 && branch_.back().a >= top.a) branch_.pop_back();
				branch_.push_back(top);
				break;
			}
			branch_.push_back(next);
			det_last = det;
			ds       = std::min(ds * 1.5, 0.05);
		}
		rupture_ = branch_.back().a * R1_;
	}

	double Bridge::jacobian_det(const Point& p) const
	{
		auto res = [&](const std::array<double, 3>& v, std::array<double, 3>& r) { return residual(v[0], v[1], v[2], p.a, V_, r); };
		const std::array<double, 3> u = { p.beta1, p.s2, p.P };
		std::array<double, 3>       r0;
		double                      J[3][4];
		if (!res(u, r0) || !fd_jacobian(u, r0, { beta0_, beta0_, 1 / Pscale_ }, res, J)) return std::numeric_limits<double>::quiet_NaN();
		return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0])
		     + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
	}

	Bridge::Vec Bridge::scaled(const Point& p) const { return { p.beta1 / beta0_, p.s2 / beta0_, p.P * Pscale_, p.a / Lr_ }; }

	bool Bridge::on_arc(const Point& base, const Vec& t, double step, const Point& guess, Point& out) const
	{
		const Vec z0 = scaled(base);
		Vec       zp;
		for (int i = 0; i < 4; ++i) zp[i] = z0[i] + step * t[i];
		// Start from the predictor, except for the coordinates a fallback guess sets apart from base.
		std::array<double, 4> v = { zp[0] * beta0_, zp[1] * beta0_, zp[2] / Pscale_, zp[3] * Lr_ };
		if (guess.beta1 != base.beta1) v = { guess.beta1, guess.s2, guess.P, guess.a };
		auto res = [&](const std::array<double, 4>& x, std::array<double, 4>& r) {
			std::array<double, 3> r3;
			if (!(x[3] > -0.5) || !residual(x[0], x[1], x[2], x[3], V_, r3)) return false;
			const Vec z = scaled({ x[0], x[1], x[2], x[3] });
			r           = { r3[0], r3[1], r3[2], (z[0] - zp[0]) * t[0] + (z[1] - zp[1]) * t[1] + (z[2] - zp[2]) * t[2] + (z[3] - zp[3]) * t[3] };
			return true;
		};
		if (!newton(v, { beta0_, beta0_, 1 / Pscale_, Lr_ }, res)) return false;
		out = { v[0], v[1], v[2], v[3] };
		return true;
	}

	Solution Bridge::solve(double gap, double gamma) const
	{
		const double a = gap / R1_;
		if (!(a >= 0 && gap <= rupture_))
			throw std::invalid_argument("gap = " + format_value(gap) + " m is outside the allowed range [0, rupture gap = " + format_value(rupture_)
			                            + " m]");
		if (!(gamma > 0)) throw std::invalid_argument("gamma = " + format_value(gamma) + " N/m is outside the allowed range (0, inf)");
		// Bracket on the stable branch; Newton on (beta1, s2, P) at this gap from the interpolated
		// guess, or, near the fold where that system becomes singular, the Illinois method on the
		// arclength of the chord between the bracketing branch points (pseudo-arclength corrector).
		size_t k = 0;
		while (k + 1 < branch_.size() && branch_[k + 1].a < a) ++k;
		Point p;
		if (a <= branch_[k].a) p = branch_[k];
		else if (k + 1 == branch_.size() || a >= branch_[k + 1].a) p = branch_[std::min(k + 1, branch_.size() - 1)];
		else {
			Point                 lo = branch_[k], hi = branch_[k + 1];
			const double          f0 = (a - lo.a) / (hi.a - lo.a);
			std::array<double, 3> u  = { lo.beta1 + f0 * (hi.beta1 - lo.beta1), lo.s2 + f0 * (hi.s2 - lo.s2), lo.P + f0 * (hi.P - lo.P) };
			auto at_gap = [&](const std::array<double, 3>& v, std::array<double, 3>& r) { return residual(v[0], v[1], v[2], a, V_, r); };
			const bool near_fold = k + 2 >= branch_.size();
			if (!near_fold && newton(u, { beta0_, std::max(1e-3, std::abs(u[1])), std::max(1.0, std::abs(u[2])) }, at_gap)
			    && std::min(lo.beta1, hi.beta1) - 1e-9 <= u[0] && u[0] <= std::max(lo.beta1, hi.beta1) + 1e-9)
				p = { u[0], u[1], u[2], a };
			else {
				// On the chord from lo to hi: the corrector at arclength s, the Illinois method on a(s) = a.
				double    d;
				const Vec t    = unit(scaled(lo), scaled(hi), d);
				const Vec back = { -t[0], -t[1], -t[2], -t[3] }; // the same hyperplanes seen from hi, in case Newton fails from lo's side
				p = lo;
				illinois(0, d, lo.a - a, hi.a - a, [&](double sm) {
					if (!on_arc(lo, t, sm, lo, p) && !on_arc(lo, t, sm, sm < d / 2 ? lo : hi, p) && !on_arc(hi, back, d - sm, hi, p))
						throw std::runtime_error("Young-Laplace: no bridge found at gap " + format_value(gap));
					return p.a - a;
				}, 1e-15, 1e-14 * (1 + a));
			}
		}
		const Shot   s  = shoot(p.beta1, p.s2, p.P, p.a, R2_, t1_, t2_, tol_, L_);
		const double y1 = std::sin(p.beta1), phi1 = p.beta1 + t1_ - pi / 2;
		Solution     out;
		out.gap             = p.a * R1_;
		out.beta1           = p.beta1;
		out.beta2           = std::isinf(R2_) ? 0 : p.s2;
		out.contact_radius1 = y1 * R1_;
		out.contact_radius2 = s.y2 * R1_;
		out.neck_radius     = s.neck_y * R1_;
		out.pressure        = gamma * p.P / R1_;
		out.force_neck      = pi * gamma * R1_ * (2 * s.neck_y * std::cos(s.neck_phi) - p.P * s.neck_y * s.neck_y);
		out.force_contact   = pi * gamma * R1_ * (2 * y1 * std::cos(phi1) - p.P * y1 * y1);
		out.volume          = s.volume * R1_ * R1_ * R1_;
		out.volume1         = s.volume1 * R1_ * R1_ * R1_;
		out.volume2         = out.volume - out.volume1;
		return out;
	}

} // namespace yl
} // namespace capillary
