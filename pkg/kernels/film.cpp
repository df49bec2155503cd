// Shi & McCarthy's bridge volumes and the film thickness (Elskamp2018 eq. 7-10, 34); see film.hpp.
#include "film.hpp"

#include <cmath>

namespace capillary {

namespace {
	void check_film(double L)
	{
		if (!(L >= 0 && std::isfinite(L))) out_of_range("film", L, "[0, inf)", "m^3");
	}
	// 1 - sqrt(1 - x2) without cancellation for small x2 = (R_j/(R_i + R_j))^2.
	double one_minus_root(double x2) { return x2 / (1 + std::sqrt(1 - x2)); }
} // namespace

double film_contribution(double Ri, double Rj, double L)
{
	check_radii(Ri, Rj);
	check_film(L);
	if (is_wall(Rj)) return L / 2 * one_minus_root(0.25); // eq. (9): 1 - sqrt(0.75)
	const double x = Rj / (Ri + Rj);
	return L / 2 * one_minus_root(x * x); // eq. (8)
}

double wall_film_contribution(double Ri, double W)
{
	check_radii(Ri, Ri);
	if (!(W >= 0 && std::isfinite(W))) out_of_range("W", W, "[0, inf)", "m");
	return W * pi / 4 * Ri * Ri; // eq. (10)
}

double film_thickness(double R, double L)
{
	check_radii(R, R);
	check_film(L);
	// (3L/(4 pi) + R^3)^(1/3) - R = R ((1 + q)^(1/3) - 1), q = 3L/(4 pi R^3); expm1/log1p keep thin films exact.
	return R * std::expm1(std::log1p(3 * L / (4 * pi * R * R * R)) / 3);
}

} // namespace capillary
