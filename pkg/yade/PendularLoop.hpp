// PendularLoop: YADE's InteractionLoop with a fused pass for the interactions of yade-capillary. The
// loop coordinates its parts, each the owner of its arrays (see their files): the body snapshot
// (LoopBodies.hpp), the pairs with the gap bound and the list of entries to visit (LoopPairs.hpp), the
// work partition between threads (LoopPartition.hpp), the record store (LoopRecords.hpp), the force
// accumulation (LoopForces.hpp), the container sort (LoopSort.hpp), the sphere geometry
// (LoopGeometry.hpp) and the instrumentation (LoopInstrumentation.hpp). It keeps the order of a step's
// phases (action, PendularLoop.cpp), the per-interaction pass (visit and what it calls) with YADE's
// dispatch for the other interactions (PendularLoop_Pass.cpp), and the entry points from Python.
#pragma once

#include "LoopBodies.hpp"
#include "LoopForces.hpp"
#include "LoopGeometry.hpp"
#include "LoopInstrumentation.hpp"
#include "LoopPairs.hpp"
#include "LoopPartition.hpp"
#include "LoopRecords.hpp"
#include "Passes.hpp"
#include "Pendular.hpp"
#include <core/InteractionLoop.hpp>

#include <boost/weak_ptr.hpp>
#include <thread>
#include <vector>

namespace yade {

class PendularLoop : public InteractionLoop {
public:
	using Particle = pendular::Particle;
	using Record   = pendular::Record;

	void action() override;
	// The recorded interactions get their own ScGeom and PendularPhys back (see RecordStore::sync).
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
	// Forgets what the PendularLoop engines of `scene` know of its potential interactions (their bounds
	// on the gap, the list of entries to visit): for code that makes potential interactions real between
	// passes (PendularBonds), which the pass would otherwise skip as apart.
	static void forgetPotential(Scene* scene);
	// How many times the colliders of `scene` have run (InsertionSortCollider::numAction).
	static long colliderRuns(const Scene& scene);
	// Gives the records back to the interactions (as sync with drop) and frees every array the PendularLoop
	// engines of `scene` hold for it, for a scene about to be replaced (O.reset, O.load: yade_capillary.objects
	// wraps them). YADE 2023.02a does not destroy the engines of a scene that O.reset replaces (not even its
	// own InsertionSortCollider), so without this every replaced scene would keep its loop's arrays and,
	// through the records, its interactions: megabytes for a small packing, gigabytes for Gladkyy's cell
	// (tests/yade/test_records.py checks heldBytes). A loop used again afterwards starts as a new one.
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
	const pendular::BodyPointers& gatheredBodies() const { return state.snapshot.pointers; }
	// The threads of the last hand-over of the forces into the force container (0: none yet) and their parts
	// of the bodies (see pendular::partOf): PendularForceResetter zeroes each part in the thread that wrote it.
	int                      flushTeam() const { return state.forces.team; }
	const std::vector<long>& flushParts() const { return state.partition.bodyParts; }
	// The force container's reset of this step, to be done by the gathering (each thread zeroes its part of the
	// bodies), from PendularForceResetter when only colliders run between them (which leave the force container
	// alone); summed: the container's summed arrays, size: their entries.
	void takeReset(const Scene* s, const pendular::SummedArrays& summed, long size) { state.forces.reset = pendular::ForceReset { s, s->iter, summed, size }; }
	void cancelReset() { state.forces.reset = pendular::ForceReset {}; } // a reset done by the resetter (one left by a failed step is dropped)
	DECLARE_LOGGER;

private:
	using Slot = pendular::Slot;
	// The functors YADE's dispatchers choose for two PendularMat spheres, resolved once per step with
	// sample objects (a dispatcher resolves by class only, see resolve()). The fused pass is used only when
	// they are exactly the functors it reproduces.
	struct Resolved {
		const Ig2_Sphere_Sphere_ScGeom*           ig2 = nullptr;
		Ip2_PendularMat_PendularMat_PendularPhys* ip2 = nullptr;
		Law2_ScGeom_PendularPhys_Bridge*          law = nullptr; // also for walls and facets
		bool                                      fused = false;
		vector<IntrCallback::FuncPtr>             callbacks;
	};
	void resolve(Resolved&);
	// Everything the loop holds for its scene, by part. A loop whose scene is released starts again from
	// SceneState {}, as a new loop: the gathering starts an epoch (no epoch bodies), the pass visits every
	// entry, no records. Capacities are not kept: a released scene frees its arrays.
	struct SceneState {
		pendular::BodySnapshot     snapshot;
		pendular::Pairs            pairs;
		pendular::WorkPartition    partition;
		pendular::RecordStore      records;
		pendular::ForceAccumulator forces;
		long                       heldBytes() const
		{
			return snapshot.heldBytes() + pairs.heldBytes() + partition.heldBytes() + records.heldBytes() + forces.heldBytes();
		}
	};
	SceneState state;
	void       releaseState();
	// Per step: the potential interactions that the collider did not see in this step are skipped (see
	// action), the periodic cell's hSize.
	bool     removeUnseen = false;
	Matrix3r cellHsize    = Matrix3r::Zero();
	// The thread of the last step (objectsOf and syncScene refuse other threads while it runs).
	std::thread::id loopThread;
	// The engine list ownsStep last looked at, and whether it has only known engines and this loop.
	mutable std::vector<boost::weak_ptr<Engine>> ownedEngines;
	mutable bool                                 enginesOwned = false;

