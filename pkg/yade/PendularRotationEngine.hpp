// PendularRotationEngine: YADE's RotationEngine step (its velocities, bit for bit), with the rotation of
// the step made once for all bodies.
#pragma once

#include "YadeHeaders.hpp"

#include <core/GlobalEngine.hpp>
#include <core/State.hpp>

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
		"body and shares its bodies between OpenMP's threads whatever its ompThreads says (on the ci shear cell it took 13-24 µs "
		"per step and made PendularIntegrator slower, docs/performance.md). This engine makes the rotation once per step and "
		"sets the bodies' velocities in the calling thread. An id that is not a body's raises an error naming it; an erased "
		"body is skipped.",
		((std::vector<Body::id_t>, ids, , Attr::triggerPostLoad, "Ids of the bodies turned [-]; an id listed twice raises ValueError (RotationEngine would add its spin twice to that body, after one zeroing)."))
		((Real, angularVelocity, 0, , "Angular velocity [rad/s]."))
		((Vector3r, rotationAxis, Vector3r::UnitX(), Attr::triggerPostLoad, "Axis of rotation (a direction, normalized when set; a zero or non-finite vector raises ValueError) [-]."))
		((bool, rotateAroundZero, false, , "If True, the bodies also turn about the axis through zeroPoint (their velocity is set), else they only spin about their centres [-]."))
		((Vector3r, zeroPoint, Vector3r::Zero(), , "A point of the rotation axis, with rotateAroundZero [m].")),
		/*ctor*/
	);
	// clang-format on
private:
	// This step's motion of the bodies, the same for all: the angular velocity and, with rotateAroundZero,
	// the rotation by angularVelocity*dt about the axis through zeroPoint.
	struct Motion {
		Vector3r    spin;
		Quaternionr rotation;
		Vector3r    zeroPoint;
		bool        aroundZero;
	};
	Motion motion(Real dt) const;
	// RotationEngine's operations on one body (KinematicEngine::action's zeroing, then RotationEngine::apply).
	static void setVelocities(State& s, const Motion& m, Real dt)
	{
		s.vel = s.angVel = Vector3r::Zero();
		s.angVel += m.spin;
		if (m.aroundZero) {
			const Vector3r l      = s.pos - m.zeroPoint;
			const Vector3r newPos = m.rotation * l + m.zeroPoint;
			s.vel += Vector3r(newPos - s.pos) / dt;
		}
	}
	// The step's velocities; the index in ids of an id that is not a body's (the bodies before it are
	// set), else -1.
	long turn();
};
REGISTER_SERIALIZABLE(PendularRotationEngine);

} // namespace yade
