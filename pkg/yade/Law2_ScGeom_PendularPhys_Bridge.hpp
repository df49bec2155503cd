// Law2_ScGeom_PendularPhys_Bridge: the contact law of yade-capillary (contact, capillary bridge,
// viscous forces), defined here so that YADE's dispatch (go) and PendularLoop inline the same apply().
#pragma once

#include "PendularPhys.hpp"
#include "PendularState.hpp"
#include "YadeHeaders.hpp"

#include <limits>
#include <mutex>
#include <type_traits>
#include <vector>

namespace yade {

// Positions and velocities of the two bodies of an interaction, as the contact law reads them;
// shift2 and shiftVel move body 2 to its periodic image (zero without periodic cell). owned: this
// scene counts the bridge in the law's totals (see pendularOwner). id1, id2: the bodies, whose films
// a film-mode bridge reads when it forms and breaks.
struct PendularKinematics {
	const Vector3r &pos1, &vel1, &angVel1, &pos2, &vel2, &angVel2;
	const Vector3r &shift2, &shiftVel; // references, as the others: a copy would be six stores per bridge-step
	bool            owned;
	Body::id_t      id1, id2;
};

// yade.mpy computes an interaction between bodies of two subdomains on both ranks: its bridge is
// counted in the totals (nBridges, liquidVolume, ...) only by the rank of the larger subdomain
// number, so that the sum over ranks counts every bridge once (the master, subdomain 0, keeps the
// walls; a wall-sphere pair belongs to the sphere's rank). Without MPI every subdomain is 0.
inline bool pendularOwner(int sceneSubdomain, int subdomain1, int subdomain2) { return sceneSubdomain == math::max(subdomain1, subdomain2); }

class Law2_ScGeom_PendularPhys_Bridge : public LawFunctor {
public:
	bool go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I) override;
	// The contact law of one interaction: updates phys and the bridge totals, hands the force to
	// `sink` (body 1 gets -f, body 2 +f) and returns false when the interaction is to be reset.
	// Used by go() (YADE's InteractionLoop) and by PendularLoop, so both compute the same numbers.
	// Sink: force(f) for a central force, forceTorque(f, t1, t2) with the torques on bodies 1, 2.
	// rotate(v): ScGeom::rotate, the shear force carried from the last contact plane to this one.
	// Geom, Phys: ScGeom and PendularPhys, or PendularLoop's record of a fixed-volume inviscid
	// sphere-sphere bridge, which has their members of the same names (see PendularLoop::Record).
	template <class Geom, class Phys, class Rotate, class Sink>
	bool apply(const Geom& geom, Phys& phys, const PendularKinematics& k, Real dt, const Rotate& rotate, Sink& sink);
	// Breaks the bridge (totals if owned; film: its liquid back to the films at the end of the step)
	// and returns false: the interaction is to be reset.
	template <class Phys> bool breakBridge(Phys& phys, const PendularKinematics& k);
	// Film mode, at the end of each step (PendularCheck, serial): forms the bridges asked for in the
	// step, sharing each film among all the bridges formed on it (Elskamp2018 section 2.2.1), then
	// adds the liquid of the bridges broken in the step to the films. Throws std::invalid_argument if
	// a bridge could not be built (after settling all others, so that no liquid is lost).
	void settleFilms(Scene* scene);
	// The Python paths that remove bodies or interactions (wrapped by pendular::installGuards, PythonSide.hpp):
	// releasePair breaks an active bridge as at rupture, its liquid to the two films (O.interactions.erase
	// and clear); eraseBody breaks the body's bridges and moves its film to liquidRemoved, with its clump's
	// members if clumpMembers (O.bodies.erase); clearBodies moves all liquid to liquidRemoved
	// (O.bodies.clear). Refused (std::runtime_error) while the simulation runs.
	void releasePair(Scene* scene, Interaction& I);
	void eraseBody(Scene* scene, Body::id_t id, bool clumpMembers);
	void clearBodies(Scene* scene);
	boost::python::dict liquidTotals() const;
	// Gives the real interaction id1-id2 of the current scene the bridge of its physics, counted in
	// the totals as at a first contact, for a bridge of a saved state (shearcell.load_state), up to a gap
	// of the rupture distance + pastRupture [m]: a state saved after Newton's half of a step may hold a
	// bridge that the step stretched past rupture and that the law breaks at the next step.
	// std::invalid_argument (ValueError) naming what does not allow it.
	void formBridge(Body::id_t id1, Body::id_t id2, Real pastRupture);
	// liquidVolume is a running sum: with no bridge left its round-off is set to exactly 0.
	void zeroEmptyTotals();

