// PendularCheck: the engine after the interaction loop that raises the step's input errors, checks
// the time step and the overlaps, and settles the films of the step's bridges.
#pragma once

#include "PythonSide.hpp"
#include "YadeHeaders.hpp"
#include <core/GlobalEngine.hpp>

#include <limits>
#include <string>

namespace yade {

class Law2_ScGeom_PendularPhys_Bridge;

class PendularCheck : public GlobalEngine {
	Real warnedDt = NaN; // O.dt of the last warning
	// The overlap check's bound as last handed to the laws, and the body count it was computed for
	// (see Law2_ScGeom_PendularPhys_Bridge::overlapAlarm).
	Real   alarmBound  = NaN;
	size_t alarmBodies = 0;
	bool   overlapWarned = false;
	// Hands maxOverlap to `law` and takes what its contacts reported (see action()).
	void checkOverlaps(Law2_ScGeom_PendularPhys_Bridge& law, bool fresh);
	// The step's dt check: warns (again if newPair lowered the limit), or with adaptDt lowers O.dt;
	// returns an input error ("" if none).
	std::string checkDt(bool newPair);

public:
	void action() override;
	// Raises `message` from a step of `scene` as PendularCheck's errors are raised: a ValueError in
	// Python, also when YADE's wait() misses it, and under mpiexec the end of every rank.
	static void raiseInStep(Scene* scene, const std::string& message);
	DECLARE_LOGGER;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularCheck, GlobalEngine,
		"Raises (as a Python ValueError from O.step, O.run(n, True) and O.wait) the first input error that "
		":yref:`Ip2_PendularMat_PendularMat_PendularPhys` met while creating interactions in this step of this scene, e.g. two "
		"materials with different models or a bridge outside its model's domain, and warns (once per value of O.dt) when O.dt "
		"exceeds dtSafety times the smallest two-body critical time step of the interactions created so far. Place it right "
		"after the InteractionLoop (yade_capillary.scene.engines does). Without it, an input error stops the simulation at the "
		"end of the step and is logged. installGuards (called by yade_capillary.patches.install, which yade_capillary.scene.engines "
		"calls) wraps Omega.run and Omega.wait so that they raise the error also when it "
		"stopped the simulation thread before YADE's wait() looked (which then returns without it), and O.bodies.erase and clear, "
		"O.interactions.erase and clear to account for the liquid they remove; it warns at its first step when they are not wrapped. "
		"With liquid='film' it also forms the bridges asked for in the step and moves the liquid of broken bridges to the films "
		"(Law2_ScGeom_PendularPhys_Bridge.settleFilms).",
		((Real, dtSafety, 0.3, , "Warn when O.dt > dtSafety * criticalDt [-], (0, 1]. 0.3 ~ 1/sqrt(12): a sphere with 12 contacts can have a highest frequency up to sqrt(12) times that of one contact (Gershgorin's bound)."))
		((Real, criticalDt, std::numeric_limits<Real>::infinity(), Attr::readonly, "Smallest two-body critical time step of the interactions created so far [s] (see Ip2_PendularMat_PendularMat_PendularPhys.criticalDt: with the viscous forces of the pair's bridge, in film mode of the largest bridge it can form); inf before the first."))
		((Vector2i, criticalPair, Vector2i(-1, -1), Attr::readonly, "The two bodies of the interaction that has criticalDt [-]; (-1, -1) before the first."))
		((long, dtWarnings, 0, Attr::readonly, "Number of time-step warnings given [-]."))
		((bool, adaptDt, false, , "When O.dt exceeds dtSafety * criticalDt (a new pair, e.g. a viscous bridge of small spheres, has a smaller limit), lower O.dt to dtSafety * criticalDt and log it, instead of only warning [-]. Off by default: YADE users expect O.dt to change only when they change it. Refused under yade.mpy with several ranks (each rank would change its own O.dt)."))
		((long, dtAdaptations, 0, Attr::readonly, "Number of times adaptDt lowered O.dt [-]."))
		((Real, maxOverlap, 0.5, , "Warn (once, with the pair, the overlap, the estimated impact speed and a tc that would keep the overlap below this bound) when a contact's overlap exceeds maxOverlap times the smaller radius of the pair [-], (0, 2]. A contact given by tc overlaps about v tc / pi at impact speed v, so fast collisions of small spheres may overlap by more than their radius. Costs one comparison per contact-step. A change takes effect from the step after the next."))
		((long, nOverlaps, 0, Attr::readonly, "Number of contact-steps whose overlap exceeded maxOverlap times the pair's smaller radius [-] (pairs of two bodies that do not move are not counted)."))
		((Real, largestOverlap, 0, Attr::readonly, "Largest overlap counted in nOverlaps, divided by the pair's smaller radius [-]; 0 if none.")),
		/*ctor*/,
		.def("installGuards", &pendular::installGuards, "Wrap Omega.run, Omega.wait, O.bodies.erase and clear, O.interactions.erase and clear (once per process; see the class). yade_capillary.patches.install calls it.")
		.staticmethod("installGuards")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularCheck);

} // namespace yade
