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
		((Vector3r, zeroPoint, Vector3r::Zero(), , "A point of the rotation axis, with rotateAroundZero [m].")),
		/*ctor*/
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularRotationEngine);

} // namespace yade
