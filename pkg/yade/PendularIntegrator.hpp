// PendularIntegrator: YADE's NewtonIntegrator step for scenes of standalone spherical bodies, with the
// bodies' objects prefetched ahead and, per body, no calls but the force container's; any other scene is
// handed to the NewtonIntegrator itself.
#pragma once

#include "Passes.hpp"
#include "YadeHeaders.hpp"

#include <core/GlobalEngine.hpp>

#include <boost/weak_ptr.hpp>
#include <algorithm>
#include <atomic>

namespace yade {

class PendularIntegrator : public GlobalEngine {
public:
	void action() override;
	// Reads the NewtonIntegrator's parameters now, in the calling thread (Python: before O.run, so that the
	// simulation thread need not take the GIL); does nothing if there is no NewtonIntegrator before it.
	void refresh();
	// Called when a NewtonIntegrator's attribute changed (Python: its setters, wrapped by yade_capillary).
	static void newtonChanged() { ++newtonVersion; }
	DECLARE_LOGGER;

private:
	// NewtonIntegrator's parameters, read through its Python attributes (the plugin is compiled
	// against other YADE headers than the installed YADE's: only the base Engine's members are read
	// in C++).
	struct Parameters {
		Real     damping = 0;
		Vector3r gravity = Vector3r::Zero();
		bool     dampGravity = true, exactAsphericalRot = true;
		int      mask = -1;
	};
	void               findNewton(); // into newton and loop
	Parameters         parameters() const; // of the NewtonIntegrator findNewton found (takes the GIL)
	long               probeFlag() const;  // see flagOffset
	// The NewtonIntegrator's parameters and where its maxVelocitySq is, read through Python (with the GIL)
	// by refresh() when they may have changed: another NewtonIntegrator, or newtonVersion moved on.
	// Reading them at every step made the simulation thread take the GIL at every step, and YADE's
	// O.reset() (O.load, ...) holds the GIL while it waits for the step in progress to end: a step
	// waiting for the GIL then never ends (a hang seen in test_film after O.pause(); O.wait(); O.reset()).
	Parameters          cached;
	const Engine*       cachedNewton  = nullptr;
	long                cachedVersion = -1;
	// Byte offset of NewtonIntegrator::maxVelocitySq in the installed YADE's object, found by probeFlag
	// (-1: not found; the flag is then written through Python, with the GIL, at every step).
	long                flagOffset = -1;
	static std::atomic<long> newtonVersion; // moved on by yade_capillary's setters of NewtonIntegrator's attributes
	// Why this step cannot be done here ("" if it can); fatal: a scene the engine order makes wrong.
	std::string unsupported(const Parameters& p, int threads, bool& fatal);
	// NewtonIntegrator's maxVelocitySq after the step of the bodies in `bodies` (filled by unsupported).
	Real integrate(const Parameters& p, const pendular::BodyPointers& bodies, int threads);
	// What findNewton found in the engine list it last scanned: the NewtonIntegrator; the PendularLoop before
	// it if every engine between them is known to leave the bodies' objects and flags alone (see unsupported).
	std::vector<boost::weak_ptr<Engine>> scannedEngines;
	shared_ptr<Engine>                   newton;
	shared_ptr<Engine>                   loop;
	bool                                 stiffnessTimeStepper = false;
	pendular::BodyPointers               ownPointers; // when the loop's cannot be used
	const pendular::BodyPointers*        bodies = nullptr; // of this step: the loop's or ownPointers

public:
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularIntegrator, GlobalEngine,
		"The step of the :yref:`NewtonIntegrator` that precedes it in O.engines (which must be dead: dead=True), for scenes of "
		"standalone bodies (no clumps) with spherical inertia: the same leapfrog, Cundall damping, gravity, blocked degrees of "
		"freedom and the same flag for the collider (NewtonIntegrator.maxVelocitySq, written back into it), in the same order "
		"of operations, so that the positions and velocities are those of NewtonIntegrator bit for bit, without its "
		"per-body function calls and with each body's State and Bound prefetched ahead (at the scale of Gladkyy 2014's "
		"cell these objects do not fit in the caches, and NewtonIntegrator waits on them in turn). Each Body is read once per "
		"step: the State and Bound pointers and the check for clumps come from the gathering of the :yref:`PendularLoop` before "
		"it when the engines between them are only PendularCheck, RotationEngine, PendularRotationEngine, TranslationEngine and the NewtonIntegrator, "
		"else from a pass of its own. Its parameters are read "
		"from the NewtonIntegrator (through Python, before O.run and after any of its damping, gravity, dampGravity, "
		"exactAsphericalRot or mask is set; see refresh), so that the NewtonIntegrator stays the one place to set gravity and damping. "
		"Any other scene (clumps, aspherical bodies with exactAsphericalRot, a periodic cell, energy tracking, density scaling, "
		"a mask) is handed to the NewtonIntegrator's own step (see nHandedOver). yade.mpy is not supported: it inserts its "
		"communication engines next to NewtonIntegrator (build the engines with yade_capillary.scene.engines(integrator='newton')).",
		((long, nIntegrated, 0, Attr::readonly, "Bodies integrated by this engine's own pass in the last step [-] (0 when the step was handed to the NewtonIntegrator)."))
		((long, nHandedOver, 0, Attr::readonly, "Steps handed to the NewtonIntegrator's own step since the engine was made [-] (see handedOverBecause)."))
		((std::string, handedOverBecause, "", Attr::readonly, "Why the last step handed to the NewtonIntegrator was [-]."))
		((bool, fromLoop, false, Attr::readonly, "Whether the last step took the bodies' State and Bound objects and the check for clumps, aspherical bodies and subdomains from the gathering of the PendularLoop before it [-] (false: from a pass over the bodies of its own, as when an engine between them may change the bodies, e.g. a PyRunner)."))
		((long, parallelBodies, 1000, , "From this many bodies on, the per-body phases (the integration) run on ompThreads threads, below it on one [-]: a parallel region costs more than a short pass (./run.sh bench compares 1000, the default, with 20000, the earlier one, on the ci cell: on two threads its 2 200 bodies gain 8-11 %)."))
		((Real, bodiesTime, 0, , "Wall time spent in the pass over the bodies since this was last set to 0 [ns].")),
		/*ctor*/,
		/*py*/
		.def("refresh", &PendularIntegrator::refresh, "Read the parameters of the NewtonIntegrator before it now (yade_capillary calls this before O.run; see newtonChanged).")
		.def("newtonChanged", &PendularIntegrator::newtonChanged, "Note that a NewtonIntegrator's attribute changed: its parameters are read again at the next step (yade_capillary's setters call this).").staticmethod("newtonChanged")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularIntegrator);

} // namespace yade
