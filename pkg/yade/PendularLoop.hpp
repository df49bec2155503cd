// PendularLoop: YADE's InteractionLoop with a fused pass for the interactions of yade-capillary.
#pragma once

#include "Pendular.hpp"
#include <core/InteractionLoop.hpp>

#include <boost/weak_ptr.hpp>
#include <cstdint>
#include <vector>

namespace yade {

class PendularLoop : public InteractionLoop {
public:
	// What the fused pass needs of one body, gathered once per step into a contiguous array
	// (instead of two shared_ptr hops to a State per interaction).
	struct Particle {
		Vector3r pos, vel, angVel;
		Real     radius;
		Real     reach; // film thickness of a sphere whose bridges form when the films touch (formation='films'), else 0
		int      subdomain;
		uint8_t  kind;
	};
	enum Kind : uint8_t { missing, other, clump, pendularSphere, pendularBoundary };

	void action() override;
	// sizeof of what an interaction and a body cost, for the memory benchmark.
	boost::python::dict memory() const;
	DECLARE_LOGGER;

private:
	struct Resolved; // the functors the dispatchers choose for PendularMat spheres, see resolve()
	void resolve(Resolved&);
	void gather(int threads);
	void step(const shared_ptr<Interaction>& I, const Resolved& r, long& fused, long& dispatchedCount);
	void dispatched(const shared_ptr<Interaction>& I, const Resolved& r, int thread);
	void sphereSphere(const shared_ptr<Interaction>& I, const Resolved& r, int thread);
	// Our law, inline, on the gathered data, into the thread's force arrays; false: reset I.
	template <class Rotate>
	bool applyLaw(const Interaction& I, const ScGeom& geom, const Resolved& r, const Vector3r& shift2, const Vector3r& shiftVel, const Rotate& rotate,
	              int thread);
	void callbacksOn(Interaction& I, const Resolved& r);
	void flushForces(int threads);

	// Per entry of the interaction container, what the last step saw: the interaction, its ids and
	// whether it was potential. Held by a weak_ptr and compared by owner (control block), not by
	// address: a new interaction allocated where an erased one was is still another owner.
	struct Slot {
		boost::weak_ptr<Interaction> interaction;
		Body::id_t                   id1 = 0, id2 = 0;
		bool                         potential = false;
		bool same(const shared_ptr<Interaction>& I) const { return !interaction.owner_before(I) && !I.owner_before(interaction); }
	};
	std::vector<Slot>                  slots;
	bool                               removeUnseen = false;
	std::vector<Particle>              particles;
	// The part of a Particle that the check of a potential pair reads, 32 B (two per cache line):
	// the centre and the radius plus the reach, signed: > 0 a PendularMat sphere of this subdomain,
	// < 0 (negated) one of another subdomain, 0 any other body.
	struct Near {
		Vector3r pos;
		Real     radius;
	};
	std::vector<Near>                  near;
	std::vector<std::vector<Vector3r>> threadForce, threadTorque; // per OpenMP thread, per body id
	Matrix3r                           cellHsize = Matrix3r::Zero();

public:
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularLoop, InteractionLoop,
		"The :yref:`InteractionLoop` of yade-capillary (yade_capillary.scene.engines uses it by default), built from the same "
		"three functor lists. Sphere-sphere interactions of two :yref:`PendularMat` bodies whose functors the dispatchers resolve "
		"to Ig2_Sphere_Sphere_ScGeom, Ip2_PendularMat_PendularMat_PendularPhys and Law2_ScGeom_PendularPhys_Bridge are computed in "
		"one fused pass: geometry, contact law and capillary bridge, force and torque accumulation, without virtual calls, with the "
		"bodies' positions and velocities gathered once per step. A potential interaction (bounding boxes overlap) costs one "
		"distance check and becomes real at contact, where the bridge forms; a separated bridge updates only the normal and the "
		"gap (ScGeom's shearInc, orthonormal_axis and twist_axis are updated in contact only, where the law uses them). "
		"Interactions of PendularMat spheres with walls and facets get their geometry from their Ig2 functor and the same inline "
		"law; every other interaction goes through the dispatchers exactly as in InteractionLoop. The numbers are those of "
		"InteractionLoop with the same functors (the law is one function, Law2_ScGeom_PendularPhys_Bridge).",
		((long, nFused, 0, Attr::readonly, "Interactions handled by the fused sphere-sphere pass in the last step [-] (real and potential)."))
		((long, nDispatched, 0, Attr::readonly, "Interactions handled through the dispatchers in the last step [-] (walls, facets, other materials)."))
		((long, nApart, 0, Attr::readonly, "Of nFused, the potential interactions found apart by the distance check alone in the last step [-]."))
		((Real, gatherTime, 0, , "Wall time spent gathering the bodies' positions and velocities since this was last set to 0 [ns]."))
		((Real, passTime, 0, , "Wall time spent in the pass over the interactions since this was last set to 0 [ns]."))
		((Real, flushTime, 0, , "Wall time spent handing the summed forces to the force container since this was last set to 0 [ns].")),
		/*ctor*/,
		/*py*/
		.def("memory", &PendularLoop::memory, "sizeof in bytes of the objects of one interaction (Interaction, ScGeom, PendularPhys, YADE's ViscElCapPhys for comparison), of the fused pass's slot per interaction (slot) and of its per-body arrays (particle: gathered body data; near: centre and radius for the check of potential pairs; forces: force and torque per thread).")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularLoop);

} // namespace yade
