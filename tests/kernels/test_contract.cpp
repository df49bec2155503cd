// The contract every capillary model passes, over the pendular domain of Willett's fits
// (V* = V/R^3 in [1e-5, 0.1], theta in [0, 50 deg]), unequal spheres up to 1:4, walls, and all
// rupture rules: finite, non-negative, zero beyond rupture, continuous up to rupture, monotone
// where the model table says so, symmetric under swapping the particles, and F proportional to
// gamma.
#include "models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace capillary;

namespace {
constexpr double pi = 3.14159265358979323846;

struct Point {
	double vstar, theta, ratio; // ratio = R2/R1, inf = wall
	Rupture rule;
};
std::vector<Point> domain()
{
	std::vector<Point> pts;
	for (double vs : { 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.1 })
		for (double tdeg : { 0.0, 10.0, 25.0, 40.0, 50.0 })
			for (double ratio : { 1.0, 2.0, 4.0, std::numeric_limits<double>::infinity() })
				for (const auto& r : rupture_rules()) pts.push_back({ vs, tdeg * pi / 180, ratio, r.rule });
	return pts;
}
std::string describe(const ModelInfo& m, const Point& p)
{
	return std::string(m.name) + " V*=" + std::to_string(p.vstar) + " theta=" + std::to_string(p.theta) + " R2/R1=" + std::to_string(p.ratio)
	        + " rupture=" + name_of(p.rule);
}
BridgeSpec specAt(Model m, const Point& p)
{
	BridgeSpec s;
	s.R1 = 1e-3, s.R2 = p.ratio * 1e-3, s.gamma = 0.05, s.theta1 = s.theta2 = p.theta, s.model = m, s.rupture = p.rule;
	const double R = std::isinf(p.ratio) ? 2e-3 : 2 * s.R1 * s.R2 / (s.R1 + s.R2);
	s.volume = p.vstar * R * R * R;
	return s;
}
} // namespace

class Contract : public ::testing::TestWithParam<ModelInfo> { };

TEST_P(Contract, HoldsOverTheDomain)
{
	const ModelInfo& m = GetParam();
	const int        n = 4000;
	for (const Point& p : domain()) {
		SCOPED_TRACE(describe(m, p));
		const BridgeSpec spec = specAt(m.model, p);
		const Bridge     b    = make_bridge(spec);
		ASSERT_TRUE(std::isfinite(b.rupture) && b.rupture > 0);
		ASSERT_TRUE(std::isfinite(b.force0) && b.force0 > 0);
		double prev = b.force0, maxJump = 0;
		for (int i = 1; i <= n; ++i) {
			const double a = std::min(b.rupture * i / n, b.rupture), F = bridge_force(b, a); // no rounding past rupture
			ASSERT_TRUE(std::isfinite(F)) << "a=" << a;
			ASSERT_GE(F, 0) << "a=" << a;
			if (m.monotone) ASSERT_LE(F, prev * (1 + 1e-12)) << "a=" << a;
			maxJump = std::max(maxJump, std::abs(F - prev));
			prev    = F;
		}
		// Continuity: on a grid of 4000 steps no step changes F by more than 1 % of F(0); a jump
		// inside (0, rupture] would not shrink with the step.
		EXPECT_LT(maxJump, 0.01 * b.force0);
		EXPECT_EQ(bridge_force(b, b.rupture * (1 + 1e-12)), 0.0);
		EXPECT_EQ(bridge_force(b, 10 * b.rupture), 0.0);
		EXPECT_EQ(bridge_force(b, -1e-6), b.force0);
		// Scaling: F proportional to gamma at fixed geometry.
		BridgeSpec twice = spec;
		twice.gamma *= 2;
		EXPECT_NEAR(force(twice, 0.5 * b.rupture), 2 * bridge_force(b, 0.5 * b.rupture), 1e-12 * b.force0);
		// Symmetry: swapping the particles changes nothing.
		if (!std::isinf(p.ratio)) {
			BridgeSpec swapped = spec;
			std::swap(swapped.R1, swapped.R2);
			const Bridge bs = make_bridge(swapped);
			EXPECT_NEAR(bs.rupture, b.rupture, 1e-14 * b.rupture);
			EXPECT_NEAR(bridge_force(bs, 0.3 * b.rupture), bridge_force(b, 0.3 * b.rupture), 1e-13 * b.force0);
		}
	}
}

INSTANTIATE_TEST_SUITE_P(EveryModel, Contract, ::testing::ValuesIn(models()),
                         [](const ::testing::TestParamInfo<ModelInfo>& info) { return std::string(info.param.name); });
