// bonds: the sharing of Richefeu2008's eq. 13-14 with the eligibility rule (iii); see bonds.hpp.
#include "bonds.hpp"

#include "conventions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace capillary {
namespace bonds {

	double cube(double R1, double R2)
	{
		double r1, r2;
		equivalent_pair(R1, R2, r1, r2);
		const double R = std::sqrt(r1 * r2);
		return R * R * R;
	}

	double threshold(Rupture rule, double R1, double R2, double gap, double theta1, double theta2)
	{
		if (!(gap > 0)) return 0;
		const double c = cube(R1, R2);
		double       r1, r2;
		equivalent_pair(R1, R2, r1, r2);
		const double Rh = harmonic_mean_radius(r1, r2);
		if (rule == Rupture::lian) {
			// (1 + theta/2) V^(1/3) (Richefeu2008 eq. 6): reach alpha R^3 where (gap / reach(V0))^3 = alpha R^3 / V0.
			const double V0 = 1e-3 * Rh * Rh * Rh;
			const double x  = gap / rupture_distance(rule, R1, R2, V0, theta1, theta2);
			return x * x * x * V0 / c;
		}
		// The other rules grow with the volume: bisection in ln V over the plausible volumes (V* <= 1 of the
		// harmonic mean radius, conventions.hpp).
		// (1e-12 inside the ends: exp(ln V) rounds.)
		double     lo = std::log(Plausible::vstar_min * Rh * Rh * Rh) + 1e-12, hi = std::log(Plausible::vstar_max * Rh * Rh * Rh) - 1e-12;
		const auto reaches = [&](double lnv) { return rupture_distance(rule, R1, R2, std::exp(lnv), theta1, theta2) >= gap; };
		if (!reaches(hi)) return std::numeric_limits<double>::infinity();
		if (reaches(lo)) return std::exp(lo) / c;
		for (int i = 0; i < 200 && hi - lo > 1e-14; ++i) {
			const double mid = 0.5 * (lo + hi);
			(reaches(mid) ? hi : lo) = mid;
		}
		return std::exp(hi) / c;
	}

	Sharing share(const std::vector<double>& threshold, const std::vector<double>& cube, double liquid)
	{
		if (!(liquid > 0 && std::isfinite(liquid))) out_of_range("liquid", liquid, "(0, inf)", "m^3");
		if (threshold.size() != cube.size()) throw std::invalid_argument("bonds::share: threshold and cube differ in length");
		std::vector<std::size_t> order(threshold.size());
		std::iota(order.begin(), order.end(), 0);
		std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return threshold[a] < threshold[b]; });
		// Greedy in order of threshold: a candidate joins if alpha, with its share, stays at or above its
		// threshold. alpha only falls as bonds join, but never below the threshold of a member (each later
		// member's threshold is larger and alpha stays above it), so the set stays consistent; a candidate
		// left out stays out (alpha only falls). Beyond alpha's current value no threshold can be met.
		Sharing     out;
		out.bonded.assign(threshold.size(), 0);
		double      sum = 0;
		std::size_t k   = 0;
		for (const std::size_t n : order) {
			if (sum > 0 && threshold[n] > liquid / sum) break;
			if (liquid / (sum + cube[n]) >= threshold[n]) {
				sum += cube[n];
				out.bonded[n] = 1;
				++k;
			}
		}
		if (k == 0)
			throw std::invalid_argument("bonds::share: liquid = " + format_value(liquid) + " m^3 reaches no pair (" + std::to_string(threshold.size())
			                            + " candidates, none in contact or within the debonding distance of a bond holding all of it)");
		out.alpha = liquid / sum;
		out.count = k;
		return out;
	}

	bool kept_dry(std::uint64_t id1, std::uint64_t id2, double fraction, std::uint64_t seed)
	{
		if (!(fraction >= 0 && fraction <= 1)) out_of_range("dry fraction", fraction, "[0, 1]", "");
		// splitmix64 of the ordered pair and the seed: a uniform number in [0, 1).
		std::uint64_t z = std::min(id1, id2) * 0x9E3779B97F4A7C15ULL ^ (std::max(id1, id2) + 0x632BE59BD9B4E019ULL) ^ (seed * 0xBF58476D1CE4E5B9ULL);
		z               = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
		z               = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
		z ^= z >> 31;
		return double(z >> 11) * 0x1.0p-53 < fraction;
	}

} // namespace bonds
} // namespace capillary
