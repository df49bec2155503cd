// Capillary bridge models. Conventions and traps: ../shared/notes/capillary-models.md.
#include "models.hpp"

#include "young_laplace_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace capillary {

namespace {

constexpr double pi = 3.14159265358979323846;

const std::vector<ModelInfo> model_table = {
	{ Model::weigert, "weigert", "Gladkyy2014 eq. (5), (A2)-(A7), half gap in (A6)", true },
	{ Model::willett_full, "willett_full", "Gladkyy2014 eq. (6), (7), (B1)-(B4)", true },
	{ Model::willett_reduced, "willett_reduced", "Gladkyy2014 eq. (6), (8)", true },
	{ Model::rabinovich, "rabinovich", "Gladkyy2014 eq. (9)-(11)", false },
	{ Model::rabinovich_lambert, "rabinovich_lambert", "Gladkyy2014 eq. (9), (10), (12)", true },
	{ Model::richefeu, "richefeu", "Richefeu2008 eq. (4), (5), (10), (11)", true },
	{ Model::soulie, "soulie", "Soulie2006 (coefficients as printed there)", true },
	{ Model::linear_irreversible, "linear_irreversible", "Roy eq. (16), (17), section 4.2", true },
	// Not monotone: at large contact angles the exact force first grows slightly with the gap.
	{ Model::young_laplace_table, "young_laplace_table", "Young-Laplace solver, tabulated (data/young_laplace_table.csv)", false },
};
const std::vector<RuptureInfo> rupture_table = {
	{ Rupture::lian, "lian", "Richefeu2008 eq. (6)" },
	{ Rupture::willett, "willett", "Gladkyy2014 eq. (2)" },
	{ Rupture::willett_elskamp, "willett_elskamp", "Elskamp2018 eq. (32)" },
};

template <class T> std::string join_names(const std::vector<T>& table)
{
	std::string s;
	for (const auto& row : table) s += (s.empty() ? "" : ", ") + std::string(row.name);
	return s;
}

[[noreturn]] void out_of_range(const char* name, double value, const char* range, const char* unit)
{
	std::ostringstream msg;
	msg.precision(10);
	msg << name << " = " << value << " " << unit << " is outside the allowed range " << range;
	throw std::invalid_argument(msg.str());
}

// Equal radii stand in for a wall (see make_bridge in the header).
void pair_radii(double R1, double R2, double& r1, double& r2)
{
	if (std::isinf(R2)) r1 = r2 = 2 * R1;
	else { r1 = R1; r2 = R2; }
}

double harmonic_mean_radius(double r1, double r2) { return 2 * r1 * r2 / (r1 + r2); } // Gladkyy2014 eq. (1)

// ---- model kernels: force at gap a > 0 from the invariants -------------------------------
// Invariants k[] per model are listed at each make_* function below.

// Weigert: k = {0.12 (2R)^3 C_theta}.
double weigert(const Bridge& b, double a)
{
	const double R     = b.R;
	const double Ca    = 1 + 6 * a / (2 * R);                                    // (A3)
	const double sinb  = std::pow(b.volume / (b.k[0] * Ca), 0.25);              // (A2)
	const double beta  = std::asin(sinb);
	const double half  = std::sin(beta / 2);
	// (A6) with the half gap a/2: the toroidal geometry of a symmetric bridge, and the form used
	// by YADE's built-in law that produced the paper's figures; (A6) as printed uses the full gap.
	const double r1 = (2 * R * half * half + a / 2) / std::cos(beta + b.theta); // R(1-cos b) = 2R sin^2(b/2)
	const double r2 = R * sinb + r1 * (std::sin(beta + b.theta) - 1);          // (A7)
	const double pk = b.gamma * (1 / r1 - 1 / r2);                               // (A5), r2 counted negative
	return pi / 4 * (2 * R) * (2 * R) * sinb * sinb * pk + b.gamma * pi * 2 * R * sinb * std::sin(beta + b.theta); // (5)
}

// Willett full: k = {f1, f2, f3, f4, 1/(2 sqrt(V/R)), 2 pi R gamma}.
double willett_full(const Bridge& b, double a)
{
	const double lnS = std::log(a * b.k[4]);                                      // (6)
	return b.k[5] * std::exp(b.k[0] - b.k[1] * std::exp(b.k[2] * lnS + b.k[3] * lnS * lnS)); // (7)
}

// Willett reduced: k = {1/(2 sqrt(V/R)), 2 pi R gamma cos(theta)}.
double willett_reduced(const Bridge& b, double a)
{
	const double S = a * b.k[0];                 // (6)
	return b.k[1] / (1 + 2.1 * S + 10 * S * S); // (8)
}

// Rabinovich: k = {c = 2V/(pi R), 2 pi R gamma cos(theta), 2 pi R gamma}.
// With c = 2V/(pi R): a/(2 d_sp) = a (a + sqrt(a^2 + c)) / c and
// alpha = sqrt(c / (R (sqrt(a^2 + c) + a))), the forms of eq. (9), (10) that stay finite at a = 0.
double rabinovich_lambert(const Bridge& b, double a)
{
	const double root = std::sqrt(a * a + b.k[0]);
	return b.k[1] / (1 + a * (a + root) / b.k[0]); // (12)
}
double rabinovich(const Bridge& b, double a)
{
	const double root  = std::sqrt(a * a + b.k[0]);
	const double alpha = std::sqrt(b.k[0] / (b.R * (root + a)));                      // (9)
	return rabinovich_lambert(b, a) + b.k[2] * std::sin(alpha) * std::sin(b.theta + alpha); // (11), attractive
}

// Richefeu: k = {kappa sqrt(R1 R2), 1/lambda}.
double richefeu(const Bridge& b, double a) { return b.k[0] * std::exp(-a * b.k[1]); } // (10)

// Soulie: k = {A/R_large, B, C, pi gamma sqrt(R1 R2)}.
double soulie(const Bridge& b, double a) { return b.k[3] * (b.k[2] + std::exp(b.k[0] * a + b.k[1])); }

// Linear irreversible: k = {f_max, k_c}.
double linear_irreversible(const Bridge& b, double a) { return std::max(0.0, b.k[0] - b.k[1] * a); } // Roy (16)

// Young-Laplace table: k = the coefficients of yltable::coefficients().
static_assert(std::tuple_size<decltype(Bridge::k)>::value >= yltable::n_coefficients, "Bridge::k too small for the young_laplace_table coefficients");
double young_laplace_table(const Bridge& b, double a) { return yltable::force(b.k.data(), a); }

double evaluate(const Bridge& b, double a)
{
	switch (b.model) {
		case Model::weigert: return weigert(b, a);
		case Model::willett_full: return willett_full(b, a);
		case Model::willett_reduced: return willett_reduced(b, a);
		case Model::rabinovich: return rabinovich(b, a);
		case Model::rabinovich_lambert: return rabinovich_lambert(b, a);
		case Model::richefeu: return richefeu(b, a);
		case Model::soulie: return soulie(b, a);
		case Model::linear_irreversible: return linear_irreversible(b, a);
		case Model::young_laplace_table: return young_laplace_table(b, a);
	}
	return 0;
}

// Adaptive Simpson quadrature of the bridge force over [lo, hi].
double simpson(const Bridge& b, double lo, double hi, double flo, double fmid, double fhi, double whole, double tol, int depth)
{
	const double mid = (lo + hi) / 2, lm = (lo + mid) / 2, rm = (mid + hi) / 2;
	const double flm = bridge_force(b, lm), frm = bridge_force(b, rm);
	const double left = (mid - lo) / 6 * (flo + 4 * flm + fmid), right = (hi - mid) / 6 * (fmid + 4 * frm + fhi);
	if (depth <= 0 || std::abs(left + right - whole) <= 15 * tol) return left + right + (left + right - whole) / 15;
	return simpson(b, lo, mid, flo, flm, fmid, left, tol / 2, depth - 1) + simpson(b, mid, hi, fmid, frm, fhi, right, tol / 2, depth - 1);
}

void check_inputs(const BridgeSpec& s)
{
	const double inf = std::numeric_limits<double>::infinity();
	if (!(s.R1 > 0 && s.R1 < inf)) out_of_range("R1", s.R1, "(0, inf)", "m");
	if (!(s.R2 > 0)) out_of_range("R2", s.R2, "(0, inf] (inf: wall)", "m");
	if (!(s.volume > 0 && s.volume < inf)) out_of_range("volume", s.volume, "(0, inf)", "m^3");
	if (!(s.gamma > 0 && s.gamma < inf)) out_of_range("gamma", s.gamma, "(0, inf)", "N/m");
	if (!(s.theta1 >= 0 && s.theta1 < pi / 2)) out_of_range("theta1", s.theta1, "[0, pi/2)", "rad");
	if (!(s.theta2 >= 0 && s.theta2 < pi / 2)) out_of_range("theta2", s.theta2, "[0, pi/2)", "rad");
}

[[noreturn]] void outside_model(const char* model, const std::string& why)
{
	throw std::invalid_argument(std::string("model ") + model + " is not defined for this bridge: " + why);
}

} // namespace

