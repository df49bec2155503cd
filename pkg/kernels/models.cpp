// Capillary bridge models: per-bridge invariants, domains, extrapolation, the model table.
// Conventions (units, the size ratio, the mean contact angle, V*) and their sources: docs/models.md, "Conventions".
#include "models.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace capillary {

namespace {

	[[noreturn]] void outside_model(const char* model, const std::string& why)
	{
		throw std::invalid_argument(std::string("model ") + model + " is not defined for this bridge: " + why);
	}

	// ---- domains ------------------------------------------------------------------------
	bool in_domain(const Domain& d, const Pair& p)
	{
		return d.allows_vstar(p.vstar) && d.allows_theta(p.theta1) && d.allows_theta(p.theta2) && d.allows_ratio(p.ratio)
		        && (d.wall || !p.wall) && d.allows_angles(p.theta1, p.theta2);
	}

	// Names the first variable outside the domain, its value and the model's range.
	[[noreturn]] void refuse(const char* model, const Domain& d, const Pair& p)
	{
		const std::string hint = std::string("the fitted domain of model ") + model + " (" + d.source
		        + "); set extrapolate=True to evaluate the model at the nearest point of its domain";
		if (!d.allows_vstar(p.vstar))
			out_of_range("V* = V/R^3", p.vstar, "[" + format_value(d.vstar_min) + ", " + format_value(d.vstar_max) + "]", "", hint);
		for (const auto& [name, t] : { std::pair<const char*, double> { "theta1", p.theta1 }, { "theta2", p.theta2 } })
			if (!d.allows_theta(t)) out_of_range(name, t, "[0, " + format_value(d.theta_max) + "]", "rad", hint);
		if (!d.allows_ratio(p.ratio)) out_of_range("R_large/R_small", p.ratio, "[1, " + format_value(d.ratio_max) + "]", "", hint);
		if (p.wall && !d.wall) throw std::invalid_argument(std::string("R2 = inf (a wall) is outside ") + hint);
		throw std::invalid_argument("theta1 = " + format_value(p.theta1) + " rad and theta2 = " + format_value(p.theta2)
		                            + " rad differ; equal contact angles are required by " + hint);
	}

	// The nearest in-domain pair: V*, angles and size ratio clamped (the larger sphere shrunk to
	// ratio_max times the smaller, each keeping its angle). A wall has ratio 1 (its equivalent pair).
	Pair clamped(const Domain& d, const Pair& p)
	{
		Pair c = p;
		if (c.ratio > d.ratio_max) {
			double& large = c.r1 > c.r2 ? c.r1 : c.r2;
			large         = d.ratio_max * std::min(c.r1, c.r2);
			c.R1 = c.r1, c.R2 = c.r2;
		}
		c.ratio  = std::max(c.r1, c.r2) / std::min(c.r1, c.r2);
		c.R      = harmonic_mean_radius(c.r1, c.r2);
		c.theta1 = std::min(p.theta1, d.theta_max);
		c.theta2 = std::min(p.theta2, d.theta_max);
		if (d.equal_angles) c.theta1 = c.theta2 = equivalent_angle(c.theta1, c.theta2);
		c.theta      = equivalent_angle(c.theta1, c.theta2);
		c.theta_mean = (c.theta1 + c.theta2) / 2;
		c.vstar  = std::clamp(p.vstar, d.vstar_min, d.vstar_max);
		c.volume = c.vstar * c.R * c.R * c.R;
		return c;
	}

	BridgeSpec spec_of(const BridgeSpec& s, const Pair& p)
	{
		BridgeSpec c = s;
		c.R1 = p.R1, c.R2 = p.R2, c.volume = p.volume, c.theta1 = p.theta1, c.theta2 = p.theta2;
		return c;
	}

