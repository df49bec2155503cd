// PendularLoop: YADE's InteractionLoop with a fused pass for the interactions of yade-capillary.
#pragma once

#include "Passes.hpp"
#include "Pendular.hpp"
#include <core/InteractionLoop.hpp>

#include <boost/python/converter/shared_ptr_deleter.hpp>
#include <boost/weak_ptr.hpp>
#include <atomic>
#include <cstdint>
#include <limits>
#include <thread>
#include <unordered_map>
#include <vector>

namespace yade {

class PendularLoop : public InteractionLoop {
public:
	// What the fused pass needs of one body, gathered once per step into a contiguous array
	// (instead of two shared_ptr hops to a State per interaction). Two whole cache lines: what every
	// bridge-step and every check of a potential pair reads (position, velocity, radius, subdomain,
	// kind) in the first, what only friction and films read in the second; whole lines, so that the
	// bodies that other threads read can be written with streaming stores (see gather).
	struct alignas(64) Particle {
		Vector3r pos, vel;
		Real     radius;
		int      subdomain;
		uint8_t  kind;
		Vector3r angVel;
		Real     reach; // film thickness of a sphere whose bridges form when the films touch (formation='films'), else 0
		// Takes p's values, writing each line only if it changes: a body that does not move costs a read, and
		// the second line of a sphere that does not spin (frictionless) is not written. (A line that another
		// thread read in the last pass is written only after that core's copy is invalidated.)
		void update(const Particle& p)
		{
			if (!(pos == p.pos && vel == p.vel && radius == p.radius && subdomain == p.subdomain && kind == p.kind)) {
				pos       = p.pos;
				vel       = p.vel;
				radius    = p.radius;
				subdomain = p.subdomain;
				kind      = p.kind;
			}
			if (!(angVel == p.angVel && reach == p.reach)) {
				angVel = p.angVel;
				reach  = p.reach;
			}
		}
	};
	enum Kind : uint8_t { missing, other, clump, pendularSphere, pendularBoundary };

	// A sphere-sphere interaction with a fixed-volume inviscid bridge (or none), between two steps:
	// what a step changes of ScGeom and PendularPhys, under their names, in two cache lines, so that a
	// step reads and writes those two lines per interaction instead of the Interaction, ScGeom and
	// PendularPhys objects (about 12, scattered over the heap). What a step does not change (the
	// bridge's invariants and the contact parameters) is shared by every record with the same ones
	// (Invariants, one entry for all the bridges of a monodisperse material); what follows from the
	// record and the bodies (the contact point, the radii) is written only into the objects. The
	// objects are brought up to date whenever something may read them (syncScene).
	struct alignas(64) Record {
		Body::id_t id1, id2; // first: what the pass reads first
		int        invariants; // index in invariants
		bool       active;     // PendularPhys
		bool       isActive;   // Interaction::isActive
		// ScGeom
		Vector3r normal, shearInc;
		Real     penetrationDepth;
		// PendularPhys
		Vector3r normalForce, shearForce;
		Real     Fcap;
	};
	// The members of PendularPhys that a step of a record reads and does not change, and the whole
	// physics they came from (every member but those of the record), from which the objects of a
	// record are made again when something reads them (see makeObjects).
	struct Invariants {
		capillary::Bridge                   bridge;
		Real                                kn, cn, ks, cs, tangensOfFrictionAngle, Vb;
		bool                                wet, forceInContact;
		shared_ptr<const PendularPhys>      prototype;
		long                                users = 0; // records that use it; freed at 0 (see release)
	};

