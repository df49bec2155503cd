// PendularState: the state of a body of a PendularMat, which carries the body's liquid film
// (PendularMat.liquid = 'film').
#pragma once

#include "AttrSnapshot.hpp"
#include "YadeHeaders.hpp"

namespace yade {

// Every body of a PendularMat gets this state (PendularMat.newAssocState, used by utils.sphere,
// utils.wall, utils.facet, ...).
// clang-format off
#define PENDULAR_STATE_ATTRS \
	((Real, film, 0, Attr::triggerPostLoad, "Free liquid on the body [m^3], [0, 1e9] (at most a body of 1 km): the film, not counting the liquid in its bridges. Only with PendularMat.liquid = 'film' or 'bonds' (an error at the first interaction otherwise). Written by the bridges at the end of each step (PendularCheck, PendularBonds).")) \
	((Real, filmArea, 0, Attr::triggerPostLoad, "Walls and facets: the wettable area [m^2], 0 or [1e-18, 1e6], over which their film spreads (film thickness W = film/filmArea, Elskamp2018 eq. 10). 0 (the default): the wall holds no liquid, gives none to a bridge and, at rupture, leaves the whole bridge to the sphere. Unused on spheres."))
// clang-format on

class PendularState : public State {
	PENDULAR_ATTR_SNAPSHOT(PENDULAR_STATE_ATTRS)
	Checked lastGood; // the values after the last successful check (a rejected assignment is rolled back)

public:
	void postLoad(PendularState&);
	// The film thickness [m]: Elskamp2018 eq. (34) on a sphere of radius R, film/filmArea on a wall or
	// facet (R = inf), 0 on a wall that holds no film.
	Real thickness(Real R) const;
	// A wall or facet holds liquid only on a wettable area; a sphere always does.
	bool holds(Real R) const { return !math::isinf(R) || filmArea > 0; }
	virtual ~PendularState() = default;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR(PendularState, State,
		"State of a body of a :yref:`PendularMat`: the liquid it carries when the material's ``liquid`` is ``'film'`` "
		"(Elskamp2018 section 2.2.1). New bridges take their liquid from the films of both bodies (Shi & McCarthy, "
		"Elskamp2018 eq. 7-10); a breaking bridge gives it back by the transfer ratio (PendularMat.transfer).",
		PENDULAR_STATE_ATTRS,
		createIndex(); lastGood = checked();
	);
	// clang-format on
	REGISTER_CLASS_INDEX(PendularState, State);
};
REGISTER_SERIALIZABLE(PendularState);
#undef PENDULAR_STATE_ATTRS

namespace pendular {
	// The state of body `id` of `scene`, a body of a PendularMat.
	inline PendularState& filmOf(Scene* scene, Body::id_t id) { return static_cast<PendularState&>(*Body::byId(id, scene)->state); }
} // namespace pendular

} // namespace yade