	// Builds variant alternative I (a model type M) or its extrapolated form.
	template <class M, std::size_t I> Bridge build(const BridgeSpec& s, const Pair& p, const char* name)
	{
		if (!M::needs_linear) {
			if (s.linear_fmax != 0) out_of_range("linear_fmax", s.linear_fmax, "{0} (not used by model " + std::string(name) + ")", "N");
			if (s.linear_kc != 0) out_of_range("linear_kc", s.linear_kc, "{0} (not used by model " + std::string(name) + ")", "N/m");
		}
		Bridge b;
		if (in_domain(M::domain, p)) {
			b.rupture = rupture_distance(s.rupture, p);
			M m       = M::make(s, p, b.rupture);
			b.force0  = m.force0();
			b.m.template emplace<I>(std::move(m));
			return b;
		}
		if (!s.extrapolate || (p.wall && !M::domain.wall)) refuse(name, M::domain, p); // no nearest point for a wall
		const Pair   c = clamped(M::domain, p);
		const double rule_c = rupture_distance(s.rupture, c), rule_p = rupture_distance(s.rupture, p);
		double       rupture_c = rule_c;
		M            m         = M::make(spec_of(s, c), c, rupture_c);
		// A model with its own range: stretched as the rupture rule stretches from c to p.
		b.rupture = M::own_rupture ? rupture_c * rule_p / rule_c : rule_p;
		Extrapolated<M> e      = { std::move(m), rupture_c / b.rupture, p.R * std::cos(p.theta) / (c.R * std::cos(c.theta)) };
		b.force0               = e.force0();
		b.m.template emplace<I + Models::n>(std::move(e));
		return b;
	}

	// Adaptive Simpson quadrature of the bridge force over [lo, hi] with a budget of evaluations.
	struct Simpson {
		const Bridge& b;
		long          budget;
		double        integrate(double lo, double hi, double flo, double fmid, double fhi, double whole, double tol)
		{
			const double mid = (lo + hi) / 2, lm = (lo + mid) / 2, rm = (mid + hi) / 2;
			const double flm = bridge_force(b, lm), frm = bridge_force(b, rm);
			budget -= 2;
			const double left = (mid - lo) / 6 * (flo + 4 * flm + fmid), right = (hi - mid) / 6 * (fmid + 4 * frm + fhi);
			if (budget <= 0) throw std::runtime_error("adhesive energy: the quadrature did not converge within its budget of evaluations");
			if (std::abs(left + right - whole) <= 15 * tol || hi - lo <= 1e-12 * b.rupture) return left + right + (left + right - whole) / 15;
			return integrate(lo, mid, flo, flm, fmid, left, tol / 2) + integrate(mid, hi, fmid, frm, fhi, right, tol / 2);
		}
	};

	const std::vector<RuptureInfo> rupture_table = {
		{ Rupture::lian, "lian", "Richefeu2008 eq. (6)" },
		{ Rupture::willett, "willett", "Gladkyy2014 eq. (2)" },
		{ Rupture::willett_elskamp, "willett_elskamp", "Elskamp2018 eq. (32)" },
	};
#define CAPILLARY_INFO_(name, Type) { Model::name, #name, Type::reference, Type::monotone, Type::own_rupture, Type::needs_linear, Type::domain },
	const std::vector<ModelInfo> model_table = { CAPILLARY_MODELS(CAPILLARY_INFO_) };
#undef CAPILLARY_INFO_

} // namespace

// ---- the models' invariants ------------------------------------------------------------------

Weigert Weigert::make(const BridgeSpec&, const Pair& p, double& rupture)
{
	Weigert w;
	w.R = p.R, w.gamma = p.gamma, w.theta = p.theta;
	w.vk = p.volume / (0.12 * 8 * p.R * p.R * p.R * (1 + 1.1 * std::sin(p.theta))); // (A1) with (A4)
	// The toroidal approximation needs beta + theta < pi/2 and a positive neck radius r2; both
	// are tightest at the largest beta (a = 0) and the largest gap (a = rupture).
	const double sinb0 = std::pow(w.vk, 0.25);
	if (!(sinb0 < 1) || std::asin(sinb0) + p.theta >= pi / 2)
		outside_model("weigert", "half-filling angle + contact angle >= pi/2 (V* = " + format_value(p.vstar) + ")");
	const double F0 = w.force(0), Frup = w.force(rupture);
	if (!(std::isfinite(F0) && std::isfinite(Frup) && Frup >= 0))
		outside_model("weigert", "negative neck radius before rupture (V* = " + format_value(p.vstar) + ")");
	return w;
}

double Weigert::force(double a) const
{
	const double Ca   = 1 + 6 * a / (2 * R);                  // (A3)
	const double sinb = std::pow(vk / Ca, 0.25);               // (A2)
	const double beta = std::asin(sinb);
	const double half = std::sin(beta / 2);
	// (A6) with the half gap a/2: the toroidal geometry of a symmetric bridge, and the form used
	// by YADE's built-in law that produced the paper's figures; (A6) as printed uses the full gap,
	// so this is a correction of the printed equation, not a literal transcription.
	const double r1 = (2 * R * half * half + a / 2) / std::cos(beta + theta); // R(1-cos b) = 2R sin^2(b/2)
	const double r2 = R * sinb + r1 * (std::sin(beta + theta) - 1);          // (A7)
	const double pk = gamma * (1 / r1 - 1 / r2);                             // (A5), r2 counted negative
	return pi / 4 * (2 * R) * (2 * R) * sinb * sinb * pk + gamma * pi * 2 * R * sinb * std::sin(beta + theta); // (5)
}

