// PendularForceResetter: YADE's ForceResetter with the force container zeroed by the threads that
// handed the forces over in the PendularLoop's last step, each its own part of the bodies.
#pragma once

#include "Passes.hpp"
#include "YadeHeaders.hpp"

#include <pkg/common/ForceResetter.hpp>

#include <boost/weak_ptr.hpp>

namespace yade {

class PendularLoop;

class PendularForceResetter : public ForceResetter {
public:
	void action() override;
	DECLARE_LOGGER;

private:
	// The PendularLoop of the engine list last scanned (see pendular::sameEngines).
	std::vector<boost::weak_ptr<Engine>> scannedEngines;
	shared_ptr<Engine>                   loop;
	// The loop follows this engine with only InsertionSortColliders between them (which neither read nor
	// add forces): its gathering can zero the forces (see PendularLoop::takeReset).
	bool                                 loopNext = false;
	// Why this step cannot be reset by parts ("" if it can); else size: the force container's, and summed:
	// its summed entries.
	std::string unsupported(const PendularLoop* l, long n, long& size, pendular::SummedArrays& summed);
	// Entries of the force container beyond the n bodies' that the reset by parts zeroes too.
	static constexpr long extraEntries = 8;

public:
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR(PendularForceResetter, ForceResetter,
		"YADE's :yref:`ForceResetter` (it is one: the same reset of the force container at the start of the step, and of the "
		"resettable energies when energy is tracked), with the container's summed forces and torques zeroed by the threads of "
		"the :yref:`PendularLoop` in O.engines, each the bodies whose forces it handed over in that loop's last step. When only "
		"InsertionSortColliders stand between this engine and the loop (as in yade_capillary.scene.engines), the loop zeroes them "
		"in the parallel region of its gathering, before anything reads or adds a force (a parallel region of its own took "
		"3-6 µs per step on two threads on the ci shear cell for 1 µs of zeroing; see nDeferred). "
		"ForceResetter zeroes them in one thread: on two threads, the cache lines of the second thread's bodies then moved to "
		"the first core and back at every step (measured on the validation shear cell: ForceResetter 31 µs per step on one "
		"thread, 193 on two). The numbers are those of ForceResetter: the same entries are set to zero. Steps it cannot do "
		"so are handed to ForceContainer::reset, which ForceResetter calls (see nHandedOver): no PendularLoop, permanent forces "
		"(O.forces.setPermF), forces added since the last sync (e.g. O.forces.addF after the integrator), a body container "
		"of another size than the force container's, or yade.mpy's redirected body lists.",
		((long, nDeferred, 0, Attr::readonly, "Steps whose zeroing the PendularLoop did in its gathering, since the engine was made [-]."))
		((long, nHandedOver, 0, Attr::readonly, "Steps whose reset was ForceContainer::reset's own, as ForceResetter's, since the engine was made [-] (see handedOverBecause)."))
		((std::string, handedOverBecause, "", Attr::readonly, "Why the last step handed to ForceContainer::reset was [-].")),
		/*ctor*/
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularForceResetter);

} // namespace yade
