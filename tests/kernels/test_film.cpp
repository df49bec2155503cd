// Liquid carried by the particles: Shi & McCarthy's bridge volumes (Elskamp2018 eq. 8-10) and the film
// thickness (eq. 34) against a literal evaluation of the printed formulas, and their limits.
#include "film.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace capillary;

namespace {
const double inf = std::numeric_limits<double>::infinity();
}

TEST(Film, ShiMcCarthyAsPrinted)
{
	// eq. (8), term of particle i, written as printed: L_i/2 (1 - sqrt(1 - r_j^2/(r_i + r_j)^2)).
	struct Row {
		double Ri, Rj, L;
	};
	for (const Row& r : { Row { 1e-3, 1e-3, 1e-10 }, Row { 1e-3, 2.5e-3, 3e-11 }, Row { 4e-3, 1e-3, 7e-9 }, Row { 2e-6, 5e-5, 1e-18 } }) {
		const double printed = r.L / 2 * (1 - std::sqrt(1 - r.Rj * r.Rj / ((r.Ri + r.Rj) * (r.Ri + r.Rj))));
		EXPECT_NEAR(film_contribution(r.Ri, r.Rj, r.L), printed, 1e-13 * printed) << r.Ri << " " << r.Rj;
		// eq. (7): the same as the liquid on the cap of height d_i, L d_i/(2 R_i).
		const double d = r.Ri - std::sqrt(r.Ri * r.Ri - std::pow(r.Ri * r.Rj / (r.Ri + r.Rj), 2));
		EXPECT_NEAR(film_contribution(r.Ri, r.Rj, r.L), r.L * d / (2 * r.Ri), 1e-9 * printed);
	}
	// Equal spheres give (1 - sqrt(0.75))/2 = 6.7 % of the film; a wall counts as a sphere of the same size (eq. 9).
	EXPECT_NEAR(film_contribution(1e-3, 1e-3, 1.0e-9) / 1.0e-9, (1 - std::sqrt(0.75)) / 2, 1e-15);
	EXPECT_DOUBLE_EQ(film_contribution(1e-3, inf, 1.0e-9), film_contribution(1e-3, 1e-3, 1.0e-9));
	// A tiny partner takes a tiny cap, without cancellation: (Rj/(Ri + Rj))^2 / 4 in the limit.
	EXPECT_NEAR(film_contribution(1.0, 1e-8, 1.0), 0.25e-16, 1e-7 * 0.25e-16); // x = 1e-8/(1 + 1e-8)
	EXPECT_EQ(film_contribution(1e-3, 1e-3, 0.0), 0.0);
}

TEST(Film, WallAndThickness)
{
	EXPECT_DOUBLE_EQ(wall_film_contribution(2e-3, 1e-6), 1e-6 * std::acos(-1.0) / 4 * 4e-6); // eq. (10)
	for (double R : { 1e-6, 1e-3, 1.0 })
		for (double vstar : { 1e-9, 1e-4, 0.3 }) {
			const double L = vstar * R * R * R;
			const double printed = std::cbrt(3 * L / (4 * std::acos(-1.0)) + R * R * R) - R; // eq. (34)
			EXPECT_NEAR(film_thickness(R, L), printed, 1e-9 * printed + 1e-15 * R) << R << " " << vstar;
			// A thin film: its volume over the sphere's area.
			if (vstar < 1e-6) EXPECT_NEAR(film_thickness(R, L), L / (4 * std::acos(-1.0) * R * R), 1e-6 * L / (R * R));
		}
}

TEST(Film, RefusedInput)
{
	for (double L : { -1e-12, std::nan(""), inf }) {
		EXPECT_THROW(film_contribution(1e-3, 1e-3, L), std::invalid_argument);
		EXPECT_THROW(film_thickness(1e-3, L), std::invalid_argument);
	}
	EXPECT_THROW(wall_film_contribution(1e-3, -1e-6), std::invalid_argument);
	EXPECT_THROW(film_contribution(-1e-3, 1e-3, 1e-9), std::invalid_argument);
	try {
		film_thickness(1e-3, -2e-12);
		FAIL();
	} catch (const std::invalid_argument& e) {
		EXPECT_NE(std::string(e.what()).find("film = -2e-12 m^3 is outside the allowed range [0, inf)"), std::string::npos) << e.what();
	}
}