WillettFull WillettFull::make(const BridgeSpec&, const Pair& p, double&)
{
	WillettFull w;
	const auto  f = willett_coefficients(p.vstar, p.theta);
	w.f1 = f[0], w.f2 = f[1], w.f3 = f[2], w.f4 = f[3];
	// F(0) is the limit e^f1 only while f4 < 0, which holds over the whole domain (tested).
	if (!(w.f4 < 0)) outside_model("willett_full", "f4 = " + format_value(w.f4) + " >= 0 (V* = " + format_value(p.vstar) + ")");
	w.inv_s = 1 / (2 * std::sqrt(p.volume / p.R));
	w.scale = 2 * pi * p.R * p.gamma;
	return w;
}

WillettReduced WillettReduced::make(const BridgeSpec&, const Pair& p, double&)
{
	return { 1 / (2 * std::sqrt(p.volume / p.R)), 2 * pi * p.R * p.gamma * std::cos(p.theta) };
}

RabinovichLambert RabinovichLambert::make(const BridgeSpec&, const Pair& p, double&)
{
	return { 2 * p.volume / (pi * p.R), 2 * pi * p.R * p.gamma * std::cos(p.theta) };
}

Rabinovich Rabinovich::make(const BridgeSpec& s, const Pair& p, double& rupture)
{
	return { RabinovichLambert::make(s, p, rupture), p.R, p.theta, 2 * pi * p.R * p.gamma };
}

Richefeu Richefeu::make(const BridgeSpec&, const Pair& p, double&)
{
	// Richefeu2008 eq. (4), (5): f0 = 2 pi gamma cos(theta) sqrt(R1 R2); eq. (11) with c = 0.9,
	// h(r) = r^(-1/2) and R' the harmonic mean.
	const double lambda = 0.9 / std::sqrt(2.0) * std::sqrt(p.volume) / std::sqrt(p.ratio) * std::sqrt(1 / p.r1 + 1 / p.r2);
	return { 2 * pi * p.gamma * std::cos(p.theta) * std::sqrt(p.r1 * p.r2), 1 / lambda };
}

Soulie Soulie::make(const BridgeSpec&, const Pair& p, double&)
{
	// Soulie2006: F = pi gamma sqrt(R1 R2) (C + exp(A a / R2 + B)), R2 the larger radius,
	// V* = V / R2^3. Coefficients as printed by Soulie (0.148, 0.0082, 0.0018, with ln); they are
	// Mikami's (0.34, 0.019, 0.0042) divided by ln(10). Soulie's set is used because it is the one
	// published with this force law for unequal spheres and the one of YADE's built-in law, so the
	// two implementations can be checked against each other.
	const double Rl = std::max(p.r1, p.r2), vs = p.volume / (Rl * Rl * Rl), L = std::log(vs);
	Soulie       m;
	m.A     = -1.1 * std::pow(vs, -0.53) / Rl;
	m.B     = (-0.148 * L - 0.96) * p.theta * p.theta - 0.0082 * L + 0.48;
	m.C     = 0.0018 * L + 0.078;
	m.scale = pi * p.gamma * std::sqrt(p.r1 * p.r2);
	return m;
}