	// The phases of a step, in the order of action().
	void prepareStep(Resolved& r);
	void gather(int threads);
	pendular::SummedArrays openContainer(int threads);
	// What a pass is to do, decided before it (see planPass).
	struct PassPlan {
		int                    threads = 1;
		long                   size = 0, m = 0, bodies = 0; // entries of the container, of this pass, bodies
		bool                   recording = false, skipApart = false;
		bool                   fast = false, listing = false; // on the list; making the list
		bool                   partsValid = false, partsReady = false;
		long                   handOffAt  = 0;
		Real                   threshold  = 0; // see Pairs::threshold
		pendular::SummedArrays summed;
		pendular::BusyTrace    trace;
	};
	// The counts of one thread's part of a pass (see nFused, nDispatched, nApart, nRecorded, nBounded).
	struct Counts {
		long fused = 0, dispatched = 0, apart = 0, recorded = 0, bounded = 0;
		int  thread = 0; // the OpenMP thread of this part (its force arrays and lists)
	};
	// Their sums over the threads, with the entries out of order and whether the whole team ran.
	struct PassCounts {
		long fused = 0, dispatched = 0, apart = 0, recorded = 0, bounded = 0, disorder = 0;
		bool teamComplete = true;
	};
	PassPlan   planPass(const Resolved& r, bool recording, long colliderRuns, int threads, const pendular::SummedArrays& summed);
	PassCounts pass(const PassPlan& plan, const Resolved& r);
	void       passOnList(const PassPlan& plan, const Resolved& r, Counts& c);
	long       passAll(const PassPlan& plan, const Resolved& r, Counts& c);
	void       finishPass(const PassPlan& plan, const Resolved& r, PassCounts counts, long colliderRuns);

	// One entry of the container, and what it calls.
	void visit(long i, long ahead1, long ahead2, const Resolved& r, bool skipApart, bool recording, Counts& c);
	void prefetchEntries(long ahead1, long ahead2, bool skipApart, int thread) const;
	bool visitRecorded(const shared_ptr<Interaction>& I, Slot& slot, const Resolved& r, Counts& c);
	bool checkApart(Slot& slot, Counts& c) const;
	void step(const shared_ptr<Interaction>& I, const Resolved& r, Counts& c);
	void sphereSphere(const shared_ptr<Interaction>& I, const Resolved& r, int thread);
	void dispatched(const shared_ptr<Interaction>& I, const Resolved& r, int thread);
	// One step of a recorded interaction; false: reset it.
	bool recordStep(Record& rec, const Resolved& r, int thread);
	// Our law, inline, on the gathered data, into the thread's force arrays; false: reset the interaction.
	template <class Geom, class Phys, class Rotate>
	bool applyLaw(Body::id_t id1, Body::id_t id2, bool isActive, const Geom& geom, Phys& phys, const Resolved& r, const Vector3r& shift2,
	              const Vector3r& shiftVel, const Rotate& rotate, int thread);
	void callbacksOn(Interaction& I, const Resolved& r);

	// Whether the records may be kept, the interaction recorded, the step owned by known engines.
	bool recordsAllowed(const Resolved& r) const;
	bool recordable(const Interaction& I, const Resolved& r) const;
	bool ownsStep(const Resolved& r) const;
	// A body that records may join: a PendularMat sphere of this scene's subdomain (as gathered this step).
	bool sphereHere(Body::id_t id) const { return state.snapshot.sphereHere(id, scene->subdomain); }
	void sortInteractions();
	void syncObjects(bool drop, bool all);

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