	// The overlap check (PendularCheck.maxOverlap). apply() compares a contact's overlap with
	// overlapAlarm, maxOverlap times the smallest sphere radius of the scene (inf: off), which
	// PendularCheck sets: one comparison per contact-step. The rare contact above it is measured
	// against its own smaller radius by overlapSeen, out of line.
	Real overlapAlarm = std::numeric_limits<Real>::infinity();
	Real overlapBound = 0.5; // maxOverlap [-]
	struct OverlapReport {
		long       count   = 0; // contact-steps above the bound
		Real       largest = 0; // overlap / smaller radius of the largest
		Body::id_t id1 = -1, id2 = -1;
		Real       overlap = 0, radius = 0, speed = 0; // of the largest [m], [m], [m/s]
	};
	// What the contacts reported since the last call, reset.
	OverlapReport takeOverlaps();

private:
	// Scalars only: a reference to the kinematics or the geometry would make the hot path keep them in
	// memory at every bridge-step; the rare call finds the rest from the bodies and the interaction.
	__attribute__((noinline, cold)) void overlapSeen(Real depth, Body::id_t id1, Body::id_t id2, Real kn);
	std::mutex    overlapMutex;
	OverlapReport overlaps;
	// Film mode: what the bridges ask of the films in a step, done by settleFilms. Rare (formation and
	// rupture only), so one lock for InteractionLoop's threads.
	struct FilmFormation {
		PendularPhys* phys;
		Body::id_t    id1, id2;
		Real          take1, take2; // Shi & McCarthy's volumes from the films of bodies id1, id2 [m^3]
		bool          owned;
	};

public:
	// The liquid of a broken film-mode bridge or bond for body `id`, whose partner was `partner`.
	struct FilmReturn {
		Body::id_t id;
		Real       volume;
		Body::id_t partner;
	};
	// The shares of the bonds broken in this step (liquid='bonds'), for PendularBonds to place; in the
	// order of the bodies and their partners, whatever the order of the threads.
	std::vector<FilmReturn> takeBondReturns();
	// Liquid [m^3] back to body `id`'s film, or to liquidRemoved if the body no longer exists. Serial.
	void giveBack(Scene* scene, Body::id_t id, Real volume);

private:
	std::mutex                 filmMutex;
	std::vector<FilmFormation> formations;
	std::vector<FilmReturn>    returns, bondReturns;
	// The sphere R1 of a bridge and its other body (a sphere R2, or a wall or facet): bodies 1 and 2
	// unless swapped.
	struct FilmPair {
		Body::id_t sphere, other;
	};
	static FilmPair filmPair(const PendularPhys& p, Body::id_t id1, Body::id_t id2) { return p.swapped ? FilmPair { id2, id1 } : FilmPair { id1, id2 }; }
	// What goes back to the sphere R1 when the bridge ends [m^3]: transfer1 of its liquid, or all of it
	// if the other body is a wall that holds no film (otherHolds false); the other body gets the rest.
	static Real sphereShare(const PendularPhys& p, bool otherHolds) { return otherHolds ? p.transfer1 * p.Vb : p.Vb; }
	void                       askFormation(PendularPhys& phys, const PendularKinematics& k);
	bool                       filmsTouch(const PendularPhys& phys, const PendularKinematics& k, Real gap) const;

public:
	FUNCTOR2D(ScGeom, PendularPhys);
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(Law2_ScGeom_PendularPhys_Bridge, LawFunctor,
		"Contact law of yade-capillary. In contact: linear viscoelastic normal force without attraction while unloading, "
		"incremental tangential spring-dashpot with Coulomb friction (Gladkyy2014 eq. 3-4), plus F(0) if forceInContact; "
		"PendularMat.normalDamping = 'approach' and friction = 'viscous' give Richefeu2008's law (eq. 3, 12). "
		"Separated with a bridge: the capillary force of the bridge's model along the line of centres; beyond the rupture "
		"distance the bridge breaks and the interaction is removed. Separated without a bridge (before the first contact, "
		"with a detection factor > 1): no force, and the interaction is reset (returns false), so that it is removed once "
		"the bounding boxes part and made again at contact; a real interaction keeps its geometry until the law ends it, so "
		"no enlarged detection range is needed for the bridge.",
		((OpenMPAccumulator<int>, nBridges, , Attr::readonly, "Number of liquid bridges that exist now [-]. Saved by O.save. Under yade.mpy, the bridges of this rank (a bridge between two subdomains belongs to the larger subdomain number); yade_capillary.mpi.liquid_totals() sums over ranks."))
		((OpenMPAccumulator<Real>, liquidVolume, , Attr::readonly, "Liquid volume in the bridges that exist now [m^3]. Saved by O.save."))
		((OpenMPAccumulator<Real>, liquidFormed, , Attr::readonly, "Liquid volume put into bridges since the start [m^3] (fixed volume per bridge, Gladkyy2014). Saved by O.save."))
		((OpenMPAccumulator<Real>, liquidReleased, , Attr::readonly, "Liquid volume of bridges broken since the start [m^3]; liquidFormed - liquidReleased = liquidVolume. Saved by O.save."))
		((Real, liquidRemoved, 0, Attr::readonly, "liquid='film' or 'bonds': liquid that left the scene with erased bodies (O.bodies.erase) [m^3]: their films and their shares of their bridges. films + bridges + liquidRemoved is constant (liquidTotals()). Saved by O.save.")),
		/*ctor*/,
		/*py*/
		.def("formBridge", &Law2_ScGeom_PendularPhys_Bridge::formBridge, (boost::python::arg("id1"), boost::python::arg("id2"), boost::python::arg("pastRupture") = 0.0),
		     "Form the bridge of the real interaction id1-id2 of the current scene, as at its first contact (nBridges, liquidVolume "
		     "and liquidFormed count it), whatever the gap up to the rupture distance + pastRupture [m] (>= 0; a saved bridge that the "
		     "step before the save stretched past its rupture distance, which the law breaks at the next step): restores a bridge of "
		     "a saved state (shearcell.load_state). Only for a wet fixed-volume pair without a bridge, not while the simulation runs; "
		     "ValueError otherwise.")
		.def("liquidTotals", &Law2_ScGeom_PendularPhys_Bridge::liquidTotals, "The liquid of the current scene [m^3] as a dict: films (sum of PendularState.film over the bodies), bridges (sum of Vb over the film-mode bridges and bonds that exist), removed (liquidRemoved), total (their sum, constant in film mode) and fixedBridges (the bridges of fixed-volume materials, not part of total)."));
	// clang-format on
};
REGISTER_SERIALIZABLE(Law2_ScGeom_PendularPhys_Bridge);

