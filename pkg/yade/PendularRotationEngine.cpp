#include "PendularRotationEngine.hpp"
#include "Passes.hpp"
#include "Pendular.hpp"

#include <stdexcept>

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
}

void PendularRotationEngine::action()
{
	if (turnedScene == scene && turnedIter == scene->iter) return; // PendularLoop did this step's (see turnAhead)
	const long invalid = turn();
	if (invalid >= 0)
		PendularCheck::raiseInStep(scene, "PendularRotationEngine: ids[" + std::to_string(invalid) + "] = " + std::to_string(ids[invalid])
		                                  + " is not a body id (0 to " + std::to_string(long(scene->bodies->body.size()) - 1) + ")");
}

bool PendularRotationEngine::turnAhead(Scene* current)
{
	scene = current;
	if (turn() >= 0) return false; // the step's own call raises the error
	turnedScene = scene;
	turnedIter  = scene->iter;
	++nAhead;
	return true;
}

long PendularRotationEngine::turn()
{
	const auto& bodies = scene->bodies->body; // the vector itself: BodyContainer::operator[] is a call into libyade per body
	const long  n      = long(bodies.size());
	const long  m      = long(ids.size());
	// RotationEngine's operations on every body (KinematicEngine::action's zeroing, then RotationEngine::apply),
	// with the two values that are the same for every body made once.
	const Vector3r    spin = rotationAxis * angularVelocity;
	const Quaternionr q(AngleAxisr(angularVelocity * scene->dt, rotationAxis));
	constexpr long    ahead = 8; // bodies ahead: the Body twice as far as its State, which is read from it
	// The body of ids[j] if j is an index of ids and ids[j] a body's id (nullptr otherwise: nothing to prefetch).
	const auto bodyAt = [&](long j) -> const Body* { return j < m && ids[j] >= 0 && ids[j] < n ? bodies[ids[j]].get() : nullptr; };
	for (long k = 0; k < m; ++k) {
		if (const Body* b = bodyAt(k + 2 * ahead)) __builtin_prefetch(b);
		if (const Body* b = bodyAt(k + ahead)) pendular::prefetchObject<1>(b->state.get());
		const Body::id_t id = ids[k];
		if (id < 0 || id >= n) return k;
		const Body* b = bodies[id].get();
		if (!b) continue;
		State& s = *b->state;
		s.vel = s.angVel = Vector3r::Zero();
		s.angVel += spin;
		if (rotateAroundZero) {
			const Vector3r l      = s.pos - zeroPoint;
			const Vector3r newPos = q * l + zeroPoint;
			s.vel += Vector3r(newPos - s.pos) / scene->dt;
		}
	}
	return -1;
}

} // namespace yade
