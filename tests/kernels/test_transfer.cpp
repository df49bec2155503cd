// Transfer ratio of a breaking bridge: Elskamp2018's parabolic bridge (eq. 35-43) satisfies its own
// equations (contact lines, contact angles, volume), splits equal spheres in halves, and agrees with
// the exact split of the Young-Laplace solver where the meniscus is nearly parabolic; Richefeu2008's
// split in proportion to the diameters; refused input.
#include "transfer.hpp"
#include "young_laplace.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace capillary;

namespace {
const double inf = std::numeric_limits<double>::infinity();
// Equal spheres break at the exact rupture gap (the solver's).
double rupture_gap_for_test(double R, double V, double theta) { return yl::Bridge(R, R, V, theta).rupture_gap(); }
} // namespace

TEST(Transfer, ParabolaMeetsItsEquations)
{
	for (double R2 : { 1e-3, 2e-3, inf }) {
		const double R1 = 1.5e-3, V = 0.01 * std::pow(is_wall(R2) ? 2 * R1 : 2 * R1 * R2 / (R1 + R2), 3), S = 2e-4;
		const double t1 = 0.17, t2 = is_wall(R2) ? 0.8 : 0.3;
		const ParabolicBridge p = parabolic_transfer(R1, R2, V, S, t1, t2);
		const double          y0 = p.c, yL = p.a * p.length * p.length + p.b * p.length + p.c;
		// eq. (36), (38), (39); the volume (41); the mirror of (39) on solid 2 (or the wall angle).
		EXPECT_NEAR(y0, std::sqrt(R1 * R1 - std::pow(R1 - p.d1, 2)), 1e-12 * R1);
		EXPECT_NEAR(p.length, p.d1 + p.d2 + S, 1e-15);
		EXPECT_NEAR(t1, pi / 2 + std::atan(p.b) - std::asin(y0 / R1), 1e-9);
		const double beta2 = is_wall(R2) ? 0 : std::asin(yL / R2);
		EXPECT_NEAR(t2, pi / 2 - std::atan(2 * p.a * p.length + p.b) - beta2, 1e-9);
		const double L = p.length, full = pi * (p.a * p.a * std::pow(L, 5) / 5 + p.a * p.b * std::pow(L, 4) / 2
		                                        + (p.b * p.b + 2 * p.a * p.c) * std::pow(L, 3) / 3 + p.b * p.c * L * L + p.c * p.c * L);
		const double caps = pi * p.d1 * (3 * y0 * y0 + p.d1 * p.d1) / 6 + pi * p.d2 * (3 * yL * yL + p.d2 * p.d2) / 6;
		EXPECT_NEAR(full - caps, V, 1e-9 * V);
		EXPECT_GT(p.a, 0); // concave: the narrowest section between the contact lines
		EXPECT_NEAR(p.x_min, -p.b / (2 * p.a), 1e-15);
		EXPECT_GT(p.transfer1, 0);
		EXPECT_LT(p.transfer1, 1);
	}
}

TEST(Transfer, EqualSpheresSplitInHalves)
{
	for (double theta : { 0.0, 0.17, 0.7 })
		for (double vstar : { 1e-3, 1e-2, 0.1 }) {
			const double R = 1e-3, V = vstar * R * R * R, S = rupture_gap_for_test(R, V, theta);
			EXPECT_NEAR(parabolic_transfer(R, R, V, S, theta, theta).transfer1, 0.5, 1e-9) << theta << " " << vstar;
		}
}

TEST(Transfer, CloseToTheExactSplitForSmallAngles)
{
	// theta = 10 deg, a sphere 1.5 times the other: the exact shares at the rupture gap are 0.570,
	// 0.633, 0.721 at V* = 0.001, 0.01, 0.1 (solver); the parabola gives 0.607, 0.612, 0.616: within
	// 0.11 of the exact share, with the larger sphere keeping more. At 40 deg the parabola departs
	// further (0.53-0.58 against 0.66-0.79, docs/models.md) and is not checked here.
	const double R2 = 1e-3, R1 = 1.5e-3, Rh = 2 * R1 * R2 / (R1 + R2), theta = 10 * pi / 180;
	for (double vstar : { 1e-3, 1e-2, 0.1 }) {
		const yl::Bridge   b(R1, R2, vstar * Rh * Rh * Rh, theta);
		const yl::Solution s = b.solve(b.rupture_gap(), 0.07);
		const double       t = parabolic_transfer(R1, R2, s.volume, b.rupture_gap(), theta, theta).transfer1;
		EXPECT_GT(t, 0.5);
		EXPECT_NEAR(t, s.volume1 / s.volume, 0.11) << vstar;
	}
}