// The viscous terms of a bridge with eta > 0 at the surface separation S (Elskamp2018 eq. 25-29),
// through the bridge's capillary::ViscousBridge: sets phys.Fvisc, phys.viscousShear and
// phys.sRupture (eq. 33 if dynamicRupture) and returns the moments on bodies 1 and 2.
// Velocities: the centres of the spheres (Elskamp2018 after eq. 25), a wall's or facet's velocity
// at the contact point, which has no radius to turn its rotation into a surface velocity (its arm
// is 0 in omega_r = r1 omega1 + r2 omega2). Moments: r n x F1 on a sphere (Elskamp2018 after eq. 6;
// for separated spheres the two do not balance the couple of the pair of forces, a property of the
// paper's model); a wall or facet gets the moment of its force at the contact point.
struct PendularViscousMoments {
	Vector3r torque1, torque2;
};
inline PendularViscousMoments pendularViscous(const ScGeom& geom, PendularPhys& phys, const PendularKinematics& k, Real S)
{
	const bool     wall1 = phys.swapped, wall2 = !phys.swapped && math::isinf(phys.R2);
	const Real     arm1 = wall1 ? 0 : phys.R1, arm2 = wall1 ? phys.R1 : (wall2 ? 0 : phys.R2);
	Vector3r       v1 = k.vel1, v2 = k.vel2 + k.shiftVel;
	if (wall1) v1 += k.angVel1.cross(geom.contactPoint - k.pos1);
	if (wall2) v2 += k.angVel2.cross(geom.contactPoint - k.pos2 - k.shift2);
	const Vector3r& n    = geom.normal; // from body 1 to body 2
	const Vector3r  vRel = v1 - v2;
	const Real      vn   = n.dot(vRel); // > 0: approaching
	double          ct, cr;
	bool            near;
	phys.viscous->tangential_coefficients(S, ct, cr, near);
	const Vector3r force1 = capillary::tangential_viscous_force(ct, cr, n, Vector3r(vRel - vn * n), Vector3r(arm1 * k.angVel1 + arm2 * k.angVel2));
	phys.Fvisc            = -phys.viscous->normal_coefficient(S) * vn; // F1 = -c v_n n, so body 2 gets -Fvisc n
	phys.viscousShear     = -force1;
	phys.sRupture         = phys.dynamicRupture ? phys.bridge.rupture * phys.viscous->rupture_stretch(vRel.norm()) : phys.bridge.rupture;
	const Vector3r nxF1   = n.cross(force1); // M1 = r1 n x F1, M2 = r2 n x F1 (Elskamp2018 after eq. 6)
	return { wall1 ? Vector3r((geom.contactPoint - k.pos1).cross(force1)) : Vector3r(arm1 * nxF1),
		 wall2 ? Vector3r((geom.contactPoint - k.pos2 - k.shift2).cross(-force1)) : Vector3r(arm2 * nxF1) };
}

