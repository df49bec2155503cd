// Liquid carried by the particles (Elskamp2018 section 2.2.1, after Shi & McCarthy 2008): the volume a
// new bridge takes from the films of its two solids, and the film thickness that decides when two
// films touch. SI units, no YADE types.
//
// A particle's liquid L is a film spread evenly over its surface. A bridge takes from each sphere the
// liquid on the spherical cap cut off where the two spheres' "immersion" discs meet (eq. 7): cap
// height d_i = R_i (1 - sqrt(1 - R_j^2/(R_i + R_j)^2)), cap area 2 pi R_i d_i, hence eq. (8). Against a
// (large) wall the sphere gives as to a sphere of its own size (eq. 9) and the wall the film of
// thickness W on the projection pi/4 R_i^2 of that cap (eq. 10). Elskamp's "small walls" (screen
// wires, eq. 11-13) are not modelled: walls and facets are large walls.
#pragma once

#include "conventions.hpp"

namespace capillary {

// Elskamp2018 eq. (8) (eq. 9 for R_j = wall_radius): the liquid [m^3] a sphere of radius Ri [m] with
// the film L [m^3] gives to a bridge with a solid of radius Rj [m].
double film_contribution(double Ri, double Rj, double L);
// Elskamp2018 eq. (10): the liquid [m^3] a wall with the film thickness W [m] gives to a bridge with
// a sphere of radius Ri [m].
double wall_film_contribution(double Ri, double W);
// Elskamp2018 eq. (34): the thickness [m] of the film L [m^3] spread over a sphere of radius R [m],
// (3 L/(4 pi) + R^3)^(1/3) - R.
double film_thickness(double R, double L);

} // namespace capillary