const std::vector<ModelInfo>&   models() { return model_table; }
const std::vector<RuptureInfo>& rupture_rules() { return rupture_table; }
std::string                     model_names() { return join_names(model_table); }
std::string                     rupture_names() { return join_names(rupture_table); }

Model model_from_name(const std::string& name)
{
	for (const auto& row : model_table)
		if (name == row.name) return row.model;
	throw std::invalid_argument("model = '" + name + "' is unknown; allowed: " + model_names());
}
Rupture rupture_from_name(const std::string& name)
{
	for (const auto& row : rupture_table)
		if (name == row.name) return row.rule;
	throw std::invalid_argument("rupture = '" + name + "' is unknown; allowed: " + rupture_names());
}
const char* name_of(Model m)
{
	for (const auto& row : model_table)
		if (row.model == m) return row.name;
	return "?";
}
const char* name_of(Rupture r)
{
	for (const auto& row : rupture_table)
		if (row.rule == r) return row.name;
	return "?";
}

std::array<double, 4> willett_coefficients(double vstar, double t)
{
	const double L = std::log(vstar), t2 = t * t;
	return {
		(-0.44507 + 0.050832 * t - 1.1466 * t2) + (-0.1119 - 0.000411 * t - 0.1490 * t2) * L
		        + (-0.012101 - 0.0036456 * t - 0.01255 * t2) * L * L + (-0.0005 - 0.0003505 * t - 0.00029076 * t2) * L * L * L, // (B1)
		(1.9222 - 0.57473 * t - 1.2918 * t2) + (-0.0668 - 0.1201 * t - 0.22574 * t2) * L
		        + (-0.0013375 - 0.0068988 * t - 0.01137 * t2) * L * L, // (B2)
		(1.268 - 0.01396 * t - 0.23566 * t2) + (0.198 + 0.092 * t - 0.06418 * t2) * L + (0.02232 + 0.02238 * t - 0.009853 * t2) * L * L
		        + (0.0008585 + 0.001318 * t - 0.00053 * t2) * L * L * L, // (B3)
		(-0.010703 + 0.073776 * t - 0.34742 * t2) + (0.03345 + 0.04543 * t - 0.09056 * t2) * L
		        + (0.0018574 + 0.004456 * t - 0.006257 * t2) * L * L, // (B4)
	};
}