// Only a PendularPhys can hold a film-mode or viscous bridge; PendularLoop's records hold the others.
template <class Phys> constexpr bool pendularFullPhys = std::is_same<Phys, PendularPhys>::value;

template <class Phys> inline bool Law2_ScGeom_PendularPhys_Bridge::breakBridge(Phys& phys, const PendularKinematics& k)
{
	phys.active = false;
	phys.Fcap   = 0;
	if (k.owned) {
		nBridges -= 1;
		liquidVolume -= phys.Vb;
		liquidReleased += phys.Vb;
	}
	if constexpr (pendularFullPhys<Phys>) {
		phys.Fvisc        = 0;
		phys.viscousShear = Vector3r::Zero();
		if (phys.film) {
			// Whether the other body holds a film is read now: filmArea may have changed since the bridge formed.
			const FilmPair ids        = filmPair(phys, k.id1, k.id2);
			const auto*    otherState = static_cast<const PendularState*>(Body::byId(ids.other, scene)->state.get());
			const Real     toSphere   = sphereShare(phys, otherState->holds(phys.R2));
			const std::lock_guard<std::mutex> lock(filmMutex);
			// A bond's liquid goes where PendularBonds' protocol sends it (Richefeu2008 sections 2.4, 3.2, 4.2).
			std::vector<FilmReturn>& to = phys.bonds ? bondReturns : returns;
			to.push_back({ ids.sphere, toSphere, ids.other });
			to.push_back({ ids.other, phys.Vb - toSphere, ids.sphere });
		}
	}
	return false;
}

