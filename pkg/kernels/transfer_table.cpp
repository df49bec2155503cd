// The exact transfer ratio at rupture, from young_laplace_table's transfer column (see transfer.hpp).
#include "transfer.hpp"
#include "young_laplace_table.hpp"

#include <cmath>

namespace capillary {

double exact_transfer(double R1, double R2, double volume, double theta1, double theta2)
{
	check_radii(R1, R2);
	if (!(volume > 0 && std::isfinite(volume))) out_of_range("volume", volume, "(0, inf)", "m^3");
	const double T1 = yltable::transfer1(R1, R2, volume, theta1, theta2, "exact transfer table"); // checks the domain
	// Equal spheres with equal angles: a symmetric bridge splits in halves. The table sits on the ridge
	// of the rupture there, where the share varies like cbrt(theta2 - theta1) and is interpolated least well.
	if (R1 == R2 && theta1 == theta2) return 0.5;
	return T1;
}

} // namespace capillary
