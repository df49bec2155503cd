// The contract every capillary model passes, derived from the model table (models()): over its
// declared domain, for every rupture rule, unequal spheres and walls: finite, non-negative, zero
// beyond rupture, continuous up to rupture, monotone where the table says so, symmetric under
// swapping the particles, and F proportional to gamma; continued beyond rupture (the dynamic rupture
// rule), finite and non-negative. Outside the domain a bridge is refused
// with an error naming the variable and the model; with extrapolate it is built and keeps the
// same contract, and inside the domain extrapolate changes nothing.
#include "models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace capillary;

namespace {
const double inf = std::numeric_limits<double>::infinity();

struct Point {
	double  vstar, theta1, theta2, ratio; // ratio = R2/R1, inf = wall
	Rupture rule;
};
std::string describe(const ModelInfo& m, const Point& p)
{
	return std::string(m.name) + " V*=" + format_value(p.vstar) + " theta1=" + format_value(p.theta1) + " theta2=" + format_value(p.theta2)
	        + " R2/R1=" + format_value(p.ratio) + " rupture=" + name_of(p.rule);
}
BridgeSpec specAt(Model m, const Point& p, bool extrapolate = false)
{
	BridgeSpec s;
	s.R1 = 1e-3, s.R2 = p.ratio * 1e-3, s.gamma = 0.05, s.theta1 = p.theta1, s.theta2 = p.theta2, s.model = m, s.rupture = p.rule;
	s.extrapolate  = extrapolate;
	const double R = std::isinf(p.ratio) ? 2e-3 : 2 * s.R1 * s.R2 / (s.R1 + s.R2);
	s.volume       = p.vstar * R * R * R;
	return s;
}

// The model's domain on a grid: its V* range, angles up to its largest, ratios 1..4 (and 100
// where it allows any ratio), walls where allowed, unequal angles where allowed.
std::vector<Point> domain_of(const ModelInfo& m)
{
	const Domain&       d = m.domain;
	std::vector<double> ratios { 1.0, 2.0, 4.0 };
	if (d.ratio_max > 100) ratios.push_back(100);
	if (d.wall) ratios.push_back(inf);
	const double lo = std::max(d.vstar_min, 1e-5), hi = std::min(d.vstar_max, 0.1);
	std::vector<Point> pts;
	for (double f : { 0.0, 0.2, 0.4, 0.6, 0.8, 1.0 })
		for (double tf : { 0.0, 0.2, 0.5, 0.8, 1.0 })
			for (double ratio : ratios)
				for (const auto& r : rupture_rules()) {
					const double t = tf * std::min(d.theta_max, 50 * pi / 180), vs = lo * std::pow(hi / lo, f);
					pts.push_back({ vs, t, t, ratio, r.rule });
					if (!d.equal_angles) pts.push_back({ vs, t, t * 0.5, ratio, r.rule });
				}
	return pts;
}

void holds(const ModelInfo& m, const BridgeSpec& spec, bool swap_check = true)
{
	const Bridge b = make_bridge(spec);
	ASSERT_TRUE(std::isfinite(b.rupture) && b.rupture > 0);
	ASSERT_TRUE(std::isfinite(b.force0) && b.force0 > 0);
	const int n = 2000;
	double    prev = b.force0, maxJump = 0;
	for (int i = 1; i <= n; ++i) {
		const double a = std::min(b.rupture * i / n, b.rupture), F = bridge_force(b, a); // no rounding past rupture
		ASSERT_TRUE(std::isfinite(F)) << "a=" << a;
		ASSERT_GE(F, 0) << "a=" << a;
		if (m.monotone) ASSERT_LE(F, prev * (1 + 1e-12)) << "a=" << a;
		maxJump = std::max(maxJump, std::abs(F - prev));
		prev    = F;
	}
	// Continuity: on a grid of 2000 steps no step changes F by more than 2 % of F(0); a jump
	// inside (0, rupture] would not shrink with the step.
	EXPECT_LT(maxJump, 0.02 * b.force0);
	EXPECT_EQ(bridge_force(b, b.rupture * (1 + 1e-12)), 0.0);
	EXPECT_EQ(bridge_force(b, 10 * b.rupture), 0.0);
	EXPECT_EQ(bridge_force(b, std::nan("")), 0.0);
	EXPECT_EQ(bridge_force(b, -1e-6), b.force0);
	// The dynamic rupture rule (Elskamp2018 eq. 33) keeps a bridge beyond its static rupture
	// distance: the continued force is finite, non-negative and at most the force at the static
	// rupture distance up to 1000 times that distance (a capillary number of 1e6), unchanged up to
	// rupture, and zero beyond the stretched range.
	const double Frup = bridge_force(b, b.rupture);
	for (double stretch : { 1.001, 1.5, 3.0, 10.0, 1000.0 }) {
		const double range = stretch * b.rupture;
		for (int i = 0; i <= 500; ++i) {
			const double a = range * i / 500, F = bridge_force_within(b, a, range);
			ASSERT_TRUE(std::isfinite(F) && F >= 0) << "a=" << a << " range=" << range << " F=" << F;
			if (a <= b.rupture) ASSERT_EQ(F, bridge_force(b, a)) << "a=" << a;
			else ASSERT_LE(F, Frup) << "a=" << a << " range=" << range;
		}
		EXPECT_EQ(bridge_force_within(b, range * (1 + 1e-12), range), 0.0);
	}
	// Scaling: F proportional to gamma at fixed geometry.
	BridgeSpec twice = spec;
	twice.gamma *= 2;
	EXPECT_NEAR(force(twice, 0.5 * b.rupture), 2 * bridge_force(b, 0.5 * b.rupture), 1e-12 * b.force0);
	// Symmetry: swapping the particles (and their angles) changes nothing.
	if (swap_check && !is_wall(spec.R2)) {
		BridgeSpec swapped = spec;
		std::swap(swapped.R1, swapped.R2);
		std::swap(swapped.theta1, swapped.theta2);
		const Bridge bs = make_bridge(swapped);
		EXPECT_NEAR(bs.rupture, b.rupture, 1e-14 * b.rupture);
		EXPECT_NEAR(bridge_force(bs, 0.3 * b.rupture), bridge_force(b, 0.3 * b.rupture), 1e-13 * b.force0);
	}
}
} // namespace