	void action() override;
	// The recorded interactions get their own ScGeom and PendularPhys back (see makeObjects).
	~PendularLoop() override;
	// sizeof of what an interaction and a body cost, for the memory benchmark.
	boost::python::dict memory() const;
	// Brings the Interaction, ScGeom and PendularPhys objects of the records of the PendularLoop
	// engines of `scene` up to date; drop: also forget the records, so that the next step reads the
	// objects again (after anything that may have changed them). all: every recorded interaction gets
	// its own ScGeom and PendularPhys (for C++ code that reads them: O.save, YADE's utils, the liquid
	// accounts), else only those that have them are written (Python reads the attributes of objects it
	// holds). Skipped while the simulation runs in another thread than the caller's (YADE's own objects
	// are not safe to read then either).
	static void syncScene(Scene* scene, bool drop, bool all = true);
	// The same for the current scene (Python: PendularLoop.sync).
	static void syncCurrent(bool drop, bool all = true);
	// Gives the records back to the interactions (as sync with drop) and frees every array the PendularLoop
	// engines of `scene` hold for it, for a scene about to be replaced (O.reset, O.load: yade_capillary.objects
	// wraps them). YADE does not destroy the engines of a scene that O.reset replaces (not even its own
	// InsertionSortCollider; seen with gdb on Debian's YADE 2023.02a), so without this every replaced scene
	// kept its loop's arrays and, through the records, its interactions: 9.5 MB for a 16^3 packing, about
	// 1.5 GB for Gladkyy's cell. A loop used again afterwards starts as a new one.
	static void releaseScene(Scene* scene);
	static void releaseCurrent() { releaseScene(Omega::instance().getScene().get()); }
	// Bytes held by the loop's arrays (their capacities; Python: PendularLoop.heldBytes).
	long heldBytes() const;
	// The ScGeom and PendularPhys of one interaction of the current scene, made from its record if it
	// has none of its own (Python: PendularLoop.objectsOf, called by the wrapped Interaction.geom and
	// .phys). RuntimeError while the simulation runs in another thread.
	static void objectsOf(const shared_ptr<Interaction>& I);
	// Records are kept only once the Python paths that read or change the objects call sync
	// (yade_capillary.patches.install, which yade_capillary.scene.engines calls).
	static bool readersGuarded;
	static void guardReaders() { readersGuarded = true; }
	// What this step's gathering read of every body (see pendular::BodyPointers).
	const pendular::BodyPointers& gatheredBodies() const { return bodyPointers; }
	// What one thread of the pass adds straight into the force container's summed arrays: the forces and
	// torques of the bodies [first, last), its part (see ThreadSink in PendularLoop.cpp).
	struct DirectPart {
		Vector3r *forces = nullptr, *torques = nullptr;
		long      first = 0, last = 0;
		bool      has(Body::id_t id) const { return id >= first && id < last; }
	};
	// The threads of the last hand-over of the forces into the force container (0: none yet) and their parts
	// of the bodies (see pendular::partOf): PendularForceResetter zeroes each part in the thread that wrote it.
	int                      flushTeam() const { return known.flushTeam; }
	const std::vector<long>& flushParts() const { return bodyParts; }
	// The force container's reset of this step, to be done by the gathering (each thread zeroes its part of the
	// bodies), from PendularForceResetter when only colliders run between them (which leave the force container
	// alone); summed: the container's summed arrays, size: their entries.
	void takeReset(const Scene* s, const pendular::SummedArrays& summed, long size) { pendingReset = PendingReset { s, s->iter, summed, size }; }
	void cancelReset() { pendingReset = PendingReset {}; } // a reset done by the resetter (one left by a failed step is dropped)
	DECLARE_LOGGER;

private:
	struct Resolved; // the functors the dispatchers choose for PendularMat spheres, see resolve()
	void resolve(Resolved&);
	void gather(int threads);
	// The counts of one thread's part of a pass (see nFused, nDispatched, nApart, nRecorded, nBounded).
	struct Counts {
		long fused = 0, dispatched = 0, apart = 0, recorded = 0, bounded = 0;
		int  thread = 0; // the OpenMP thread of this part (its force arrays and lists)
	};
	void visit(long i, long ahead1, long ahead2, const Resolved& r, bool skipApart, bool recording, Counts& c);
	void step(const shared_ptr<Interaction>& I, const Resolved& r, Counts& c);
	long colliderRunCount() const;
	void buildWork(bool use, long colliderRuns, int threads);
	void shareWork(int threads);
	void dispatched(const shared_ptr<Interaction>& I, const Resolved& r, int thread);
	void sphereSphere(const shared_ptr<Interaction>& I, const Resolved& r, int thread);
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
	// Ig2_Sphere_Sphere_ScGeom and ScGeom::precompute after the distance, in their order of
	// operations, on an ScGeom or a Record: `normal` the unit vector from centre 1 to centre 2, `depth`
	// the overlap.
	// record: the geometry of a Record, whose shearInc is made only when read (see shearIncrement); without
	// friction the law reads only its gap and normal (no contact point, no rotation axes).
	template <class Geom>
	Rotation sphereGeometry(Geom& geom, const Particle& p1, const Particle& p2, const Vector3r& normal, Real depth, const Vector3r& shift2,
	                        const Vector3r& shiftVel, bool isNew, const Resolved& r, bool record = false, bool friction = true) const;
	// ScGeom::shearInc of two spheres in contact as Ig2_Sphere_Sphere_ScGeom makes it (ScGeom::precompute),
	// from the bodies as a step saw them, the normal, overlap and contact point of that step, and its
	// Ig2's avoidGranularRatcheting and time step. A record keeps shearInc only while its bridge is
	// separated (the value of its last step in contact, where Ig2 last updated it): in contact the law
	// never reads it (it computes the relative velocity itself), so it is made from the bodies when the
	// objects are (store), and kept when the bridge separates (recordStep, from the step before).
	static Vector3r shearIncrement(const Particle& p1, const Particle& p2, const Vector3r& normal, Real depth, const Vector3r& contactPoint,
	                               const Vector3r& shift2, const Vector3r& shiftVel, bool ratcheting, Real dt);
	// The shearInc of a record as of its last step, from `seen`, the particles that step read.
	Vector3r recordShearInc(const Record& rec, const std::vector<Particle>& seen) const;
	// Our law, inline, on the gathered data, into the thread's force arrays; false: reset the interaction.
	template <class Geom, class Phys, class Rotate>
	bool applyLaw(Body::id_t id1, Body::id_t id2, bool isActive, const Geom& geom, Phys& phys, const Resolved& r, const Vector3r& shift2,
	              const Vector3r& shiftVel, const Rotate& rotate, int thread);
	// One step of a recorded interaction; false: reset it.
	bool recordStep(Record& rec, const Resolved& r, int thread);
	bool recordable(const Interaction& I, const Resolved& r) const;
	// A body that records may join: a PendularMat sphere of this scene's subdomain (as gathered this step).
	bool sphereHere(Body::id_t id) const
	{
		const Particle& p = particles[id];
		return p.kind == pendularSphere && p.subdomain == scene->subdomain;
	}
	// Ig2_Sphere_Sphere_ScGeom's contact point: from the centre of body 1 along the normal, at its radius
	// less half the overlap.
	static Vector3r contactPointOf(const Particle& p1, const Vector3r& normal, Real depth) { return p1.pos + (p1.radius - 0.5 * depth) * normal; }
	void load(Record& rec, const shared_ptr<Interaction>& I);
	int  invariantsOf(const PendularPhys& phys);
	static std::string invariantsKey(const PendularPhys& phys);
	// A record no longer uses entry `index` of invariants (freed when none does, so that a polydisperse
	// packing keeps only the entries of the bridges that exist).
	void release(int index);
	// Frees a record whose interaction is reset or has its own objects again.
	void forget(int index);
	// Writes the record into its interaction's objects, made first if the interaction holds the
	// placeholders; true if they were made.
	// seen: the particles of the record's last step (particles between two steps; previous during a pass).
	bool store(const Record& rec, Interaction& I, const std::vector<Particle>& seen) const;
	bool store(const Record& rec, Interaction& I) const { return store(rec, I, particles); }
	void syncObjects(bool drop, bool all);
	void freeArrays();
	template <class Loop, class Visit> static void forEachArray(Loop& loop, Visit&& visit);
	// The recorded interactions whose objects nothing but the interaction holds get the placeholders.
	void dropObjects();
	// After the collider has changed the container: the slot of each record's interaction (Interaction::linIx).
	void reconcile();
	void settleRecords();
	bool recordsAllowed(const Resolved& r) const;
	bool ownsStep(const Resolved& r) const;
	// The engine list ownsStep last looked at, and whether it has only known engines and this loop.
	mutable std::vector<boost::weak_ptr<Engine>> ownedEngines;
	mutable bool                                 enginesOwned = false;
	void sortInteractions();
	void callbacksOn(Interaction& I, const Resolved& r);
	// parted: the pass computed the parts of work, each on its thread (see shareWork); direct: each thread
	// added the forces of its part of the bodies into the force container itself (directParts);
	// bordersDone: and handed the borders over (handOverBorders) in the pass's parallel region.
	void flushForces(int threads, bool parted, bool direct, bool bordersDone);
	// Thread `thread` of a pass by parts adds into the container's summed arrays what the other threads'
	// arrays hold for the bodies of its part (their borders with it), in the order of the arrays, and
	// zeroes those entries.
	void handOverBorders(int thread, const pendular::SummedArrays& summed);

