// The geometry of two spheres as PendularLoop's fused pass computes it on the gathered bodies
// (Particle): what Ig2_Sphere_Sphere_ScGeom::go and ScGeom::precompute do after the distance, in their
// order of operations, so that the numbers are theirs bit for bit, on an ScGeom or on a record's view
// of one (RecordGeom). Functions of their arguments only; inline (once per bridge-step), but for
// shearIncrement, which only contacts and the making of objects call.
#pragma once

#include "LoopBodies.hpp"

#include <pkg/dem/Ig2_Sphere_Sphere_ScGeom.hpp>

namespace yade {
namespace pendular {
	// ScGeom::rotate's rotation of the shear force from the last normal to this one (its axes are
	// private to ScGeom: kept here, and used by the law).
	struct Rotation {
		Vector3r orthonormalAxis = Vector3r::Zero(), twistAxis = Vector3r::Zero();
		void     operator()(Vector3r& v) const
		{
			v -= v.cross(orthonormalAxis);
			v -= v.cross(twistAxis);
		}
	};
	// Ig2_Sphere_Sphere_ScGeom's contact point: from the centre of body 1 along the normal, at its radius
	// less half the overlap.
	inline Vector3r contactPointOf(const Particle& p1, const Vector3r& normal, Real depth) { return p1.pos + (p1.radius - 0.5 * depth) * normal; }
	// ScGeom::shearInc of two spheres in contact as Ig2_Sphere_Sphere_ScGeom makes it (ScGeom::precompute),
	// from the bodies as a step saw them, the normal, overlap and contact point of that step, and its
	// Ig2's avoidGranularRatcheting and time step. A record keeps shearInc only while its bridge is
	// separated (the value of its last step in contact, where Ig2 last updated it): in contact the law
	// never reads it (it computes the relative velocity itself), so it is made from the bodies when the
	// objects are (RecordStore::store), and kept when the bridge separates (from the step before).
	Vector3r shearIncrement(const Particle& p1, const Particle& p2, const Vector3r& normal, Real depth, const Vector3r& contactPoint,
	                        const Vector3r& shift2, const Vector3r& shiftVel, bool ratcheting, Real dt);
	// Ig2_Sphere_Sphere_ScGeom and ScGeom::precompute after the distance, in their order of operations, on
	// an ScGeom or a record's view of one: `normal` the unit vector from centre 1 to centre 2, `depth` the
	// overlap, shift2 and shiftVel those of a periodic cell, isNew: the geometry was just made; ig2 the
	// functor it stands for (its avoidGranularRatcheting). record: the geometry of a Record, whose shearInc
	// is made only when read (see shearIncrement); without friction the law reads only its gap and normal
	// (no contact point, no rotation axes).
	template <class Geom>
	Rotation sphereGeometry(Geom& geom, const Particle& p1, const Particle& p2, const Vector3r& normal, Real depth, const Vector3r& shift2,
	                        const Vector3r& shiftVel, bool isNew, const Scene& scene, const Ig2_Sphere_Sphere_ScGeom* ig2, bool record = false,
	                        bool friction = true)
	{
		geom.penetrationDepth = depth;
		// A frictionless record: the law reads the gap and the normal only (the contact point and the radii
		// of its objects follow from the bodies, see RecordStore::store).
		if (record && !friction) {
			geom.normal = normal;
			return Rotation {};
		}
		geom.contactPoint = contactPointOf(p1, normal, depth);
		geom.radius1      = p1.radius;
		geom.radius2      = p2.radius;
		Rotation axes;
		if (depth >= 0 || isNew) { // in contact: what the law's tangential spring reads
			if (!isNew) {
				axes.orthonormalAxis = geom.normal.cross(normal);
				const Real angle     = scene.dt * 0.5 * geom.normal.dot(p1.angVel + p2.angVel);
				axes.twistAxis       = angle * geom.normal;
			}
			geom.normal = normal;
			if (!record)
				geom.shearInc = shearIncrement(p1, p2, normal, depth, geom.contactPoint, shift2, shiftVel, ig2->avoidGranularRatcheting, scene.dt);
		} else
			geom.normal = normal; // a separated bridge: the gap and the normal only
		return axes;
	}
} // namespace pendular
} // namespace yade