LinearIrreversible LinearIrreversible::make(const BridgeSpec& s, const Pair& p, double& rupture)
{
	double fmax = s.linear_fmax, kc = s.linear_kc;
	if (!(fmax > 0 && kc > 0)) {
		if (fmax != 0 || kc != 0) {
			if (!(fmax > 0)) out_of_range("linear_fmax", fmax, "(0, inf), or 0 with linear_kc = 0 to calibrate", "N");
			out_of_range("linear_kc", kc, "(0, inf), or 0 with linear_fmax = 0 to calibrate", "N/m");
		}
		if (s.calibrate_from == Model::linear_irreversible) {
			std::string others;
			for (const auto& row : models())
				if (row.model != Model::linear_irreversible) others += (others.empty() ? "" : ", ") + std::string(row.name);
			throw std::invalid_argument("calibrate_from = linear_irreversible is not allowed; allowed: " + others);
		}
		// Roy et al. section 4.2: equal maximum force and equal adhesive energy E = fmax^2 / (2 kc),
		// hence kc = fmax^2 / (2 E) and rupture fmax / kc = 2 E / fmax.
		BridgeSpec ref = s;
		ref.model      = s.calibrate_from;
		Bridge rb;
		try {
			rb = make_bridge(ref);
		} catch (const std::invalid_argument& e) {
			throw std::invalid_argument(std::string("calibrate_from = ") + name_of(s.calibrate_from) + ": " + e.what());
		}
		fmax = rb.force0;
		for (int i = 1; i <= 256; ++i) fmax = std::max(fmax, bridge_force(rb, rb.rupture * i / 256.0));
		kc = fmax * fmax / (2 * adhesive_energy(rb));
	}
	if (!(fmax <= Plausible::force_max)) out_of_range("linear_fmax", fmax, "(0, " + format_value(Plausible::force_max) + "]", "N");
	rupture = fmax / kc; // Roy eq. (17): the model defines its own interaction range
	if (!(rupture > 0 && rupture <= Plausible::range_max * p.R))
		throw std::invalid_argument("linear_fmax = " + format_value(fmax) + " N and linear_kc = " + format_value(kc) + " N/m give the range fmax/kc = " + format_value(rupture) + " m, outside the allowed range (0, "
		                            + format_value(Plausible::range_max * p.R) + "] m (" + format_value(Plausible::range_max)
		                            + " effective radii)");
	return { fmax, kc };
}

YoungLaplaceTable YoungLaplaceTable::make(const BridgeSpec&, const Pair& p, double& rupture)
{
	// The exact rupture distance of the solver, whatever the rupture rule.
	const yltable::Curve c = yltable::curve(p.R1, p.R2, p.volume, p.gamma, p.theta1, p.theta2);
	// The evaluated form is 1/F: the table holds attractive bridges. At V* above about 0.3 with both
	// angles near 70 deg the exact force turns repulsive somewhere between contact and rupture; a
	// force below 1e-3 of the bridge's largest counts as turning (1/F between the nodes could cross 0).
	double g_max = c.g[0];
	for (double g : c.g) g_max = std::max(g_max, g);
	const double g_min = std::asinh(1e-3 * std::sinh(g_max));
	for (int m = 0; m < yltable::n_w; ++m)
		if (!(c.g[m] > g_min))
			throw std::invalid_argument("young_laplace_table: the exact force of this bridge (V* = V/Rh^3 = " + format_value(p.vstar) + ", theta1 = "
			                            + format_value(p.theta1) + " rad, theta2 = " + format_value(p.theta2) + " rad) turns repulsive at a/a_rupture = "
			                            + format_value(yltable::gap_fraction(yltable::tau_node(m))) + " (F = "
			                            + format_value(c.scale * yltable::force_delta * std::sinh(c.g[m])) + " N); the table holds attractive bridges only (a force above 1e-3 of its largest from contact to rupture)");
	auto                 k = std::make_shared<Coefficients>();
	yltable::coefficients(c, k->data());
	rupture = c.rupture;
	return { std::move(k) };
}

// ---- validation, rupture rules, the bridge ----------------------------------------------------