TEST(Transfer, DiametersAndBadInput)
{
	EXPECT_DOUBLE_EQ(diameter_transfer(2e-3, 1e-3), 2.0 / 3);
	EXPECT_DOUBLE_EQ(diameter_transfer(1e-3, inf), 1.0);
	EXPECT_THROW(parabolic_transfer(1e-3, inf, 1e-12, 1e-4, 0.1, 0.0), std::invalid_argument); // a wall needs theta2 > 0
	EXPECT_THROW(parabolic_transfer(1e-3, 1e-3, -1e-12, 1e-4, 0.1, 0.1), std::invalid_argument);
	EXPECT_THROW(parabolic_transfer(1e-3, 1e-3, 1e-12, std::nan(""), 0.1, 0.1), std::invalid_argument);
	EXPECT_THROW(parabolic_transfer(1e-3, 1e-3, 1e-12, 1.0, 0.1, 0.1), std::runtime_error); // far beyond any bridge
}

// The exact transfer table against the solver away from the nodes (between nodes in every axis), and
// its limits: equal spheres split in halves; the rule of an exchanged pair is 1 - T1.
TEST(Transfer, ExactTableAgainstSolver)
{
	struct Row {
		double R1, R2, vstar, theta;
	};
	double worst = 0;
	for (const Row& r : { Row { 1e-3, 1e-3, 3e-4, 0.2 }, Row { 1e-3, 2.7e-3, 2e-3, 0.05 }, Row { 3.1e-3, 1e-3, 4e-5, 0.61 }, Row { 1e-3, 1.3e-3, 0.07, 0.4 },
	                      Row { 1e-3, inf, 5e-4, 0.3 }, Row { 2e-3, inf, 0.02, 0.0 }, Row { 1e-3, 3.9e-3, 1.5e-5, 0.8 }, Row { 1e-3, 2e-3, 0.4, 1.1 },
	                      Row { 1e-3, inf, 0.3, 1.2 } }) {
		const double Rh = is_wall(r.R2) ? 2 * r.R1 : harmonic_mean_radius(r.R1, r.R2), V = r.vstar * Rh * Rh * Rh;
		const yl::Bridge   b(r.R1, r.R2, V, r.theta);
		const yl::Solution s = b.solve(b.rupture_gap(), 0.07);
		const double       exact = s.volume1 / s.volume, table = exact_transfer(r.R1, r.R2, V, r.theta, r.theta);
		worst = std::max(worst, std::abs(table - exact));
		EXPECT_NEAR(table, exact, 5e-3) << r.R1 << " " << r.R2 << " " << r.vstar << " " << r.theta; // measured 1.6e-3
		if (!is_wall(r.R2) && r.R1 != r.R2) EXPECT_NEAR(exact_transfer(r.R2, r.R1, V, r.theta, r.theta), 1 - table, 1e-15);
		if (r.R1 == r.R2) EXPECT_EQ(table, 0.5); // a symmetric bridge
	}
	std::printf("exact transfer table: largest deviation from the solver %.2e\n", worst);
	// Elskamp2018 Fig. 7 trends: the larger sphere gets more, and more so as V* rises.
	const double R = 1e-3, Rh = harmonic_mean_radius(R, 2 * R);
	double       last = 1;
	for (double vstar : { 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.5 }) {
		const double small = exact_transfer(R, 2 * R, vstar * Rh * Rh * Rh, 0.3, 0.3);
		EXPECT_LT(small, 0.5);
		EXPECT_LT(small, last);
		last = small;
	}
	// Unequal angles (Elskamp's glass 15 deg on steel 45 deg) against the solver, in both orders: within
	// 1e-3 (measured 1.1e-4; near the ridge of the rupture, where the share varies like cbrt(theta_l - c),
	// the table's worst is 9.3e-3, docs/models.md).
	for (double vstar : { 1e-4, 0.12, 0.45 }) {
		const double       R1 = 1e-3, R2 = 1.5e-3, t1 = 15 * pi / 180, t2 = 45 * pi / 180, V = vstar * std::pow(harmonic_mean_radius(R1, R2), 3);
		const yl::Bridge   b(R1, R2, V, t1, t2, 1e-10);
		const yl::Solution s = b.solve(b.rupture_gap(), 0.07);
		EXPECT_NEAR(exact_transfer(R1, R2, V, t1, t2), s.volume1 / s.volume, 1e-3) << vstar;
		EXPECT_NEAR(exact_transfer(R2, R1, V, t2, t1), s.volume2 / s.volume, 1e-3) << vstar;
	}
	EXPECT_THROW(exact_transfer(1e-3, 1e-3, 1e-11, 0.2, 1.3), std::invalid_argument); // 74 deg > 70 deg (V* = 0.01)
	EXPECT_THROW(exact_transfer(1e-3, 1e-3, 0.6e-9, 0.2, 0.2), std::invalid_argument); // V* = 0.6 > 0.5
	EXPECT_THROW(transfer_from_name("half"), std::invalid_argument);
	EXPECT_EQ(transfer_ratio(Transfer::diameter, 1e-3, 3e-3, 1e-12, 1e-4, 0, 0), 0.25);
}
