// PendularRotationEngine: YADE's RotationEngine step (its velocities, bit for bit), with the rotation of
// the step made once for all bodies, and set body by body in PendularIntegrator's pass when one follows.
#pragma once

#include "YadeHeaders.hpp"

#include <core/GlobalEngine.hpp>
#include <core/State.hpp>

#include <boost/weak_ptr.hpp>

namespace yade {

class PendularIntegrator;

class PendularRotationEngine : public GlobalEngine {
public:
	void action() override;
	void postLoad(PendularRotationEngine&);
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
	// The velocities of this step set on every body of ids now (PendularIntegrator, when it hands its step to
	// the NewtonIntegrator after this engine left it the step).
	void turnNow() { turn(); }
	DECLARE_LOGGER;

	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR(PendularRotationEngine, GlobalEngine,
		"YADE's :yref:`RotationEngine` for the walls of our scenes (the same attributes and the same velocities, bit for bit): "
		"the bodies' velocities are set to zero, then their angular velocity to rotationAxis times angularVelocity and, with "
		"rotateAroundZero, their velocity to the displacement of a rotation by angularVelocity*dt about the axis through "
		"zeroPoint, divided by dt. It differs in how: RotationEngine computes that rotation (a sine and a cosine) for every "
		"body and shares its bodies between OpenMP's threads whatever its ompThreads says (on the ci shear cell it took 13-24 µs "
		"per step and made PendularIntegrator slower). This engine makes the rotation once per step. When a :yref:`PendularIntegrator` "
		"follows it with only other PendularRotationEngines and the (dead) NewtonIntegrator between them (as in "
		"yade_capillary.shearcell), that engine sets the velocities in its pass, each body's just before it moves the body and "
		"in the thread that moves it (see nDeferred): the same operations on the same numbers, without a pass of their own over "
		"the bodies' State objects (6-8 µs per step on the ci cell). Else it sets them in the calling thread. Not while "
		"sub-stepping (O.subStepping: Python may read the velocities between the engines). An id that is not a body's raises "
		"an error naming it; an erased body is skipped.",
		((std::vector<Body::id_t>, ids, , Attr::triggerPostLoad, "Ids of the bodies turned [-]; an id listed twice raises ValueError (RotationEngine would add its spin twice to that body, after one zeroing)."))
		((Real, angularVelocity, 0, , "Angular velocity [rad/s]."))
		((Vector3r, rotationAxis, Vector3r::UnitX(), Attr::triggerPostLoad, "Axis of rotation (a direction, normalized when set; a zero or non-finite vector raises ValueError) [-]."))
		((bool, rotateAroundZero, false, , "If True, the bodies also turn about the axis through zeroPoint (their velocity is set), else they only spin about their centres [-]."))
		((Vector3r, zeroPoint, Vector3r::Zero(), , "A point of the rotation axis, with rotateAroundZero [m]."))
		((long, nDeferred, 0, Attr::readonly, "Steps whose velocities this engine left to the :yref:`PendularIntegrator` after it [-]: set in its pass over the bodies, or before the NewtonIntegrator's step when it hands the step to that engine.")),
		/*ctor*/
	);
	// clang-format on
private:
	// The step's velocities; the index in ids of an id that is not a body's (the bodies before it are
	// set), else -1.
	long turn();
	// The index in ids of the first id that is not one of the n bodies', else -1.
	long invalidId(long n) const;
	// The PendularIntegrator that sets this engine's velocities in its pass (nullptr: none), for the engine
	// list last scanned (see pendular::sameEngines).
	std::vector<boost::weak_ptr<Engine>> scannedEngines;
	shared_ptr<Engine>                   integrator;
	std::vector<shared_ptr<Engine>>      newtons; // between this engine and the integrator (dead, else the step is this engine's)
};
REGISTER_SERIALIZABLE(PendularRotationEngine);

} // namespace yade
