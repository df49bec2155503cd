// How the liquid of a breaking bridge is shared by its two solids: the transfer ratio T1 = V1/V,
// V1 the liquid that goes to solid 1 (Elskamp2018 section 2.2.4). SI units, radians, no YADE types.
//
//   parabolic_transfer  Elskamp2018 eq. (35)-(43): the meniscus at rupture approximated by a parabola
//                       Y(x) = a x^2 + b x + c between the contact-line planes (x = 0 on solid 1,
//                       x = d_lb on solid 2), through the contact lines (eq. 36-38), meeting each solid
//                       at its contact angle (eq. 39-40) and holding the volume (eq. 41); the bridge
//                       breaks at the narrowest section x_min = -b/(2a) and V1 is the liquid left of it
//                       (eq. 42).
//   diameter_transfer   Richefeu2008: in proportion to the diameters, T1 = R1/(R1 + R2) (a wall, which
//                       has no diameter, gets nothing).
//   exact_transfer      the Young-Laplace solver's split at the neck at the exact rupture gap
//                       (yl::Solution::volume1 / volume there), a column of young_laplace_table
//                       (young_laplace_table.hpp), interpolated like its forces.
//
// Deviations from the printed equations: eq. (40) is printed with + atan(y'(d_lb)); the mirror image
// of eq. (39) for the solid on the right is theta_j = pi/2 - atan(Y'(d_lb)) - asin(y(d_lb)/r_j) (with
// the printed sign a symmetric bridge could not meet equal angles on equal spheres), and eq. (43)'s
// cap is that of solid 2, pi/6 (3 y(d_lb)^2 d_j + d_j^3) (printed with b and y(0)). A wall is a
// plane at x = d_lb without a cap, where the meniscus meets it at theta_w = pi/2 - atan(Y'(d_lb))
// (the limit r_j -> inf of the corrected eq. 40).
#pragma once

#include "conventions.hpp"

#include <array>
#include <string>

namespace capillary {

struct ParabolicBridge {
	double a = 0, b = 0, c = 0; // Y(x) = a x^2 + b x + c [1/m, -, m]
	double d1 = 0, d2 = 0;      // cap heights of the solids beyond their contact-line planes [m] (0 for a wall)
	double length = 0;          // d_lb: distance of the contact-line planes [m], d1 + d2 + S
	double x_min = 0;           // narrowest section [m]
	double volume1 = 0;         // liquid left of x_min, on solid 1's side [m^3]
	double transfer1 = 0;       // volume1 / volume [-]
};

// The parabolic bridge of volume V [m^3] between sphere R1 and sphere R2 (R2 = wall_radius: a plane)
// at the surface separation S [m] (the rupture distance), contact angles theta1, theta2 [rad].
// Throws std::invalid_argument for input outside the Plausible ranges and std::runtime_error if no
// parabola meets the conditions (e.g. S far beyond any rupture distance).
ParabolicBridge parabolic_transfer(double R1, double R2, double volume, double S, double theta1, double theta2);

// Richefeu2008: T1 = R1/(R1 + R2), 1 against a wall.
double diameter_transfer(double R1, double R2);

// The exact T1 of a bridge of volume V [m^3] between R1 and R2 (R2 = wall_radius: a plane) with equal
// contact angles theta1 = theta2 [rad], at its exact rupture. Throws std::invalid_argument outside the
// table (V* = V/Rh^3 in [1e-5, 0.1], theta <= 50 deg, R_small/R_large >= 1/4 or a plane).
double exact_transfer(double R1, double R2, double volume, double theta1, double theta2);

// The rules, selected once by index (PendularMat.transfer).
enum class Transfer { exact, parabolic, diameter };
struct TransferInfo {
	Transfer    rule;
	const char* name;
	const char* source;
};
const std::array<TransferInfo, 3>& transfer_rules();
Transfer    transfer_from_name(const std::string& name); // std::invalid_argument listing the names
std::string transfer_names();
// T1 of the rule for a bridge of volume V [m^3] whose rupture distance is S [m] (parabolic: the
// parabola at S; exact: the exact rupture, S unused; diameter: neither).
double transfer_ratio(Transfer rule, double R1, double R2, double volume, double S, double theta1, double theta2);

} // namespace capillary