template <class Geom, class Phys, class Rotate, class Sink>
inline bool Law2_ScGeom_PendularPhys_Bridge::apply(
        const Geom& geom, Phys& phys, const PendularKinematics& k, Real dt, const Rotate& rotate, Sink& sink)
{
	constexpr bool full = pendularFullPhys<Phys>; // else no film, no viscosity and the default contact law
	if (geom.penetrationDepth < 0) { // separated
		phys.shearForce = Vector3r::Zero();
		if (!phys.active) {
			phys.normalForce = Vector3r::Zero();
			// Film mode, formation when the films touch: the pair is kept while they do.
			if constexpr (full)
				if (phys.filmFormation && filmsTouch(phys, k, -geom.penetrationDepth)) {
					if (!phys.pending) askFormation(phys, k);
					return true;
				}
			// No bridge yet (or dry): nothing to keep. Returning false resets the interaction, so the
			// collider removes it once the bounding boxes part, and the Ig2 makes it real again at
			// contact, where the bridge forms; a pair that stays close merely gets new physics.
			return false;
		}
		const Real gap = -geom.penetrationDepth;
		if constexpr (full)
			if (phys.viscous) {
				const PendularViscousMoments m = pendularViscous(geom, phys, k, gap);
				if (gap > phys.sRupture) return breakBridge(phys, k);
				phys.Fcap        = capillary::bridge_force_within(phys.bridge, gap, phys.sRupture);
				phys.normalForce = -(phys.Fcap + phys.Fvisc) * geom.normal;
				sink.forceTorque(phys.normalForce + phys.viscousShear, m.torque1, m.torque2);
				return true;
			}
		// An inviscid separated bridge needs only the gap and the normal: no tangential work, no torque.
		if (gap > phys.bridge.rupture) return breakBridge(phys, k);
		phys.Fcap        = capillary::bridge_force(phys.bridge, gap);
		phys.normalForce = -phys.Fcap * geom.normal;
		sink.force(phys.normalForce);
		return true;
	}

	// kn = 0 only if the Ip2 rejected the contact parameters: reset, so that its error comes again.
	if (!(phys.kn > 0)) return false;
	if (__builtin_expect(geom.penetrationDepth > overlapAlarm, 0)) overlapSeen(geom.penetrationDepth, k.id1, k.id2, phys.kn);
	// In contact. The bridge forms at the first contact (Gladkyy2014 section 2).
	if (phys.wet && !phys.active) {
		bool film = false;
		if constexpr (full) film = phys.film;
		if (!film) {
			phys.active = true;
			if (k.owned) {
				nBridges += 1;
				liquidVolume += phys.Vb;
				liquidFormed += phys.Vb;
			}
		} else if constexpr (full)
			if (!phys.pending) askFormation(phys, k); // formed by settleFilms at the end of the step
	}
	bool twoSpheres = true; // a record is always a sphere-sphere pair
	if constexpr (full) twoSpheres = !phys.swapped && math::isfinite(phys.R2);
	bool viscous = false; // the bridge's viscous forces also act in contact, at S_eff = S_min
	if constexpr (full) viscous = phys.viscous && phys.active;
	phys.Fcap = (phys.active && phys.forceInContact) ? phys.bridge.force0 : 0;
	// Gladkyy2014 eq. (3): linear spring-dashpot; no attraction while unloading (Schwager2007). vn > 0: approaching.
	// approach: the dashpot acts only while approaching (Richefeu2008 eq. 3, printed with the sign of the
	// overlap rate: a dashpot resists the approach), so the force is never below the spring's.
	bool approach = false, viscousFriction = false, rolling = false; // options never on a record (recordable)
	if constexpr (full) approach = phys.approachDamping, viscousFriction = phys.viscousFriction, rolling = phys.rollingFriction > 0;
	const auto springDashpot = [&phys, &geom, approach](Real vn) {
		return math::max(Real(0), phys.kn * geom.penetrationDepth + phys.cn * (approach ? math::max(vn, Real(0)) : vn));
	};
	if (twoSpheres && !(phys.tangensOfFrictionAngle > 0) && !viscous && !rolling) {
		// Frictionless between two spheres: a central force, from the overlap and the normal relative
		// velocity only. The spheres' rotations do not enter it (the arms from the centres to the contact
		// point lie along the normal, so omega x arm is normal to it), and the force has no moment about
		// either centre; so no contact point, arms or cross products (their round-off, in the other
		// branch, gives vn a part of 1e-16 and the spheres round-off torques that spin them).
		// By component: GCC leaves Eigen's assignment loop of this expression out of line (a call per bridge-step).
		const Vector3r dv(k.vel1[0] - k.vel2[0] - k.shiftVel[0], k.vel1[1] - k.vel2[1] - k.shiftVel[1], k.vel1[2] - k.vel2[2] - k.shiftVel[2]);
		const Real     fn = springDashpot(geom.normal.dot(dv));
		phys.shearForce    = Vector3r::Zero(); // the Coulomb cap is 0: no tangential spring or dashpot
		phys.normalForce   = (fn - phys.Fcap) * geom.normal;
		sink.force(phys.normalForce);
		return true;
	}
	const Vector3r c1x    = geom.contactPoint - k.pos1;
	const Vector3r c2x    = geom.contactPoint - k.pos2 - k.shift2;
	// Body 2's periodic image moves with vel2 + shiftVel (ScGeom::getIncidentVel).
	const Vector3r relVel = (k.vel1 + k.angVel1.cross(c1x)) - (k.vel2 + k.angVel2.cross(c2x)) - k.shiftVel;
	const Real     vn     = geom.normal.dot(relVel);
	const Real     fn     = springDashpot(vn);
	Vector3r&  shear = phys.shearForce;
	Vector3r   shearVisc = Vector3r::Zero();
	if (viscousFriction && phys.tangensOfFrictionAngle > 0) {
		// Richefeu2008 eq. (12): the viscous force cs v_s capped by Coulomb, along the sliding velocity; no
		// spring, so nothing to rotate or remember. vs is body 1's velocity relative to body 2 at the contact
		// point, and shear acts on body 2.
		const Vector3r vs    = relVel - vn * geom.normal;
		const Real     speed = vs.norm();
		const Real     maxFs = fn * phys.tangensOfFrictionAngle;
		shear                = speed > 0 ? Vector3r(vs * (math::min(phys.cs * speed, maxFs) / speed)) : Vector3r::Zero();
	} else if (phys.tangensOfFrictionAngle > 0) {
		const Vector3r vs = relVel - vn * geom.normal;
		rotate(shear);
		shear += phys.ks * dt * vs;
		const Real maxFs = fn * phys.tangensOfFrictionAngle;
		if (shear.squaredNorm() > maxFs * maxFs) shear *= maxFs / shear.norm(); // Coulomb slip: elastic part capped, no viscous part
		else shearVisc = phys.cs * vs;
	} else {
		// Frictionless (Gladkyy2014: particle friction 0) with a wall or facet, or with a viscous
		// bridge: the Coulomb cap is 0, so the tangential spring and dashpot would be cut to zero anyway.
		shear = Vector3r::Zero();
	}
	// Rolling friction (Elskamp2018 Table 3, mu_roll [m]): a moment of constant magnitude mu_roll fn against
	// the relative rolling, on body 1; its opposite on body 2. At rest it flips with the residual rolling,
	// whose speed it bounds to mu_roll fn dt (1/I1 + 1/I2).
	Vector3r roll1 = Vector3r::Zero();
	if constexpr (full)
		if (rolling) {
			const Vector3r w     = k.angVel1 - k.angVel2;
			const Vector3r wRoll = w - w.dot(geom.normal) * geom.normal;
			const Real     speed = wRoll.norm();
			if (speed > 0) roll1 = -(phys.rollingFriction * fn / speed) * wRoll;
		}
	if constexpr (full)
		if (viscous) {
			const PendularViscousMoments m = pendularViscous(geom, phys, k, -geom.penetrationDepth);
			phys.normalForce               = (fn - phys.Fcap - phys.Fvisc) * geom.normal;
			const Vector3r f               = phys.normalForce + shear + shearVisc; // acts at the contact point
			sink.forceTorque(f + phys.viscousShear, m.torque1 - c1x.cross(f) + roll1, m.torque2 + c2x.cross(f) - roll1);
			return true;
		}
	// A wall or facet keeps the moment of the force at the contact point about its own position.
	phys.normalForce = (fn - phys.Fcap) * geom.normal;
	const Vector3r f = phys.normalForce + shear + shearVisc;
	if constexpr (full)
		if (rolling) {
			sink.forceTorque(f, roll1 - c1x.cross(f), c2x.cross(f) - roll1);
			return true;
		}
	sink.forceTorque(f, -c1x.cross(f), c2x.cross(f));
	return true;
}

} // namespace yade
