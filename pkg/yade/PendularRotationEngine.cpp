// PendularRotationEngine (see PendularRotationEngine.hpp): the velocities of the step from one rotation.
#include "PendularRotationEngine.hpp"
#include "Passes.hpp"
#include "Pendular.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace yade {

YADE_PLUGIN((PendularRotationEngine));
CREATE_LOGGER(PendularRotationEngine);

void PendularRotationEngine::postLoad(PendularRotationEngine&)
{
	const Real norm = rotationAxis.norm();
	if (!(norm > 0) || !math::isfinite(norm))
		throw std::invalid_argument("PendularRotationEngine.rotationAxis = (" + std::to_string(double(rotationAxis[0])) + ", "
		                            + std::to_string(double(rotationAxis[1])) + ", " + std::to_string(double(rotationAxis[2]))
		                            + "): must be a nonzero finite vector (the direction of the axis)");
	rotationAxis.normalize();
	// setVelocities sets each listed body's velocities whole (RotationEngine zeroes every body, then adds per listed id).
	std::vector<std::pair<Body::id_t, long>> sorted;
	for (long k = 0; k < long(ids.size()); ++k)
		sorted.emplace_back(ids[k], k);
	std::sort(sorted.begin(), sorted.end());
	for (size_t k = 1; k < sorted.size(); ++k)
		if (sorted[k].first == sorted[k - 1].first)
			throw std::invalid_argument("PendularRotationEngine.ids: id " + std::to_string(sorted[k].first) + " is listed twice (ids["
			                            + std::to_string(sorted[k - 1].second) + "] and ids[" + std::to_string(sorted[k].second)
			                            + "]); each body may be listed once");
}

void PendularRotationEngine::action()
{
	const long invalid = turn();
	if (invalid >= 0)
		PendularCheck::raiseInStep(scene, "PendularRotationEngine: ids[" + std::to_string(invalid) + "] = " + std::to_string(ids[invalid])
		                                  + " is not a body id (0 to " + std::to_string(long(scene->bodies->body.size()) - 1) + ")");
}

PendularRotationEngine::Motion PendularRotationEngine::motion(Real dt) const
{
	return Motion { rotationAxis * angularVelocity, Quaternionr(AngleAxisr(angularVelocity * dt, rotationAxis)), zeroPoint, rotateAroundZero };
}

long PendularRotationEngine::turn()
{
	const auto&  bodies = scene->bodies->body; // the vector itself: BodyContainer::operator[] is a call into libyade per body
	const long   n      = long(bodies.size());
	const long   m      = long(ids.size());
	const Motion step   = motion(scene->dt);
	constexpr long ahead = 8; // bodies ahead: the Body twice as far as its State, which is read from it
	// The body of ids[j] if j is an index of ids and ids[j] a body's id (nullptr otherwise: nothing to prefetch).
	const auto bodyAt = [&](long j) -> const Body* { return j < m && ids[j] >= 0 && ids[j] < n ? bodies[ids[j]].get() : nullptr; };
	for (long k = 0; k < m; ++k) {
		if (const Body* b = bodyAt(k + 2 * ahead)) __builtin_prefetch(b);
		if (const Body* b = bodyAt(k + ahead)) pendular::prefetchObject<1>(b->state.get());
		const Body::id_t id = ids[k];
		if (id < 0 || id >= n) return k;
		const Body* b = bodies[id].get();
		if (!b) continue;
		setVelocities(*b->state, step, scene->dt);
	}
	return -1;
}

} // namespace yade
