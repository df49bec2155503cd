// Kernel unit tests: every model against an independent, literal evaluation of the published
// formula (written here from the papers, in their printed form) and against analytic limits.
#include "models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace capillary;

namespace {

const double     inf = std::numeric_limits<double>::infinity();

// Gladkyy2014 Table 1 (R_i, R_j [m], gamma [N/m], theta [rad], V [m^3]).
struct Case {
	const char* code;
	double      Ri, Rj, gamma, theta, V;
};
const std::vector<Case> table1 = {
	{ "W11", 2.381e-3, 2.381e-3, 20.6e-3, 0, 13.6e-12 },  { "W12", 2.381e-3, 2.381e-3, 20.6e-3, 0, 31.3e-12 },
	{ "W13", 2.381e-3, 2.381e-3, 20.6e-3, 0, 74.2e-12 },  { "W21", 2.381e-3, 1.588e-3, 20.6e-3, 0, 9.6e-12 },
	{ "W22", 2.381e-3, 1.588e-3, 20.6e-3, 0, 13.2e-12 },  { "W23", 2.381e-3, 1.588e-3, 20.6e-3, 0, 24.7e-12 },
	{ "W24", 2.381e-3, 1.588e-3, 20.6e-3, 0, 59.3e-12 },  { "W31", 2.381e-3, 1.191e-3, 20.6e-3, 0, 25.3e-12 },
	{ "W32", 2.381e-3, 1.191e-3, 20.6e-3, 0, 61.8e-12 },  { "W33", 2.381e-3, 1.191e-3, 20.6e-3, 0, 127.8e-12 },
	{ "R1", 19e-6, 35e-6, 27e-3, 10 * pi / 180, 2e-19 },  { "R2", 19e-6, 32.5e-6, 24e-3, 10 * pi / 180, 12e-19 },
	{ "R3", 19e-6, 27.5e-6, 28e-3, 10 * pi / 180, 36e-19 },
};

BridgeSpec specFor(const Case& c, Model m, Rupture r = Rupture::willett)
{
	BridgeSpec s;
	s.R1 = c.Ri, s.R2 = c.Rj, s.volume = c.V, s.gamma = c.gamma, s.theta1 = s.theta2 = c.theta, s.model = m, s.rupture = r;
	return s;
}

// ---- literal paper formulas (independent of models.cpp) -----------------------------------
double Rh(double a, double b) { return 2 * a * b / (a + b); } // Gladkyy eq. (1)
double paperWeigert(double R, double V, double g, double t, double a)
{
	const double Ca = 1 + 6 * a / (2 * R), Ct = 1 + 1.1 * std::sin(t);                       // (A3), (A4)
	const double beta = std::asin(std::pow(V / (0.12 * std::pow(2 * R, 3) * Ca * Ct), 0.25)); // (A2)
	const double R1 = (R * (1 - std::cos(beta)) + a / 2) / std::cos(beta + t);               // (A6), half gap
	const double R2 = R * std::sin(beta) + R1 * (std::sin(beta + t) - 1);                     // (A7)
	const double pk = g * (1 / R1 - 1 / R2);                                                  // (A5)
	return pi / 4 * std::pow(2 * R, 2) * std::pow(std::sin(beta), 2) * pk + g * pi * 2 * R * std::sin(beta) * std::sin(beta + t); // (5)
}
double paperWillettFull(double R, double V, double g, double t, double a)
{
	const double L = std::log(V / std::pow(R, 3));
	const double f1 = (-0.44507 + 0.050832 * t - 1.1466 * t * t) + (-0.1119 - 0.000411 * t - 0.1490 * t * t) * L
	        + (-0.012101 - 0.0036456 * t - 0.01255 * t * t) * std::pow(L, 2) + (-0.0005 - 0.0003505 * t - 0.00029076 * t * t) * std::pow(L, 3);
	const double f2 = (1.9222 - 0.57473 * t - 1.2918 * t * t) + (-0.0668 - 0.1201 * t - 0.22574 * t * t) * L
	        + (-0.0013375 - 0.0068988 * t - 0.01137 * t * t) * std::pow(L, 2);
	const double f3 = (1.268 - 0.01396 * t - 0.23566 * t * t) + (0.198 + 0.092 * t - 0.06418 * t * t) * L
	        + (0.02232 + 0.02238 * t - 0.009853 * t * t) * std::pow(L, 2) + (0.0008585 + 0.001318 * t - 0.00053 * t * t) * std::pow(L, 3);
	const double f4 = (-0.010703 + 0.073776 * t - 0.34742 * t * t) + (0.03345 + 0.04543 * t - 0.09056 * t * t) * L
	        + (0.0018574 + 0.004456 * t - 0.006257 * t * t) * std::pow(L, 2);
	const double S = a / (2 * std::sqrt(V / R)); // (6)
	return 2 * pi * R * g * std::exp(f1 - f2 * std::exp(f3 * std::log(S) + f4 * std::pow(std::log(S), 2))); // (7)
}
double paperWillettReduced(double R, double V, double g, double t, double a)
{
	const double S = a / (2 * std::sqrt(V / R));
	return 2 * pi * R * g * std::cos(t) / (1 + 2.1 * S + 10 * S * S); // (8)
}
double paperRabinovich(double R, double V, double g, double t, double a, bool sine)
{
	const double alpha = std::sqrt(a / R * (-1 + std::sqrt(1 + 2 * V / (pi * R * a * a)))); // (9)
	const double d     = a / 2 * (-1 + std::sqrt(1 + 2 * V / (pi * R * a * a)));           // (10)
	const double F     = 2 * pi * R * g * std::cos(t) / (1 + a / (2 * d));                  // (12)
	return sine ? F + 2 * pi * g * R * std::sin(alpha) * std::sin(t + alpha) : F;           // (11), attraction > 0
}
double paperRichefeu(double Ri, double Rj, double V, double g, double t, double a)
{
	const double lambda = 0.9 / std::sqrt(2.0) * std::sqrt(V) * std::pow(std::max(Ri / Rj, Rj / Ri), -0.5) * std::sqrt(1 / Ri + 1 / Rj); // (11)
	return 2 * pi * g * std::cos(t) * std::sqrt(Ri * Rj) * std::exp(-a / lambda); // (4), (5), (10)
}
double paperSoulie(double Ri, double Rj, double V, double g, double t, double a)
{
	const double R2 = std::max(Ri, Rj), Vs = V / std::pow(R2, 3);
	const double A = -1.1 * std::pow(Vs, -0.53), B = (-0.148 * std::log(Vs) - 0.96) * t * t - 0.0082 * std::log(Vs) + 0.48,
	             C = 0.0018 * std::log(Vs) + 0.078;
	return pi * g * std::sqrt(Ri * Rj) * (C + std::exp(A * a / R2 + B));
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

} // namespace

// Every Table 1 case, gaps 1e-4 .. 0.999 of the rupture distance: the kernel equals the
// literal formula to rounding (1e-10 relative; the kernels use cancellation-free rewrites).
TEST(PaperFormulas, Table1AllGaps)
{
	for (const auto& c : table1) {
		const double R = Rh(c.Ri, c.Rj);
		for (double frac : { 1e-4, 0.01, 0.1, 0.25, 0.5, 0.75, 0.95, 0.999 }) {
			const double a    = frac * make_bridge(specFor(c, Model::willett_reduced)).rupture;
			const auto   kern = [&](Model m) { return force(specFor(c, m), a); };
			SCOPED_TRACE(std::string(c.code) + " a/a_crit=" + std::to_string(frac));
			EXPECT_LT(rel(kern(Model::weigert), paperWeigert(R, c.V, c.gamma, c.theta, a)), 1e-10);
			EXPECT_LT(rel(kern(Model::willett_full), paperWillettFull(R, c.V, c.gamma, c.theta, a)), 1e-10);
			EXPECT_LT(rel(kern(Model::willett_reduced), paperWillettReduced(R, c.V, c.gamma, c.theta, a)), 1e-12);
			EXPECT_LT(rel(kern(Model::rabinovich), paperRabinovich(R, c.V, c.gamma, c.theta, a, true)), 1e-9);
			EXPECT_LT(rel(kern(Model::rabinovich_lambert), paperRabinovich(R, c.V, c.gamma, c.theta, a, false)), 1e-9);
			EXPECT_LT(rel(kern(Model::richefeu), paperRichefeu(c.Ri, c.Rj, c.V, c.gamma, c.theta, a)), 1e-12);
			EXPECT_LT(rel(kern(Model::soulie), paperSoulie(c.Ri, c.Rj, c.V, c.gamma, c.theta, a)), 1e-12);
		}
	}
}

// Derjaguin limit F(0) = 2 pi R gamma cos(theta) for the reduced models (Gladkyy eq. 8, 12 at
// a = 0; Richefeu eq. 4-5 with the geometric mean), and the analytic a -> 0 limits of the
// models whose printed formula is singular there.
TEST(Limits, ForceAtContact)
{
	for (const auto& c : table1) {
		SCOPED_TRACE(c.code);
		const double R = Rh(c.Ri, c.Rj), derjaguin = 2 * pi * R * c.gamma * std::cos(c.theta);
		EXPECT_NEAR(force(specFor(c, Model::willett_reduced), 0), derjaguin, 1e-14 * derjaguin);
		EXPECT_NEAR(force(specFor(c, Model::rabinovich_lambert), 0), derjaguin, 1e-14 * derjaguin);
		EXPECT_NEAR(force(specFor(c, Model::richefeu), 0), 2 * pi * std::sqrt(c.Ri * c.Rj) * c.gamma * std::cos(c.theta), 1e-14 * derjaguin);
		// Willett full: f3 ln S + f4 ln^2 S -> -inf (f4 < 0), so F(0) = 2 pi R gamma exp(f1).
		const auto f = willett_coefficients(c.V / (R * R * R), c.theta);
		EXPECT_NEAR(force(specFor(c, Model::willett_full), 0), 2 * pi * R * c.gamma * std::exp(f[0]), 1e-12 * derjaguin);
		// Rabinovich: alpha(0) = (2V / (pi R^3))^(1/4) from eq. (9), Elskamp2018 eq. (17) at S = 0.
		const double alpha0 = std::pow(2 * c.V / (pi * R * R * R), 0.25);
		EXPECT_NEAR(force(specFor(c, Model::rabinovich), 0), derjaguin + 2 * pi * R * c.gamma * std::sin(alpha0) * std::sin(c.theta + alpha0),
		            1e-12 * derjaguin);
		// Continuity into the limit: the printed formulas at a tiny gap approach the limits.
		for (Model m : { Model::willett_full, Model::rabinovich, Model::rabinovich_lambert }) {
			const Bridge b = make_bridge(specFor(c, m));
			EXPECT_LT(rel(bridge_force(b, 1e-12 * b.rupture), b.force0), 1e-4) << name_of(m);
		}
	}
}

// Willett's reduced model in the Herminghaus/MercuryDPM/Roy normalisation (Roy eq. 12):
// 1/(1 + 1.05 Sbar + 2.5 Sbar^2), Sbar = a sqrt(R/V). Same function as Gladkyy eq. (8).
TEST(Limits, WillettReducedBothNormalisations)
{
	for (const auto& c : table1) {
		const double R = Rh(c.Ri, c.Rj);
		const Bridge b = make_bridge(specFor(c, Model::willett_reduced));
		for (double frac : { 0.0, 0.1, 0.3, 0.6, 0.9 }) {
			const double a = frac * b.rupture, Sbar = a * std::sqrt(R / c.V);
			const double roy = 2 * pi * R * c.gamma * std::cos(c.theta) / (1 + 1.05 * Sbar + 2.5 * Sbar * Sbar);
			EXPECT_LT(rel(bridge_force(b, a), roy), 1e-13) << c.code;
		}
	}
}

// A sphere-wall bridge: effective radius 2R (harmonic mean with R2 -> inf), so F(0) = 4 pi R
// gamma cos(theta) (Derjaguin sphere-plane limit); every closed-form model equals the pair of
// equal spheres of radius 2R (young_laplace_table holds the exact sphere-plane solution instead,
// tested against the solver in test_young_laplace.cpp), and a very large second sphere
// approaches the wall for the harmonic-mean models.
TEST(Limits, SphereWall)
{
	const double R = 1e-3, V = 1e-11, g = 0.07, t = 0.3;
	for (const auto& row : models()) {
		if (row.model == Model::young_laplace_table) continue;
		BridgeSpec wall;
		wall.R1 = R, wall.R2 = inf, wall.volume = V, wall.gamma = g, wall.theta1 = wall.theta2 = t, wall.model = row.model;
		BridgeSpec pair = wall;
		pair.R1 = pair.R2 = 2 * R;
		const Bridge bw = make_bridge(wall), bp = make_bridge(pair);
		EXPECT_DOUBLE_EQ(pair_of(wall).R, 2 * R) << row.name;
		EXPECT_DOUBLE_EQ(bw.rupture, bp.rupture) << row.name;
		for (double frac : { 0.0, 0.3, 0.8 }) EXPECT_DOUBLE_EQ(bridge_force(bw, frac * bw.rupture), bridge_force(bp, frac * bp.rupture)) << row.name;
	}
	BridgeSpec s;
	s.R1 = R, s.R2 = inf, s.volume = V, s.gamma = g, s.theta1 = s.theta2 = t, s.model = Model::willett_reduced;
	EXPECT_NEAR(force(s, 0), 4 * pi * R * g * std::cos(t), 1e-15);
	for (Model m : { Model::willett_full, Model::willett_reduced, Model::rabinovich_lambert, Model::weigert }) {
		BridgeSpec big = s;
		big.R2 = 1e6 * R, big.model = m;
		s.model = m;
		EXPECT_LT(rel(force(big, 0.5 * make_bridge(s).rupture), force(s, 0.5 * make_bridge(s).rupture)), 1e-5) << name_of(m);
	}
}

// Rupture rules against their printed formulas.
TEST(Rupture, PrintedFormulas)
{
	for (const auto& c : table1) {
		for (double t2 : { c.theta, c.theta + 0.3 }) {
			SCOPED_TRACE(c.code);
			const double t = (c.theta + t2) / 2, R = Rh(c.Ri, c.Rj), vs = c.V / (R * R * R);
			EXPECT_NEAR(rupture_distance(Rupture::lian, c.Ri, c.Rj, c.V, c.theta, t2), (1 + t / 2) * std::cbrt(c.V), 1e-15); // Richefeu eq. (6)
			EXPECT_NEAR(rupture_distance(Rupture::willett, c.Ri, c.Rj, c.V, c.theta, t2),
			            R * (1 + t / 2) * (std::pow(vs, 1. / 3) + std::pow(vs, 2. / 3) / 10), 1e-15); // Gladkyy eq. (2)
			const double ri = std::max(c.Ri, c.Rj), rj = std::min(c.Ri, c.Rj);
			EXPECT_NEAR(rupture_distance(Rupture::willett_elskamp, c.Ri, c.Rj, c.V, c.theta, t2),
			            R * (1 + (0.125 * c.theta + 0.125 * t2) * (1 + rj / ri)) * (std::pow(vs, 1. / 3) + (rj / (2 * ri) - 2. / 5) * std::pow(vs, 2. / 3)),
			            1e-15); // Elskamp eq. (32)
		}
	}
	// Elskamp eq. (32) reduces to Willett's eq. (2) (Elskamp eq. 31) for equal spheres and angles.
	EXPECT_NEAR(rupture_distance(Rupture::willett_elskamp, 1e-3, 1e-3, 1e-11, 0.4, 0.4), rupture_distance(Rupture::willett, 1e-3, 1e-3, 1e-11, 0.4, 0.4),
	            1e-18);
}

// Roy et al. section 4.2: the calibrated linear law has the reference model's maximum force and
// adhesive energy; E = fmax^2 / (2 kc) (area of the triangle, eq. 16-17), checked against a
// trapezoid integration of the reference force that is independent of the kernel's quadrature.
TEST(LinearIrreversible, CalibratedByForceAndEnergy)
{
	for (const auto& c : table1) {
		for (Model ref : { Model::willett_full, Model::willett_reduced, Model::rabinovich_lambert, Model::richefeu }) {
			BridgeSpec s = specFor(c, Model::linear_irreversible);
			s.calibrate_from = ref;
			const Bridge lin = make_bridge(s), rb = make_bridge(specFor(c, ref));
			const int    n   = 200000;
			double       E   = 0;
			for (int i = 0; i < n; ++i) {
				const double a0 = rb.rupture * i / n, a1 = rb.rupture * (i + 1) / n;
				E += (bridge_force(rb, a0) + bridge_force(rb, std::min(a1, rb.rupture))) / 2 * (a1 - a0);
			}
			SCOPED_TRACE(std::string(c.code) + " from " + name_of(ref));
			EXPECT_NEAR(lin.force0, rb.force0, 1e-12 * rb.force0);
			EXPECT_LT(rel(lin.force0 * lin.force0 / (2 * std::get<LinearIrreversible>(lin.m).kc), E), 1e-6);
			EXPECT_LT(rel(adhesive_energy(lin), E), 1e-6);
			EXPECT_NEAR(lin.rupture, 2 * E / lin.force0, 1e-6 * lin.rupture);
		}
	}
	BridgeSpec given = specFor(table1[0], Model::linear_irreversible);
	given.linear_fmax = 2e-4, given.linear_kc = 0.5;
	const Bridge b = make_bridge(given);
	EXPECT_DOUBLE_EQ(b.rupture, 2e-4 / 0.5);
	EXPECT_DOUBLE_EQ(bridge_force(b, 1e-4), 2e-4 - 0.5 * 1e-4);
}

// Bad input: std::invalid_argument whose message names the parameter.
TEST(BadInput, NamesTheParameter)
{
	const BridgeSpec good = specFor(table1[0], Model::willett_full);
	struct Bad {
		const char*                      param;
		std::function<void(BridgeSpec&)> spoil;
	};
	const double nan = std::nan("");
	const std::vector<Bad> bad = {
		{ "volume", [](BridgeSpec& s) { s.volume = -1e-12; } }, { "volume", [](BridgeSpec& s) { s.volume = 0; } },
		{ "volume", [&](BridgeSpec& s) { s.volume = nan; } },   { "gamma", [](BridgeSpec& s) { s.gamma = 0; } },
		{ "theta1", [](BridgeSpec& s) { s.theta1 = pi / 2; } }, { "theta2", [](BridgeSpec& s) { s.theta2 = -0.1; } },
		{ "theta1", [&](BridgeSpec& s) { s.theta1 = nan; } },   { "R1", [](BridgeSpec& s) { s.R1 = -1; } },
		{ "R2", [&](BridgeSpec& s) { s.R2 = nan; } },
		{ "linear_kc", [](BridgeSpec& s) { s.model = Model::linear_irreversible, s.linear_fmax = 1e-4; } },
		{ "calibrate_from", [](BridgeSpec& s) { s.model = Model::linear_irreversible, s.calibrate_from = Model::linear_irreversible; } },
	};
	for (const auto& b : bad) {
		BridgeSpec s = good;
		b.spoil(s);
		try {
			make_bridge(s);
			ADD_FAILURE() << "no error for bad " << b.param;
		} catch (const std::invalid_argument& e) {
			EXPECT_NE(std::string(e.what()).find(b.param), std::string::npos) << e.what();
		}
	}
	EXPECT_THROW(model_from_name("Willett_numeric"), std::invalid_argument);
	EXPECT_THROW(rupture_from_name("pitois"), std::invalid_argument);
	try {
		model_from_name("nope");
	} catch (const std::invalid_argument& e) {
		EXPECT_NE(std::string(e.what()).find("willett_full"), std::string::npos) << "the message lists the allowed names";
	}
}

// F(0) = 2 pi R gamma e^f1 needs f4 < 0 (Gladkyy eq. B4): true over the whole declared domain of
// willett_full, checked on a dense grid up to its corners.
TEST(Limits, WillettF4NegativeOverTheDomain)
{
	const Domain& d = info(Model::willett_full).domain;
	for (int i = 0; i <= 400; ++i)
		for (int j = 0; j <= 100; ++j) {
			const double vs = d.vstar_min * std::pow(d.vstar_max / d.vstar_min, i / 400.0), t = d.theta_max * j / 100;
			ASSERT_LT(willett_coefficients(vs, t)[3], 0) << "V*=" << vs << " theta=" << t;
		}
}

// Input that no bridge can have is refused whatever the model, naming the parameter and keeping
// its value (before the hardening these gave NaN or inf, or an infinite rupture distance).
TEST(BadInput, AbsurdValues)
{
	const BridgeSpec good = specFor(table1[0], Model::willett_reduced);
	struct Bad {
		const char*                      words;
		std::function<void(BridgeSpec&)> spoil;
	};
	const std::vector<Bad> bad = {
		{ "R1 = 1e-150 m", [](BridgeSpec& s) { s.R1 = 1e-150; } },     { "R1 = 1e+150 m", [](BridgeSpec& s) { s.R1 = 1e150; } },
		{ "R2 = 1e+150 m", [](BridgeSpec& s) { s.R2 = 1e150; } },      { "R2 = -inf m", [](BridgeSpec& s) { s.R2 = -inf; } },
		{ "volume = 1e+300 m^3", [](BridgeSpec& s) { s.volume = 1e300; } }, { "volume = 4.94065645841247e-324", [](BridgeSpec& s) { s.volume = 5e-324; } },
		{ "gamma = 1e-300 N/m", [](BridgeSpec& s) { s.gamma = 1e-300; } },
		{ "linear_fmax = 1e+300 N", [](BridgeSpec& s) { s.model = Model::linear_irreversible, s.linear_fmax = 1e300, s.linear_kc = 1; } },
		{ "linear_fmax = 0.001 N and linear_kc = 1e-300 N/m give the range", [](BridgeSpec& s) { s.model = Model::linear_irreversible, s.linear_fmax = 1e-3, s.linear_kc = 1e-300; } },
		{ "linear_kc = inf N/m", [](BridgeSpec& s) { s.model = Model::linear_irreversible, s.linear_fmax = 1e-3, s.linear_kc = inf; } },
		{ "linear_fmax = -5 N is outside the allowed range {0} (not used by model willett_reduced)", [](BridgeSpec& s) { s.linear_fmax = -5; } },
	};
	for (const auto& b : bad) {
		BridgeSpec s = good;
		b.spoil(s);
		try {
			make_bridge(s);
			ADD_FAILURE() << "no error for " << b.words;
		} catch (const std::invalid_argument& e) {
			EXPECT_NE(std::string(e.what()).find(b.words), std::string::npos) << e.what();
		}
	}
}
