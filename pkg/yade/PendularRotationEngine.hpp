// PendularRotationEngine: YADE's RotationEngine step (its velocities, bit for bit) in one thread, with the
// rotation of the step made once for all bodies.
#pragma once

#include "YadeHeaders.hpp"

#include <core/GlobalEngine.hpp>

namespace yade {

class PendularRotationEngine : public GlobalEngine {
public:
	void action() override;
	void postLoad(PendularRotationEngine&);
	// This step's velocities, set by a PendularLoop ahead of the step's call of action() (which then does
	// nothing), in the time its first thread would wait for the second one (see PendularLoop::action).
	// False, with nothing to skip, if an id is not a body's: action() then raises the error. Never throws.
	bool turnAhead(Scene* current);
	void forgetAhead() { turnedIter = -1; }
	DECLARE_LOGGER;

	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR(PendularRotationEngine, GlobalEngine,
		"YADE's :yref:`RotationEngine` for the walls of our scenes (the same attributes and the same velocities, bit for bit): "
		"the bodies' velocities are set to zero, then their angular velocity to rotationAxis times angularVelocity and, with "
		"rotateAroundZero, their velocity to the displacement of a rotation by angularVelocity*dt about the axis through "
		"zeroPoint, divided by dt. It differs in how: RotationEngine computes that rotation (a sine and a cosine) for every "
		"body and shares its bodies between OpenMP's threads whatever its ompThreads says, so that with the bodies of a "
		"rotating wall, which all belong to the first thread's part of a :yref:`PendularLoop` scene, the second thread wrote "
		"their State objects, which the first thread then read back (on the ci shear cell RotationEngine took 13-24 µs per "
		"step and made PendularIntegrator slower). This engine makes the rotation once per step and sets the bodies in the "
		"calling thread, OpenMP's first. An id that is not a body's raises an error naming it; an erased body is skipped.",
		((std::vector<Body::id_t>, ids, , , "Ids of the bodies turned [-]."))
		((Real, angularVelocity, 0, , "Angular velocity [rad/s]."))
		((Vector3r, rotationAxis, Vector3r::UnitX(), Attr::triggerPostLoad, "Axis of rotation (a direction, normalized when set; a zero or non-finite vector raises ValueError) [-]."))
		((bool, rotateAroundZero, false, , "If True, the bodies also turn about the axis through zeroPoint (their velocity is set), else they only spin about their centres [-]."))
		((Vector3r, zeroPoint, Vector3r::Zero(), , "A point of the rotation axis, with rotateAroundZero [m]."))
		((long, nAhead, 0, Attr::readonly, "Steps whose velocities a :yref:`PendularLoop` set ahead of this engine's turn, in the time its first thread would wait for the second one at the end of its pass (the engine's own step then does nothing) [-].")),
		/*ctor*/
	);
	// clang-format on
private:
	// The step's velocities; the index in ids of an id that is not a body's (the bodies before it are
	// set), else -1.
	long         turn();
	const Scene* turnedScene = nullptr;
	long         turnedIter  = -1;
};
REGISTER_SERIALIZABLE(PendularRotationEngine);

} // namespace yade