Pair pair_of(const BridgeSpec& s)
{
	check_radii(s.R1, s.R2);
	if (!(s.gamma >= Plausible::gamma_min && s.gamma <= Plausible::gamma_max))
		out_of_range("gamma", s.gamma, "[" + format_value(Plausible::gamma_min) + ", " + format_value(Plausible::gamma_max) + "]", "N/m");
	if (!(s.theta1 >= 0 && s.theta1 < pi / 2)) out_of_range("theta1", s.theta1, "[0, pi/2)", "rad");
	if (!(s.theta2 >= 0 && s.theta2 < pi / 2)) out_of_range("theta2", s.theta2, "[0, pi/2)", "rad");
	if (!(s.volume > 0 && std::isfinite(s.volume))) out_of_range("volume", s.volume, "(0, inf)", "m^3");
	Pair p;
	p.R1 = s.R1, p.R2 = s.R2, p.wall = is_wall(s.R2);
	equivalent_pair(s.R1, s.R2, p.r1, p.r2);
	p.R      = harmonic_mean_radius(p.r1, p.r2);
	p.ratio  = std::max(p.r1, p.r2) / std::min(p.r1, p.r2);
	p.volume = s.volume, p.gamma = s.gamma;
	p.theta1 = s.theta1, p.theta2 = s.theta2, p.theta = equivalent_angle(s.theta1, s.theta2), p.theta_mean = (s.theta1 + s.theta2) / 2;
	p.vstar  = s.volume / (p.R * p.R * p.R);
	if (!(p.vstar >= Plausible::vstar_min && p.vstar <= Plausible::vstar_max))
		out_of_range("volume", s.volume,
		             "[" + format_value(Plausible::vstar_min * p.R * p.R * p.R) + ", " + format_value(Plausible::vstar_max * p.R * p.R * p.R)
		                     + "] for R = " + format_value(p.R) + " m (V* = V/R^3 in [" + format_value(Plausible::vstar_min) + ", "
		                     + format_value(Plausible::vstar_max) + "], a pendular bridge)",
		             "m^3");
	return p;
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

double rupture_distance(Rupture rule, const Pair& p)
{
	switch (rule) {
		// lian, willett: printed for equal angles; unequal ones enter by their mean (the exact rupture
		// of unequal angles is shorter still, docs/models.md "Unequal contact angles").
		case Rupture::lian: return (1 + p.theta_mean / 2) * std::cbrt(p.volume); // Richefeu2008 eq. (6)
		case Rupture::willett: {
			const double vs = std::cbrt(p.vstar);
			return p.R * (1 + p.theta_mean / 2) * (vs + vs * vs / 10); // Gladkyy2014 eq. (2)
		}
		case Rupture::willett_elskamp: {
			// Elskamp2018 eq. (32): r_i is the larger sphere; r_eff the harmonic mean, V* = V/r_eff^3.
			const double ri = std::max(p.r1, p.r2), rj = std::min(p.r1, p.r2), vs = std::cbrt(p.vstar);
			return p.R * (1 + (p.theta1 + p.theta2) / 8 * (1 + rj / ri)) * (vs + (rj / (2 * ri) - 0.4) * vs * vs);
		}
	}
	throw std::invalid_argument("rupture: unknown enumerator");
}

double rupture_distance(Rupture rule, double R1, double R2, double volume, double theta1, double theta2)
{
	BridgeSpec s;
	s.R1 = R1, s.R2 = R2, s.volume = volume, s.theta1 = theta1, s.theta2 = theta2;
	s.gamma = 1; // the rupture distance does not depend on the surface tension
	return rupture_distance(rule, pair_of(s));
}

Bridge make_bridge(const BridgeSpec& s)
{
	const Pair p = pair_of(s);
	Bridge     b;
	switch (s.model) {
#define CAPILLARY_BUILD_(name, Type)                                                                                                                 \
	case Model::name: b = build<Type, 1 + std::size_t(Model::name)>(s, p, #name); break;
		CAPILLARY_MODELS(CAPILLARY_BUILD_)
#undef CAPILLARY_BUILD_
		default: throw std::invalid_argument("model: unknown enumerator");
	}
	b.force_rupture = bridge_force(b, b.rupture);
	return b;
}

double force(const BridgeSpec& spec, double a) { return bridge_force(make_bridge(spec), a); }

double adhesive_energy(const Bridge& b)
{
	const double hi = b.rupture, f0 = bridge_force(b, 0), fm = bridge_force(b, hi / 2), f1 = bridge_force(b, hi);
	const double whole = hi / 6 * (f0 + 4 * fm + f1);
	if (!std::isfinite(whole)) throw std::invalid_argument("adhesive energy: F(0) = " + format_value(f0) + " N over " + format_value(hi) + " m is not finite");
	// Relative tolerance: an absolute one would underflow for tiny forces and never be met.
	Simpson s { b, 1 << 20 };
	return s.integrate(0, hi, f0, fm, f1, whole, 1e-12 * std::abs(whole));
}

// ---- the table -------------------------------------------------------------------------------

const std::vector<ModelInfo>&   models() { return model_table; }
const std::vector<RuptureInfo>& rupture_rules() { return rupture_table; }
const ModelInfo& info(Model m)
{
	if (std::size_t(m) >= model_table.size()) throw std::invalid_argument("model: unknown enumerator " + std::to_string(int(m)));
	return model_table[std::size_t(m)];
}
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
const char* name_of(Model m) { return info(m).name; }
const char* name_of(Rupture r)
{
	for (const auto& row : rupture_table)
		if (row.rule == r) return row.name;
	return "?";
}

} // namespace capillary