double rupture_distance(Rupture rule, double R1, double R2, double volume, double theta1, double theta2)
{
	double r1, r2;
	pair_radii(R1, R2, r1, r2);
	const double theta = (theta1 + theta2) / 2;
	switch (rule) {
		case Rupture::lian: return (1 + theta / 2) * std::cbrt(volume); // Richefeu2008 eq. (6)
		case Rupture::willett: {
			const double R = harmonic_mean_radius(r1, r2), vs = std::cbrt(volume / (R * R * R));
			return R * (1 + theta / 2) * (vs + vs * vs / 10); // Gladkyy2014 eq. (2)
		}
		case Rupture::willett_elskamp: {
			// Elskamp2018 eq. (32): r_i is the larger sphere; r_eff the harmonic mean, V* = V/r_eff^3.
			const double ri = std::max(r1, r2), rj = std::min(r1, r2), R = harmonic_mean_radius(r1, r2);
			const double vs = std::cbrt(volume / (R * R * R));
			return R * (1 + (theta1 + theta2) / 8 * (1 + rj / ri)) * (vs + (rj / (2 * ri) - 0.4) * vs * vs);
		}
	}
	return 0;
}

Bridge make_bridge(const BridgeSpec& s)
{
	check_inputs(s);
	double r1, r2;
	pair_radii(s.R1, s.R2, r1, r2);
	Bridge b {};
	b.model   = s.model;
	b.R       = harmonic_mean_radius(r1, r2);
	b.gamma   = s.gamma;
	b.theta   = (s.theta1 + s.theta2) / 2;
	b.volume  = s.volume;
	b.rupture = rupture_distance(s.rupture, s.R1, s.R2, s.volume, s.theta1, s.theta2);
	const double R = b.R, cos_t = std::cos(b.theta), vstar = s.volume / (R * R * R);
	switch (s.model) {
		case Model::weigert: {
			b.k[0] = 0.12 * 8 * R * R * R * (1 + 1.1 * std::sin(b.theta)); // (A1) with (A4)
			// The toroidal approximation needs beta + theta < pi/2 and a positive neck radius r2;
			// both are tightest at the largest beta (a = 0) and the largest gap (a = rupture).
			const double sinb0 = std::pow(s.volume / b.k[0], 0.25);
			if (!(sinb0 < 1) || std::asin(sinb0) + b.theta >= pi / 2)
				outside_model("weigert", "half-filling angle + contact angle >= pi/2 (V* = " + std::to_string(vstar) + ")");
			b.force0 = weigert(b, 0);
			const double Frup = weigert(b, b.rupture);
			if (!(std::isfinite(b.force0) && std::isfinite(Frup) && Frup >= 0))
				outside_model("weigert", "negative neck radius before rupture (V* = " + std::to_string(vstar) + ")");
			return b;
		}
		case Model::willett_full: {
			const auto f = willett_coefficients(vstar, b.theta);
			std::copy(f.begin(), f.end(), b.k.begin());
			if (!(f[3] < 0))
				outside_model("willett_full", "f4 >= 0 outside the fitted range (V* = " + std::to_string(vstar) + ", theta = "
				                      + std::to_string(b.theta) + " rad); Willett's fit covers V* <= 0.1, theta <= 50 deg");
			b.k[4]   = 1 / (2 * std::sqrt(s.volume / R));
			b.k[5]   = 2 * pi * R * s.gamma;
			b.force0 = b.k[5] * std::exp(f[0]); // a -> 0: f3 ln S + f4 ln^2 S -> -inf as f4 < 0
			return b;
		}
		case Model::willett_reduced:
			b.k[0]   = 1 / (2 * std::sqrt(s.volume / R));
			b.k[1]   = 2 * pi * R * s.gamma * cos_t;
			b.force0 = b.k[1];
			return b;
		case Model::rabinovich:
		case Model::rabinovich_lambert:
			b.k[0]   = 2 * s.volume / (pi * R);
			b.k[1]   = 2 * pi * R * s.gamma * cos_t;
			b.k[2]   = 2 * pi * R * s.gamma;
			b.force0 = evaluate(b, 0);
			return b;
		case Model::richefeu: {
			// Richefeu2008 eq. (4), (5): f0 = 2 pi gamma cos(theta) sqrt(R1 R2); eq. (11) with c = 0.9.
			const double ratio  = std::max(r1 / r2, r2 / r1);
			const double lambda = 0.9 / std::sqrt(2.0) * std::sqrt(s.volume) / std::sqrt(ratio) * std::sqrt(1 / r1 + 1 / r2);
			b.k[0]   = 2 * pi * s.gamma * cos_t * std::sqrt(r1 * r2);
			b.k[1]   = 1 / lambda;
			b.force0 = b.k[0];
			return b;
		}
		case Model::soulie: {
			// Soulie2006: F = pi gamma sqrt(R1 R2) (C + exp(A a / R2 + B)), R2 the larger radius,
			// V* = V / R2^3. Coefficients as printed by Soulie (0.148, 0.0082, 0.0018, with ln);
			// they are Mikami's (0.34, 0.019, 0.0042) divided by ln(10). Soulie's set is used because
			// it is the one published with this force law for unequal spheres and the one of YADE's
			// built-in law, so the two implementations can be checked against each other.
			const double Rl = std::max(r1, r2), vs = s.volume / (Rl * Rl * Rl), L = std::log(vs);
			b.k[0]   = -1.1 * std::pow(vs, -0.53) / Rl;
			b.k[1]   = (-0.148 * L - 0.96) * b.theta * b.theta - 0.0082 * L + 0.48;
			b.k[2]   = 0.0018 * L + 0.078;
			b.k[3]   = pi * s.gamma * std::sqrt(r1 * r2);
			b.force0 = soulie(b, 0);
			return b;
		}
		case Model::linear_irreversible: {
			double fmax = s.linear_fmax, kc = s.linear_kc;
			if (!(fmax > 0 && kc > 0)) {
				if (fmax != 0 || kc != 0) {
					if (!(fmax > 0 && std::isfinite(fmax))) out_of_range("linear_fmax", fmax, "(0, inf), or 0 with linear_kc = 0 to calibrate", "N");
					out_of_range("linear_kc", kc, "(0, inf), or 0 with linear_fmax = 0 to calibrate", "N/m");
				}
				if (s.calibrate_from == Model::linear_irreversible)
					throw std::invalid_argument("calibrate_from = linear_irreversible: choose another model to calibrate from");
				// Roy et al. section 4.2: equal maximum force and equal adhesive energy
				// E = fmax^2 / (2 kc), hence kc = fmax^2 / (2 E) and rupture fmax / kc = 2 E / fmax.
				BridgeSpec ref = s;
				ref.model      = s.calibrate_from;
				const Bridge rb = make_bridge(ref);
				fmax            = rb.force0;
				for (int i = 1; i <= 256; ++i) fmax = std::max(fmax, bridge_force(rb, rb.rupture * i / 256.0));
				kc = fmax * fmax / (2 * adhesive_energy(rb));
			}
			if (!std::isfinite(fmax)) out_of_range("linear_fmax", fmax, "(0, inf)", "N");
			if (!std::isfinite(kc)) out_of_range("linear_kc", kc, "(0, inf)", "N/m");
			b.k[0]    = fmax;
			b.k[1]    = kc;
			b.rupture = fmax / kc; // Roy eq. (17): the model defines its own interaction range
			b.force0  = fmax;
			return b;
		}
		case Model::young_laplace_table: {
			// The exact rupture distance of the solver, whatever the rupture rule.
			const yltable::Curve c = yltable::curve(s.R1, s.R2, s.volume, s.gamma, s.theta1, s.theta2);
			yltable::coefficients(c, b.k.data());
			b.rupture = c.rupture;
			b.force0  = c.force[yltable::n_w - 1];
			return b;
		}
	}
	throw std::invalid_argument("model: unknown enumerator");
}

double bridge_force(const Bridge& b, double a)
{
	if (!(a <= b.rupture)) return 0; // also a NaN gap: no force rather than NaN
	if (a <= 0) return b.force0;
	return evaluate(b, a);
}

double adhesive_energy(const Bridge& b)
{
	const double hi = b.rupture, f0 = bridge_force(b, 0), fm = bridge_force(b, hi / 2), f1 = bridge_force(b, hi);
	const double whole = hi / 6 * (f0 + 4 * fm + f1);
	return simpson(b, 0, hi, f0, fm, f1, whole, 1e-12 * b.force0 * hi, 40);
}

double force(const BridgeSpec& spec, double a) { return bridge_force(make_bridge(spec), a); }

} // namespace capillary