class Contract : public ::testing::TestWithParam<ModelInfo> { };

TEST_P(Contract, HoldsOverTheDomain)
{
	const ModelInfo& m = GetParam();
	for (const Point& p : domain_of(m)) {
		SCOPED_TRACE(describe(m, p));
		holds(m, specAt(m.model, p));
		// Inside the domain extrapolate changes nothing.
		const Bridge b = make_bridge(specAt(m.model, p)), e = make_bridge(specAt(m.model, p, true));
		EXPECT_FALSE(e.extrapolated());
		EXPECT_EQ(bridge_force(e, 0.4 * b.rupture), bridge_force(b, 0.4 * b.rupture));
	}
}

// Points beyond each bound of the domain: refused by default, naming the variable and the
// model; with extrapolate, built and the contract holds.
TEST_P(Contract, OutsideTheDomain)
{
	const ModelInfo& m = GetParam();
	const Domain&    d = m.domain;
	struct Beyond {
		Point       p;
		const char* variable;
	};
	std::vector<Beyond> beyond;
	for (const auto& r : rupture_rules()) {
		for (double ratio : { 1.0, 3.0, inf }) {
			if (d.vstar_max < Plausible::vstar_max) beyond.push_back({ { std::min(1.0, d.vstar_max * 8), 0.2, 0.2, ratio, r.rule }, "V* = V/R^3" });
			if (d.vstar_min > 1e-14) beyond.push_back({ { d.vstar_min / 100, 0.2, 0.2, ratio, r.rule }, "V* = V/R^3" });
			if (d.theta_max < pi / 2) {
				beyond.push_back({ { 1e-3, 1.4, 1.4, ratio, r.rule }, "theta1" });
				beyond.push_back({ { 1e-3, 0.1, 1.3, ratio, r.rule }, "theta2" });
			}
		}
		if (d.ratio_max < 1e6) beyond.push_back({ { 1e-3, 0.2, 0.2, 3 * d.ratio_max, r.rule }, "R_large/R_small" });
		if (d.equal_angles) beyond.push_back({ { 1e-3, 0.2, 0.4, 1.0, r.rule }, "differ" });
	}
	if (beyond.empty()) GTEST_SKIP() << m.name << " has no bounds inside the plausible range";
	for (const Beyond& x : beyond) {
		SCOPED_TRACE(describe(m, x.p));
		try {
			make_bridge(specAt(m.model, x.p));
			ADD_FAILURE() << "no error outside the domain";
		} catch (const std::invalid_argument& e) {
			const std::string what = e.what();
			EXPECT_NE(what.find(x.variable), std::string::npos) << what;
			EXPECT_NE(what.find(m.name), std::string::npos) << what;
			EXPECT_NE(what.find("extrapolate"), std::string::npos) << what;
		}
		const BridgeSpec spec = specAt(m.model, x.p, true);
		EXPECT_TRUE(make_bridge(spec).extrapolated());
		holds(m, spec);
	}
}

INSTANTIATE_TEST_SUITE_P(EveryModel, Contract, ::testing::ValuesIn(models()),
                         [](const ::testing::TestParamInfo<ModelInfo>& info) { return std::string(info.param.name); });
