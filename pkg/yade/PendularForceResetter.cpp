// PendularForceResetter (see PendularForceResetter.hpp): which steps the zeroing is left to PendularLoop's gathering, and the zeroing by parts.
#include "PendularForceResetter.hpp"
#include "PendularLoop.hpp"

#include <core/EnergyTracker.hpp>
#include <pkg/common/InsertionSortCollider.hpp>

#include <algorithm>
#include <limits>

namespace yade {

YADE_PLUGIN((PendularForceResetter));
CREATE_LOGGER(PendularForceResetter);

std::string PendularForceResetter::unsupported(const PendularLoop* l, long n, long& size, pendular::SummedArrays& summed)
{
	if (!l) return "no PendularLoop in O.engines (or a dead one)";
	if (l->flushTeam() == 0) return "the PendularLoop has not handed forces over yet";
	if (scene->bodies->useRedirection) return "redirected body lists (yade.mpy)";
	ForceContainer& container = scene->forces;
	if (container.getPermForceUsed()) return "permanent forces (O.forces.setPermF)";
	// Forces added to the per-thread arrays since the last sync (e.g. O.forces.addF at the end of a step):
	// reset leaves those arrays to sync, which adds them to the summed ones.
	if (!container.synced) return "forces added since the last sync";
	if (n == 0) return "no bodies";
	// reset zeroes the summed arrays over the container's size (getForce gives the container's zero beyond
	// it). That size is at least the bodies' after the loop's hand-over (ForceContainer::addMaxId), and
	// Debian's YADE 2023.02a keeps one entry more (seen: 307 for 306 bodies); more than a few means ids
	// far beyond the bodies', left to reset.
	const Vector3r* beyond = &container.getForce(std::numeric_limits<Body::id_t>::max());
	size                   = n;
	while (&container.getForce(Body::id_t(size)) != beyond)
		if (++size > n + extraEntries) return "a force container larger than the body container";
	summed = pendular::summedArrays(container, size);
	if (!summed.forces) return "a force container smaller than the body container, or not contiguous";
	return "";
}

void PendularForceResetter::action()
{
	if (!pendular::sameEngines(scannedEngines, scene->engines)) {
		loop.reset();
		loopNext         = false;
		bool followsThis = false, onlyColliders = true;
		for (const auto& engine : scene->engines) {
			if (dynamic_cast<const PendularLoop*>(engine.get())) {
				loop     = engine;
				loopNext = followsThis && onlyColliders;
				break;
			}
			if (followsThis && !dynamic_cast<const InsertionSortCollider*>(engine.get())) onlyColliders = false;
			followsThis = followsThis || engine.get() == this;
		}
	}
	const PendularLoop* l = loop && !loop->dead ? static_cast<const PendularLoop*>(loop.get()) : nullptr;
	const long          n = long(scene->bodies->size());
	long                size   = 0;
	pendular::SummedArrays summed;
	const std::string   why = unsupported(l, n, size, summed);
	// Left to the loop's gathering unless sub-steps let Python read the forces between the engines.
	const bool deferring = why.empty() && loopNext && !scene->subStepping;
	if (loop && !deferring) static_cast<PendularLoop*>(loop.get())->cancelReset();
	if (!why.empty()) {
		++nHandedOver;
		handedOverBecause = why;
		ForceResetter::action();
		return;
	}
	// What ForceContainer::reset sets besides the arrays: synced stays true (no permanent forces, and the
	// per-thread arrays were emptied by the last sync); its private permForceSynced matters only for
	// permanent forces, and a step with those is handed over.
	scene->forces.lastReset = scene->iter;
	if (scene->trackEnergy) scene->energy->resetResettables();
	if (deferring) {
		++nDeferred;
		static_cast<PendularLoop*>(loop.get())->takeReset(scene, summed, size);
		return;
	}
	// Each thread of the loop's last hand-over zeroes the part of the bodies it wrote (PendularLoop::flushForces),
	// so that those cache lines stay in its core.
	const std::vector<long>& parts = l->flushParts();
#ifdef YADE_OPENMP
#pragma omp parallel num_threads(l->flushTeam()) if (l->flushTeam() > 1)
#endif
	{
		const auto part = pendular::partOf(parts, n, pendular::threadNumber(), pendular::teamSize());
		pendular::zeroEntries(summed.forces, part.first, part.second);
		pendular::zeroEntries(summed.torques, part.first, part.second);
	}
	pendular::zeroEntries(summed.forces, n, size); // entries of no body
	pendular::zeroEntries(summed.torques, n, size);
}

} // namespace yade