	// Per entry of the interaction container, what the last step saw: the interaction, its ids and
	// whether it was potential. Held by a weak_ptr and compared by owner (control block), not by
	// address: a new interaction allocated where an erased one was is still another owner.
	struct Slot {
		boost::weak_ptr<Interaction> interaction;
		Body::id_t                   id1 = 0, id2 = 0;
		// >= 0: index in records; none: a real interaction without record (or not yet seen); potentialPair.
		int record = none;
		// potentialPair: a lower bound of the surface gap minus 2 epochDisplacement at the start of the
		// epoch [m] (see gather), -inf if unknown; rounded down to float to keep the slot at 32 B.
		float                gapBound = -std::numeric_limits<float>::infinity();
		static constexpr int none = -1, potentialPair = -2;
		bool                 potential() const { return record == potentialPair; }
		bool                 recorded() const { return record >= 0; }
		bool same(const shared_ptr<Interaction>& I) const { return !interaction.owner_before(I) && !I.owner_before(interaction); }
		// The order of sortInteractions: by id1, then id2 (ids are >= 0).
		uint64_t key() const { return (uint64_t(uint32_t(id1)) << 32) | uint32_t(id2); }
	};
	std::vector<Slot>                  slots;
	bool                               removeUnseen = false;
	std::vector<Particle>              particles;
	// The particles of the pass before (gather swaps the two arrays): with Known::seenDt and
	// seenRatcheting, what the shearInc of a record in contact follows from (shearIncrement).
	std::vector<Particle>              previous;
	pendular::BodyPointers             bodyPointers;
	// A body as the check of a potential pair sees it: the centre and the radius plus the reach, signed:
	// > 0 a PendularMat sphere of this subdomain, < 0 (negated) one of another subdomain, 0 any other body.
	// films: some sphere has a reach (else it is 0 and not read: it is on the particle's second line).
	struct Near {
		Vector3r pos;
		Real     radius;
	};
	static Near nearOf(const Particle& p, int subdomain, bool films)
	{
		if (p.kind != pendularSphere) return Near { Vector3r::Zero(), 0 };
		const Real r = films ? p.radius + p.reach : p.radius;
		return Near { p.pos, p.subdomain == subdomain ? r : -r };
	}
	// The bodies as of the start of the epoch of the bound on potential pairs' gaps (see gather).
	std::vector<Near>                  epoch;
	// Per body: reached by the entries of another thread's part of the list (see shareWork), so gathered
	// with streaming stores (see gather); empty: none.
	std::vector<uint8_t>               sharedBodies;
	// The container entries a pass of this epoch may have to visit (see buildWork; valid: Known says
	// what for). Atomic: the wrapped Python paths drop it from other threads.
	std::vector<long>                  work;
	// What a full pass lists for work: per thread, the entries it listed; per chunk of the pass's schedule,
	// the thread that visited it and the end of the chunk's entries in that thread's list (see buildWork).
	struct ChunkEnd {
		int  thread = 0;
		long end    = 0;
	};
	std::vector<std::vector<long>> listed;
	std::vector<ChunkEnd>          chunkEnds;
	// A potential pair that a pass of this epoch skips: its bound on the gap exceeds `threshold`, twice the
	// largest move of the epoch (see buildWork). Asked of a slot just visited, which holds its entry's
	// interaction (visit makes it so).
	static bool listedOut(const Slot& slot, Real threshold) { return slot.potential() && Real(slot.gapBound) >= threshold; }
	std::atomic<bool>                  workValid { false };
	// The threads' parts of the bodies and of work (see shareWork; empty: even parts); borders[k][t]: the
	// bodies of part t that the entries of part k reach (ascending). Part k of work lists first its entries
	// that reach another part, up to workBorders[k], then those within the part.
	std::vector<long>                                bodyParts, workParts, workBorders;
	// Per thread of a pass on the list by parts, the last pass (handOffPass) whose entries that reach other
	// parts it has computed: the owners of those bodies then hand them over (handOverBorders) while it
	// computes the rest of its part. One cache line each: the others spin on it.
	struct alignas(64) HandOff {
		std::atomic<long> pass { 0 };
	};
	std::vector<HandOff> handOffs; // made whole for a team (HandOff is not movable), never resized
	long                 handOffPass = 0;
	std::vector<std::vector<std::vector<Body::id_t>>> borders;
	// What shareWork computes them from, kept between its calls: each body's estimated cost and part, and
	// the parts whose entries reach it from another part (a bit per part).
	std::vector<float>                               shareCost;
	std::vector<int>                                 bodyPart;
	std::vector<uint64_t>                            reachedBy;
	// Each thread's pace (threadPace) is measured in the passes on the list since the last shareWork: the wall
	// time of its own entries and of its hand-over where the pass does it (partsReady), without its waits
	// (paceTime, over paceSteps passes), per unit of the estimated cost of its part (partCost).
	std::vector<float>     partCost;
	std::vector<double>    paceTime;
	long                   paceSteps    = 0;
	static constexpr long  minPaceSteps = 8;  // passes measured before a share follows them
	static constexpr Real  maxPace      = 4;  // at most this many times the others' (a thread held up by others' processes)
	// What the loop knows of its scene between two passes, besides its arrays. A loop whose arrays are
	// freed (freeArrays) starts again from these values, as a new loop.
	struct Known {
		// The bound on potential pairs' gaps (see gather): the largest distance a body has moved since
		// the start of the epoch [m], the smallest sphere radius of the epoch [m] and the epoch's number;
		// fullCheck: every potential pair is checked this step.
		Real epochDisplacement = 0, epochRmin = 0;
		long epochCount        = 0;
		bool fullCheck         = true;
		// epochPending: the last pass started an epoch, whose bodies the next gathering takes from the particles
		// of that pass (previous); films: some sphere gathered by the last gathering has a film's reach.
		bool epochPending = false, films = false;
		// No body's kind or subdomain changed since the last pass (the records' bodies then need no check).
		bool bodiesKept = false;
		// What work was built for: the epoch, the collider's runs, the container and its size.
		long                        workEpoch = -1, workColliderRuns = -1;
		const InteractionContainer* workContainer = nullptr;
		size_t                      workSize      = 0;
		// The collider's runs and the container the slots of the records were last matched to (reconcile).
		long                        reconciledRuns      = -1;
		const InteractionContainer* reconciledContainer = nullptr;
		size_t                      reconciledSize      = 0;
		// The last pass's time step and Ig2's avoidGranularRatcheting (see previous).
		Real seenDt         = 0;
		bool seenRatcheting = true;
		// The scene of the records; stale: the records are newer than the objects; placeholders: some
		// recorded interaction may hold the placeholders.
		Scene* recordScene  = nullptr;
		bool   stale        = false;
		bool   placeholders = false;
		// A pass has added to the force arrays and no flush has read them since (a step that ended in between).
		bool forcesPending = false;
		// The threads of the last flush (0: none since the loop started; see flushTeam).
		int flushTeam = 0;
	};
	Known                              known;
	// The reset that takeReset handed to this step's gathering (scene nullptr: none).
	struct PendingReset {
		const Scene*           scene = nullptr;
		long                   iter  = -1;
		pendular::SummedArrays summed;
		long                   size = 0;
	};
	PendingReset pendingReset;
	// A potential pair apart by the bound alone: its gap at its last check, less what the bodies can have
	// moved since, is still positive (see gather), so nothing of it is read but the slot.
	bool apartByBound(const Slot& slot) const { return !known.fullCheck && slot.gapBound > 2 * known.epochDisplacement; }
	// Per OpenMP thread, per body id; zero between steps (the flush zeroes what it read, see Known::forcesPending).
	std::vector<std::vector<Vector3r>> threadForce, threadTorque;
	std::vector<DirectPart>            directParts; // per OpenMP thread of the pass
	// The records, their interactions (kept alive while recorded; read only when loaded, stored or
	// reset) and their free entries. Changed only between the passes. A recorded interaction holds
	// two placeholders shared by all (so that YADE's collider sees it real) instead of its own ScGeom
	// and PendularPhys, which are made from the record when something reads them (store) and dropped
	// again after the next pass if nothing else holds them (dropObjects): withObjects lists the
	// records that may have their own.
	std::vector<Record>                            records;
	std::vector<shared_ptr<Interaction>>           recordInteractions;
	// The distinct invariants of the records, and where each is, by the PendularPhys members they
	// are made from (see invariantsOf).
	std::vector<Invariants>                        invariants;
	std::unordered_map<std::string, int>           invariantsIndex;
	std::vector<int>                               freeRecords, freeInvariants;
	std::vector<int>                               withObjects;
	long liveRecords() const { return long(records.size()) - long(freeRecords.size()); }
	std::vector<std::vector<long>>                 toRecord;   // per thread: container entries to record after the pass
	std::vector<std::vector<int>>                  toForget;   // per thread: records to free after the pass
	std::thread::id                                loopThread;
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
		((long, nBounded, 0, Attr::readonly, "Of nApart, the potential interactions found apart by the bound on their gap alone in the last step [-], without reading the bodies (the bound: the gap at the last check minus how far the bodies can have moved since)."))
		((long, nRecorded, 0, Attr::readonly, "Of nFused, the interactions computed from the loop's own records in the last step [-] (see keepRecords)."))
		((long, nInvariants, 0, Attr::readonly | Attr::noSave, "Distinct sets of bridge and contact parameters that the records used after the last step [-] (one for all the bridges of a monodisperse material; an entry is freed with its last record)."))
		((long, nWithObjects, 0, Attr::readonly | Attr::noSave, "Of nRecorded, the interactions that still had their own ScGeom and PendularPhys after the last step [-]: those held by Python (the others hold two shared placeholders, and theirs are made from the record when read, see keepRecords)."))
		((Real, sortDisorder, 0.1, , "Fraction of the interaction container's entries out of (id1, id2) order in a step [-] above which the loop sorts YADE's interaction container by (id1, id2) before its next pass, so that consecutive interactions read nearby bodies and records (the collider appends new interactions at the end, erasures move the last entry into the hole); 0: never. Only with engines known not to depend on the container's order (as for keepRecords), without callbacks and MPI. The order of the container is the order in which the forces on a body are summed: runs with and without sorting differ by round-off."))
		((long, nDisorder, 0, Attr::readonly, "Entries of the interaction container found after an entry with larger (id1, id2) in the last step [-] (see sortDisorder)."))
		((long, nSorts, 0, Attr::readonly, "How many times the loop has sorted the interaction container [-] (see sortDisorder)."))
		((bool, sortPending, false, Attr::hidden, "The last pass found more than sortDisorder of the container out of order: sort before the next one (saved, so that a run continued from O.save sorts where the original run does)."))
		((Real, sortTime, 0, , "Wall time spent sorting the interaction container since this was last set to 0 [ns] (part of passTime)."))
		((bool, skipFar, true, , "Between two runs of the collider, visit only the entries of the interaction container that a step may have to compute: the potential pairs whose bound on the gap (see nBounded) exceeds what the bodies can move before the bound is renewed are left out of a list of entries made after each full pass, so that the pass no longer reads their container entries and slots at every step. Same results bit for bit on one thread (the entries are visited in the container's order; on several threads the entries are shared out differently, so the force sums differ by round-off; nFused, nApart and nBounded count the skipped ones as before); only with records (keepRecords), and the list is dropped by anything that may change the container (the collider, sorting, the wrapped Python paths). False: every entry at every step."))
		((long, nSkipped, 0, Attr::readonly, "Of nBounded, the entries of the interaction container not visited at all in the last step [-] (see skipFar)."))
		((long, nFastPasses, 0, Attr::readonly, "Steps in which the pass visited only its list of entries [-] (see skipFar)."))
		((std::vector<Real>, threadPace, , Attr::readonly | Attr::noSave, "On several threads, each thread's pace in the passes on the list, relative to the others' (about 1 on average) [-]: the wall time of its own entries and of its hand-over of the others' forces on its bodies (not its waits) per unit of its part's estimated cost, measured between two shares of the work and smoothed (half the last value); each thread gets a share of the estimated cost inversely proportional to it (between 1/4 and 4), so that the threads finish their entries and hand-overs together where the estimate or a core's speed is off. Empty on one thread."))
		((long, traceBusy, 0, Attr::noSave, "Passes on the list (see skipFar) still to be traced in busyTimes [-]: set it to n to record each thread's busy time in the next n such passes (decremented at each; 0: none). For benchmark.thread_noise, which measures how the threads' times vary from step to step."))
		((std::vector<Real>, busyTimes, , Attr::readonly | Attr::noSave, "Each thread's busy time in each traced pass on the list [ns], pass after pass, one value per thread of the pass (its ompThreads) in thread order: the wall time of its own entries and of its hand-over of the other threads' forces on its bodies, without its waits (what threadPace measures); NaN for a thread that OpenMP did not give the pass. Appended to, so that a run's values are those after the length it had before."))
		((bool, keepRecords, true, , "Keep the state of sphere-sphere interactions without film or viscosity in the loop's own contiguous array between steps; their interactions hold two placeholders shared by all instead of their own ScGeom and PendularPhys, which are made from the record when read (from Python, by O.save, by YADE's utils functions) and dropped after the next step unless Python still holds them (176 B per recorded bridge instead of 816); only once yade_capillary.patches.install(records=True) has wrapped those paths (yade_capillary.scene.engines() calls it; engines(records=False) sets this to False and installs only the patches that leave YADE's results as they are), with engines known not to read the interactions during the run (ForceResetter, InsertionSortCollider, PendularCheck, NewtonIntegrator, PendularIntegrator, PyRunner, RotationEngine), without interaction callbacks, periodic cell or MPI. False: the objects are read and written at every step."))
		((long, parallelBodies, 1000, , "From this many bodies on, the per-body phases (gathering the bodies, zeroing the force arrays, handing the forces over) run on ompThreads threads, below it on one [-]: a parallel region costs more than a short pass (./run.sh bench compares 1000, the default, with 20000, the earlier one, on the ci cell: on two threads its 2 200 bodies gain 8-11 %)."))
		((Real, gatherTime, 0, , "Wall time spent gathering the bodies' positions and velocities since this was last set to 0 [ns]."))
		((Real, passTime, 0, , "Wall time spent in the pass over the interactions since this was last set to 0 [ns]."))
		((Real, flushTime, 0, , "Wall time spent handing the summed forces to the force container since this was last set to 0 [ns].")),
		/*ctor*/,
		/*py*/
		.def("sync", &PendularLoop::syncCurrent, (boost::python::arg("drop") = false, boost::python::arg("all") = true), "Write the loop's records into the Interaction, ScGeom and PendularPhys objects of the current scene (drop: and read the objects again at the next step; all: make the objects of every recorded interaction first, else write only those that exist). Called by the wrapped Python paths that read or change them (attributes of the geometry and physics, O.save, yade.utils functions); not needed in user code.")
		.staticmethod("sync")
		.def("release", &PendularLoop::releaseCurrent, "Give the records of the PendularLoop engines of the current scene back to its interactions and free every array they hold for it (called by the wrapped O.reset, O.load and O.loadTmp before the scene is replaced: YADE keeps the engines of a replaced scene alive); not needed in user code.")
		.staticmethod("release")
		.def("heldBytes", &PendularLoop::heldBytes, "Bytes held by the loop's arrays for its scene [B] (per-body, per-interaction and per-record arrays, by capacity): 0 after release.")
		.def("objectsOf", &PendularLoop::objectsOf, (boost::python::arg("interaction")), "Make the ScGeom and PendularPhys of a recorded interaction of the current scene from its record, if it holds the placeholders. Called by the wrapped Interaction.geom and Interaction.phys; not needed in user code.")
		.staticmethod("objectsOf")
		.def("readersGuarded", &PendularLoop::guardReaders, "Declare that the Python paths that read or change interactions call sync (yade_capillary.patches.install(records=True) does it); before, no records are kept.")
		.staticmethod("readersGuarded")
		.def("memory", &PendularLoop::memory, "sizeof in bytes of the objects of one interaction (Interaction, ScGeom, PendularPhys, YADE's ViscElCapPhys for comparison), of the fused pass's slot per interaction (slot), of a record (record: its entry in the record array and its pointer to the interaction; a recorded interaction has no ScGeom and PendularPhys of its own unless they are read; invariants: once per distinct set of bridge and contact parameters, with its prototype physics, PendularPhys) and of its per-body arrays (particle: gathered body data of this step and the last; epoch: centre and radius at the start of the epoch of the bound on potential pairs' gaps; forces: force and torque per thread).")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularLoop);

} // namespace yade
