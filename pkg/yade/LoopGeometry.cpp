// The sphere geometry's out-of-line part (see LoopGeometry.hpp): ScGeom's shear increment, which only
// contacts and the making of objects from records call.
#include "LoopGeometry.hpp"

namespace yade {
namespace pendular {
	Vector3r shearIncrement(const Particle& p1, const Particle& p2, const Vector3r& normal, Real depth, const Vector3r& contactPoint,
	                        const Vector3r& shift2, const Vector3r& shiftVel, bool ratcheting, Real dt)
	{
		Vector3r relVel;
		if (ratcheting) {
			const Real alpha = (p1.radius + p2.radius) / (p1.radius + p2.radius - depth);
			relVel           = (p2.vel - p1.vel) * alpha + p2.angVel.cross(-p2.radius * normal) - p1.angVel.cross(p1.radius * normal);
			relVel += alpha * shiftVel;
		} else {
			const Vector3r c1x = contactPoint - p1.pos, c2x = contactPoint - (p2.pos + shift2);
			relVel             = (p2.vel + p2.angVel.cross(c2x)) - (p1.vel + p1.angVel.cross(c1x));
			relVel += shiftVel;
		}
		relVel = relVel - normal.dot(relVel) * normal;
		return relVel * dt;
	}
} // namespace pendular
} // namespace yade
