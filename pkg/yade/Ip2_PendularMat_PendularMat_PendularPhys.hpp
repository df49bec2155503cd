// Ip2_PendularMat_PendularMat_PendularPhys: the PendularPhys of two PendularMat bodies (contact
// parameters and bridge), with the input errors and critical time steps it hands to PendularCheck.
#pragma once

#include "PendularMat.hpp"
#include "PendularPhys.hpp"
#include "YadeHeaders.hpp"

#include <pkg/common/MatchMaker.hpp>

#include <array>
#include <limits>
#include <mutex>
#include <string>

namespace yade {

class Ip2_PendularMat_PendularMat_PendularPhys : public IPhysFunctor {
public:
	void go(const shared_ptr<Material>& m1, const shared_ptr<Material>& m2, const shared_ptr<Interaction>& I) override;
	// Two-body critical time step [s] of bodies id1 and id2 of the current scene, whatever their distance.
	Real criticalDt(Body::id_t id1, Body::id_t id2);
	// For PendularCheck, in serial code: the first input error met in the current step of `scene`
	// ("" if none; an error of an earlier step or another scene is dropped), and the smallest
	// critical time step of the interactions created since the last call (inf if none).
	std::string takeError(Scene* scene);
	struct PairDt {
		Real       dt = std::numeric_limits<Real>::infinity();
		Body::id_t id1 = -1, id2 = -1; // the pair that has it (-1 if none)
	};
	PairDt takeCriticalDt();
	FUNCTOR2D(PendularMat, PendularMat);
	DECLARE_LOGGER;
	// Sets the contact parameters of every real interaction of the current scene again from its materials
	// (and the pair tables); returns how many. Python: updateContacts.
	long updateContacts();
	// Checks the values of the pair tables (frictionAngle, rollingFriction, en) when one is assigned.
	void postLoad(Ip2_PendularMat_PendularMat_PendularPhys&);

private:
	void setContact(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void setLiquid(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void setFilm(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void setBonds(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void report(const std::string& message, const Interaction& I);
	// Written from InteractionLoop's OpenMP threads, hence the locks.
	std::mutex  errorMutex, dtMutex;
	bool        errorPending = false;
	std::string error;
	Scene*      errorScene       = nullptr;
	long        errorIter        = -1;
	long        stopAtIterBefore = 0;
	PairDt      newCriticalDt;
	// The pair tables after the last successful check (postLoad).
	std::array<shared_ptr<MatchMaker>, 3> goodTables;

public:
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(Ip2_PendularMat_PendularMat_PendularPhys, IPhysFunctor,
		"Creates :yref:`PendularPhys` from two :yref:`PendularMat`. Mixing rules: tc, en, et arithmetic means; kn, cn, ks, cs "
		"in series; friction angle the smaller; rolling friction the arithmetic mean; the pair tables frictionAngle, "
		"rollingFriction and en override them for the pairs of materials they list; Vb and gamma arithmetic means; "
		"contact angles kept per body; model, rupture rule, "
		"forceInContact and linear parameters must be equal (else an error). Effective mass m1 m2/(m1+m2), where a body that is "
		"not dynamic counts as infinitely heavy (unless neither is dynamic). A body whose shape is not a Sphere (wall, facet) "
		"is a plane for the bridge. Input errors are raised by :yref:`PendularCheck`: if only the liquid is wrong, the pair "
		"gets the contact law without a bridge; if the contact parameters are wrong, the interaction is reset and the error "
		"comes again at every step.",
		((shared_ptr<MatchMaker>, frictionAngle, , Attr::triggerPostLoad, "Contact friction angle per pair of materials [rad], [0, pi/2): a :yref:`MatchMaker` whose matches (id1, id2, value) list pairs of material ids (Elskamp2018 Table 3); a pair it does not list takes the smaller of the two materials' frictionAngle (the MatchMaker's algo is not used). None (the default): the rule for every pair."))
		((shared_ptr<MatchMaker>, rollingFriction, , Attr::triggerPostLoad, "Rolling friction mu_roll per pair of materials [m], [0, inf): a :yref:`MatchMaker` as frictionAngle; a pair it does not list takes the arithmetic mean of the materials' rollingFriction."))
		((shared_ptr<MatchMaker>, en, , Attr::triggerPostLoad, "Normal restitution coefficient per pair of materials [-], (exp(-2), 1] ((exp(-1), 1] with normalDamping='approach'): a :yref:`MatchMaker` as frictionAngle, for materials given by tc, en, et; a pair it does not list takes the arithmetic mean of the materials' en.")),
		/*ctor*/,
		.def("criticalDt", &Ip2_PendularMat_PendularMat_PendularPhys::criticalDt, (boost::python::arg("id1"), boost::python::arg("id2")),
		     "Two-body critical time step [s] of bodies id1 and id2 of the current scene (their contact parameters and masses, "
		     "whatever their distance): the stability limit of YADE's leapfrog for the normal and the tangential spring-dashpot, "
		     "dt_c = (2/w0)(sqrt(1+z^2) - z), w0^2 = k/m, z = c/(2 sqrt(k m)); tangential mass 1/(1/m + r^2/I) per dynamic sphere. "
		     "See yade_capillary.scene.stable_dt.")
		.def("updateContacts", &Ip2_PendularMat_PendularMat_PendularPhys::updateContacts,
		     "Set the contact parameters (kn, cn, ks, cs, friction, rolling friction, normalDamping, friction law) of every existing "
		     "interaction of two PendularMat bodies of the current scene again from their materials and the pair tables, as for a new "
		     "interaction, e.g. after changing PendularMat.frictionAngle (Richefeu2008 section 3.2.1: consolidated without friction, then "
		     "mu = 0.4); the liquid bridges and the tangential forces stay. Returns the number of interactions updated. Not while the "
		     "simulation runs; ValueError if a pair's parameters are refused (none is changed then).")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(Ip2_PendularMat_PendularMat_PendularPhys);

} // namespace yade
