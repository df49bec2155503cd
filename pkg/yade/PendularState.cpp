// PendularState: the checks of a body's film and its thickness.
#include "PendularState.hpp"
#include "film.hpp"
#include "conventions.hpp"

#include <string>

namespace yade {

YADE_PLUGIN((PendularState));

void PendularState::postLoad(PendularState&)
{
	const auto refuseRange = [this](const char* name, Real value, const std::string& range, const char* unit) {
		restore(lastGood);
		capillary::out_of_range(std::string("PendularState.") + name, value, range, unit);
	};
	// Plausible: at most the volume of a body of the largest plausible radius (1 km), and a wettable
	// area of at least a square nanometre, so that the film thickness film/filmArea stays finite.
	const Real rmin = capillary::Plausible::radius_min, rmax = capillary::Plausible::radius_max;
	if (!(film >= 0 && film <= rmax * rmax * rmax)) refuseRange("film", film, "[0, " + capillary::format_value(rmax * rmax * rmax) + "]", "m^3");
	if (!(filmArea == 0 || (filmArea >= rmin * rmin && filmArea <= rmax * rmax)))
		refuseRange("filmArea", filmArea, "0 (holds no film) or [" + capillary::format_value(rmin * rmin) + ", " + capillary::format_value(rmax * rmax) + "]", "m^2");
	lastGood = checked();
}

Real PendularState::thickness(Real R) const
{
	if (!math::isinf(R)) return capillary::film_thickness(R, film);
	return filmArea > 0 ? film / filmArea : 0;
}

} // namespace yade
