// bonds: the liquid shared over bonds of Richefeu2008 (section 2.4): the total liquid V_l = sum V_b
// (eq. 13) goes to every eligible pair, V_b = alpha R^3 with R = sqrt(R1 R2) (eq. 14; a wall counts as the
// Derjaguin pair of radius 2 R1, conventions.hpp), and a pair is eligible when its gap is within the
// debonding distance of its own bond (rule iii). alpha and the set of bonds fix each other; share()
// finds them. Pure: SI units, no YADE types.
#pragma once

#include "models.hpp"

#include <cstdint>
#include <vector>

namespace capillary {
namespace bonds {

	// R^3 of a pair, R = sqrt(r1 r2) of the Derjaguin-equivalent pair [m^3].
	double cube(double R1, double R2);
	// The least alpha at which a pair at surface gap `gap` [m] is within the debonding distance of
	// the rupture rule for V_b = alpha R^3: 0 in contact (gap <= 0), (gap / ((1 + theta/2) R))^3 for
	// lian (Richefeu2008 eq. 6), by bisection for the other rules (their distance grows with the volume);
	// inf if no plausible volume reaches the gap.
	double threshold(Rupture rule, double R1, double R2, double gap, double theta1, double theta2);

	struct Sharing {
		double            alpha = 0; // V_b / R^3 [-]
		std::vector<char> bonded;    // per candidate: 1 if it holds a bond
		std::size_t       count = 0; // bonds
	};
	// Shares `liquid` [m^3] over the candidates (threshold and cube of each): in order of threshold, a
	// candidate becomes a bond if alpha = liquid / sum R^3 over the bonds, its own share included, stays at
	// or above its threshold. So sum V_b = liquid exactly (up to rounding), every bond is within its
	// debonding distance, and no candidate left dry could join alone: one within reach at the final alpha
	// stays dry only if its own share would pull alpha below its threshold (the paper leaves that case open).
	// Throws std::invalid_argument naming `liquid` if it is not > 0 and finite, or if no candidate can hold it.
	Sharing share(const std::vector<double>& threshold, const std::vector<double>& cube, double liquid);

	// Whether the pair (id1, id2) is kept dry for a dry fraction in [0, 1] and a seed: a hash of the
	// unordered pair and the seed, so the same pairs stay dry at every redistribution and in any order.
	bool kept_dry(std::uint64_t id1, std::uint64_t id2, double fraction, std::uint64_t seed);

} // namespace bonds
} // namespace capillary
