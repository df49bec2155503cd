// PendularLoop: the coordinator of the fused pass (see PendularLoop.hpp): the order of a step's
// phases (action), the gathering of the bodies, the plan of the pass and what follows it, the records' entry
// points from Python. The pass itself, one entry of the container at a time, is in PendularLoop_Pass.cpp.
#include "PendularLoop.hpp"
#include "LoopSort.hpp"

#include <pkg/common/InsertionSortCollider.hpp>

#include <core/Omega.hpp>
#include <mpi.h>

#include <limits>
#include <set>
#include <typeinfo>

#ifdef YADE_OPENMP
#include <omp.h>
#endif

namespace yade {

YADE_PLUGIN((PendularLoop));
CREATE_LOGGER(PendularLoop);
bool PendularLoop::readersGuarded = false;
using Clock = pendular::Clock;
using pendular::prefetchAhead;
using pendular::prefetchObject;


void PendularLoop::resolve(Resolved& r)
{
	static shared_ptr<Shape>    sphere(new Sphere);
	static shared_ptr<Material> material(new PendularMat);
	static shared_ptr<IGeom>    geom(new ScGeom);
	static shared_ptr<IPhys>    phys(new PendularPhys);
	bool                        swap = false;
	const auto                  ig2 = geomDispatcher->getFunctor2D(sphere, sphere, swap);
	const auto                  ip2 = physDispatcher->getFunctor2D(material, material, swap);
	const auto                  law = lawDispatcher->getFunctor2D(geom, phys, swap);
	r.law                           = dynamic_cast<Law2_ScGeom_PendularPhys_Bridge*>(law.get());
	r.ip2                           = dynamic_cast<Ip2_PendularMat_PendularMat_PendularPhys*>(ip2.get());
	// Exactly Ig2_Sphere_Sphere_ScGeom: a subclass (ScGeom6D) makes another geometry.
	if (ig2 && typeid(*ig2) == typeid(Ig2_Sphere_Sphere_ScGeom)) r.ig2 = static_cast<const Ig2_Sphere_Sphere_ScGeom*>(ig2.get());
	r.fused = r.ig2 && r.ip2 && r.law;
}

void PendularLoop::gather(int threads)
{
	const auto&  bodies = scene->bodies->body; // the vector itself: BodyContainer::operator[] is a call into libyade per body
	const size_t n      = bodies.size();
	state.snapshot.begin(n, state.partition.bodyParts);
	state.forces.fitBodies(n);
	// The gap bound's check of every body (see Pairs), in the same pass as the gathering. The bodies of an
	// epoch are those of the pass that started it: taken here, by each thread for its part, from that pass's
	// particles (previous), instead of copied by one thread after it. (A reduction's private copies start at
	// its identity, not at this value: every iteration computes its part.)
	const bool comparable = state.snapshot.previous.size() == n;
	bool       takeEpoch  = false;
	int        restart = state.pairs.startScan(n, comparable, takeEpoch), films = 0;
	// The force container's reset handed over by PendularForceResetter (takeReset): each thread zeroes the
	// summed forces and torques of its part of the bodies below (the cache lines it writes in the pass and
	// reads in PendularIntegrator), the entries of no body after it.
	const pendular::ForceReset reset = state.forces.takeReset(scene, scene->iter);
	// Whether a body's kind or subdomain differs from the last pass's (or the bodies are others): else
	// every record's two bodies are still PendularMat spheres of this subdomain (see visit).
	int                    kindsChanged = 0, clumps = 0, aspherical = 0, subdomains = 0;
	Real                   move2 = 0, rmin = std::numeric_limits<Real>::infinity();
	pendular::BodyReader   reader;
	// Each thread its part of the bodies (bodyParts): the part whose interactions it computes in the pass.
#ifdef YADE_OPENMP
#pragma omp parallel num_threads(threads) if (long(n) >= parallelBodies) reduction(max : restart, films, move2, kindsChanged) reduction(min : rmin) \
        reduction(| : clumps, aspherical, subdomains) firstprivate(reader)
#endif
	{
	const auto part = pendular::partOf(state.partition.bodyParts, long(n), pendular::threadNumber(), pendular::teamSize());
	reset.zero(part.first, part.second);
	// The bodies that other threads' entries reach (sharedBodies, made by shareWork for these parts): see streamStore.
	const bool streaming = state.partition.sharedBodies.size() == n;
	bool       streamed  = false;
	for (size_t id = size_t(part.first); id < size_t(part.second); ++id) {
		pendular::BodySnapshot::prefetch(bodies, id, prefetchAhead);
		// The last pass's particle: a streamed one is in memory only.
		if (streaming && comparable && id + prefetchAhead < n) {
			if (takeEpoch) prefetchObject(&state.snapshot.previous[id + prefetchAhead]);
			else __builtin_prefetch(&state.snapshot.previous[id + prefetchAhead]);
		}
		const auto& b = bodies[id];
		// What PendularIntegrator reads of every body (see pendular::BodyPointers).
		pendular::readBody(b.get(), scene->subdomain, state.snapshot.pointers.states[id], state.snapshot.pointers.bounds[id], clumps, aspherical, subdomains);
		const Particle  p    = reader.read(b.get()); // made in registers, stored once
		const Particle& last = state.snapshot.previous[id];
		streamed |= state.snapshot.store(id, p, streaming && state.partition.sharedBodies[id]);
		kindsChanged = math::max(kindsChanged, int(!comparable || p.kind != last.kind || p.subdomain != last.subdomain));
		state.pairs.observe(id, p, last, takeEpoch, scene->subdomain, restart, films, rmin, move2);
	}
	if (streamed) pendular::streamFence(); // before the region's barrier, after which other threads read them
	}
	reset.zero(long(n), reset.size);
	state.snapshot.finish(scene, scene->iter, clumps, aspherical, subdomains);
	state.snapshot.kindsKept = !kindsChanged;
	state.pairs.endScan(restart, films, math::sqrt(move2), rmin);
}

void PendularLoop::action()
{
	Resolved r;
	prepareStep(r);
	const auto t0      = Clock::now();
	const int  threads = pendular::passThreads(ompThreads);
	// The records belong to one scene, and only to the steps where nothing else reads the objects.
	// Handed back before the gathering: what the objects get from the records is completed from the
	// bodies as the records' last step saw them (RecordStore::store).
	const bool             recording = recordsAllowed(r);
	pendular::RecordStore& records   = state.records;
	if (!records.records.empty() && (!recording || records.scene != scene)) syncObjects(true, true);
	records.scene           = scene;
	loopThread              = std::this_thread::get_id();
	const long colliderRuns = PendularLoop::colliderRuns(*scene);
	records.reconcile(colliderRuns, *scene->interactions, state.pairs.slots, state.snapshot.particles);
	if (sortPending && sortDisorder > 0 && ownsStep(r)) sortInteractions();
	sortPending = false;
	state.forces.useThreads(threads);
	gather(threads); // also zeroes the force arrays after a step that ended before its flush
	const pendular::SummedArrays summed = openContainer(threads);
	const auto                   t1     = Clock::now();
	const PassPlan               plan   = planPass(r, recording, colliderRuns, threads, summed);
	const PassCounts             counts = pass(plan, r);
	finishPass(plan, r, counts, colliderRuns);
	const auto t2 = Clock::now();
	// The flush may read the arrays by parts and borders (parted: each thread computed its part of the list).
	const bool parted = plan.partsValid && counts.teamComplete;
	state.forces.flush(scene->forces, long(state.snapshot.particles.size()), threads, parallelBodies, parted, summed.forces != nullptr,
	                   plan.partsReady && counts.teamComplete, state.partition.bodyParts, state.partition.borders);
	gatherTime += pendular::nanoseconds(t0, t1);
	passTime += pendular::nanoseconds(t1, t2);
	flushTime += pendular::nanoseconds(t2, Clock::now());
}

// The dispatchers on this scene, the functors they choose for PendularMat spheres, the callbacks.
void PendularLoop::prepareStep(Resolved& r)
{
	geomDispatcher->scene = physDispatcher->scene = lawDispatcher->scene = scene;
	geomDispatcher->updateScenePtr();
	physDispatcher->updateScenePtr();
	lawDispatcher->updateScenePtr();
	resolve(r);
	for (const auto& cb : callbacks) {
		cb->scene = scene;
		r.callbacks.push_back(cb->stepInit());
	}
	cellHsize = scene->isPeriodic ? scene->cell->hSize : Matrix3r::Zero();
}

// The force container covers every body and its per-thread entries are summed (addMaxId, sync): the
// pass adds the forces of each thread's part of the bodies into its summed arrays (see ThreadSink).
pendular::SummedArrays PendularLoop::openContainer(int threads)
{
	const long bodies = long(state.snapshot.particles.size());
	if (bodies > 0) {
		scene->forces.addMaxId(Body::id_t(bodies - 1));
		scene->forces.sync();
	}
	const pendular::SummedArrays summed = pendular::summedArrays(scene->forces, bodies);
	state.forces.direct.assign(size_t(threads), pendular::DirectPart {});
	return summed;
}

PendularLoop::PassPlan PendularLoop::planPass(const Resolved& r, bool recording, long colliderRuns, int threads, const pendular::SummedArrays& summed)
{
	// As InteractionLoop: with a collider that does not erase interactions itself, the potential
	// interactions it did not see in this step are skipped.
	removeUnseen = scene->interactions->iterColliderLastRun >= 0 && scene->interactions->iterColliderLastRun == scene->iter;
	PassPlan plan { threads, long(scene->interactions->size()), 0, long(state.snapshot.particles.size()) };
	plan.recording = recording;
	plan.summed    = summed;
	state.pairs.slots.resize(size_t(plan.size));
	state.records.useThreads(threads);
	plan.skipApart      = r.fused && !removeUnseen && !scene->isPeriodic;
	state.forces.pending = true; // until the flush has read and zeroed the force arrays
	// Between two runs of the collider and within one epoch of the bound on potential pairs' gaps
	// (see Pairs), the container is the one of the last pass, and a potential pair whose bound exceeds
	// what the bodies can move in the whole epoch is skipped at every step: the pass visits only the
	// entries of the list (built after the last full pass), in the same order at every step (the
	// container's order on one thread, see WorkPartition on several), so that the forces are summed in
	// the same order, and the skipped entries are counted as the full pass counts them. Anything else
	// that changes the container drops the list: the Python paths through syncScene, sorting, another
	// scene (see Pairs::listValid).
	plan.fast = skipFar && recording && plan.skipApart && !state.pairs.fullCheck && state.pairs.listValid(colliderRuns, *scene->interactions);
	plan.m    = plan.fast ? long(state.pairs.work.size()) : plan.size;
	// The parts of the bodies and of the list, and the borders, are those of this pass. Then a pass on the
	// list whose threads add their own bodies' forces into the container hands the borders over in its own
	// parallel region (partsReady, see ForceAccumulator::handOverBorders), if the whole team runs it.
	plan.partsValid = plan.fast && state.partition.valid(plan.m, threads, plan.bodies);
	plan.partsReady = plan.partsValid && summed.forces;
	plan.handOffAt  = plan.partsReady ? state.partition.nextHandOff(threads) : 0;
	// Shares fixed between two full passes, so that each thread sums the forces on its bodies in the same
	// order at every step of an epoch. The list is shared by the parts of the bodies (WorkPartition, which
	// follows the threads' measured paces: two runs on several threads may differ by round-off, as YADE's
	// collider already makes them on several threads by its parallel insertion); a full pass in
	// interleaved chunks of the container: real and potential interactions are not spread evenly over it
	// (one half per thread left one thread idle a third of the time).
	// A full pass lists the entries that the passes of this epoch may have to visit (see Pairs::buildList)
	// as it visits them, each thread those of its chunks (a list made after the pass would read every slot
	// again, on several threads half of them from another core; docs/performance.md, "The list of a full
	// pass made during the pass"). The gathering ends an epoch unless move < epochMove * rmin, the same
	// product as the threshold: each slot left out has gapBound >= 2 (epochMove rmin) > 2
	// epochDisplacement at every step of the epoch.
	plan.listing   = !plan.fast && skipFar && recording && plan.skipApart;
	plan.threshold = state.pairs.threshold();
	if (plan.listing) state.pairs.startListing(threads, plan.size);
	plan.trace = pendular::BusyTrace(busyTimes, traceBusy, plan.fast, threads);
	return plan;
}

// After the pass: the attributes that count it, the records settled, the list and the parts for the
// passes of the epoch after a full pass.
void PendularLoop::finishPass(const PassPlan& plan, const Resolved& r, PassCounts counts, long colliderRuns)
{
	if (plan.partsValid && counts.teamComplete) ++state.partition.paceSteps;
	if (plan.trace.on) --traceBusy;
	// The skipped entries, counted as the full pass counts them (apart by the bound).
	nSkipped = plan.size - plan.m;
	counts.fused += nSkipped;
	counts.apart += nSkipped;
	counts.bounded += nSkipped;
	if (plan.fast) {
		++nFastPasses;
		counts.disorder = nDisorder; // the container's order has not changed
	}
	nDisorder   = counts.disorder;
	sortPending = sortDisorder > 0 && Real(counts.disorder) > sortDisorder * Real(plan.size);
	nFused      = counts.fused;
	nDispatched = counts.dispatched;
	nApart      = counts.apart;
	nRecorded   = counts.recorded;
	nBounded    = counts.bounded;
	pendular::RecordStore& records = state.records;
	records.seenDt                 = scene->dt; // what the records' shearInc now follows from (RecordStore::shearIncOf)
	records.seenRatcheting         = r.ig2 ? r.ig2->avoidGranularRatcheting : true;
	records.settle(*scene->interactions, state.pairs.slots);
	nWithObjects = long(records.withObjects.size());
	nInvariants  = records.liveInvariants();
	if (!plan.fast && state.pairs.buildList(plan.listing, colliderRuns, *scene->interactions))
		state.partition.share(state.pairs.work, state.pairs.slots, plan.bodies, plan.threads, threadPace);
	records.stale = records.live() > 0;
}


// How many times the scene's colliders have run (InsertionSortCollider::numAction counts the steps it
// is activated in): the only engine that recordsAllowed lets change the container during a run.
long PendularLoop::colliderRuns(const Scene& scene)
{
	long runs = 0;
	for (const auto& e : scene.engines)
		if (const auto* collider = dynamic_cast<const InsertionSortCollider*>(e.get())) runs += collider->numAction;
	return runs;
}

// Which engines may run beside recorded interactions: those known not to read or change the
// interactions' geometry and physics in a step (PyRunner's Python reads them through the wrapped
// attributes, which write the records into the objects first).
bool PendularLoop::recordsAllowed(const Resolved& r) const
{
	return keepRecords && readersGuarded && r.fused && !scene->isPeriodic && ownsStep(r);
}

// The step has no other reader of the interactions than the known engines (see recordsAllowed), no
// interaction callbacks and no other MPI rank (yade.mpy keeps its own lists of interactions).
bool PendularLoop::ownsStep(const Resolved&) const
{
	if (!callbacks.empty()) return false;
	int initialized = 0, finalized = 0, ranks = 1;
	MPI_Initialized(&initialized);
	MPI_Finalized(&finalized);
	if (initialized && !finalized) MPI_Comm_size(MPI_COMM_WORLD, &ranks);
	if (ranks > 1) return false;
	// The engines, by class name, once per engine list (getClassName makes a string per engine and call).
	if (!pendular::sameEngines(ownedEngines, scene->engines)) {
		static const std::set<std::string> known { "ForceResetter", "PendularForceResetter", "InsertionSortCollider", "PendularLoop", "PendularCheck",
			                                   "NewtonIntegrator", "PendularIntegrator", "PyRunner", "RotationEngine", "PendularRotationEngine" };
		int  loops = 0; // another PendularLoop would take the placeholders of this one's records for objects
		bool all   = true;
		for (const auto& e : scene->engines) {
			all = all && (!e || known.count(e->getClassName()));
			loops += e && dynamic_cast<const PendularLoop*>(e.get());
		}
		enginesOwned = all && loops == 1;
	}
	return enginesOwned;
}


// Sorts the container, its slots and the records by (id1, id2) (see LoopSort.hpp); the list of entries
// no longer holds.
void PendularLoop::sortInteractions()
{
	const auto started = Clock::now();
	pendular::sortContainer(*scene->interactions, state.pairs.slots, uint64_t(scene->bodies->size()));
	++nSorts;
	state.records.reorder(state.pairs.slots, state.snapshot.particles);
	state.pairs.workValid = false;
	sortTime += pendular::nanoseconds(started, Clock::now());
}

void PendularLoop::syncObjects(bool drop, bool all)
{
	state.records.sync(drop, all, state.pairs.slots, state.snapshot.particles);
	if (!drop) return;
	state.pairs.workValid = false;
	nWithObjects          = 0;
	nInvariants           = 0;
}

PendularLoop::~PendularLoop() { syncObjects(true, true); }

long PendularLoop::heldBytes() const { return state.heldBytes() + pendular::capacityBytes(threadPace); }

// As a new loop (see SceneState); threadPace, the partition's measure, is a Python attribute.
void PendularLoop::releaseState()
{
	state      = SceneState {};
	threadPace = {};
}

void PendularLoop::releaseScene(Scene* scene)
{
	if (!scene) return;
	if (Omega::instance().isRunning())
		throw std::runtime_error("PendularLoop.release while the simulation runs (O.run()): call O.pause() or O.wait() first");
	syncScene(scene, true, true); // the records into the objects
	for (const auto& e : scene->engines)
		if (auto* loop = dynamic_cast<PendularLoop*>(e.get())) loop->releaseState();
}

void PendularLoop::objectsOf(const shared_ptr<Interaction>& I)
{
	if (!I) return;
	const auto& scene = Omega::instance().getScene();
	for (const auto& e : scene->engines) {
		auto* loop = dynamic_cast<PendularLoop*>(e.get());
		if (!loop || loop->state.records.live() == 0) continue;
		// While it runs, the loop makes and drops the objects of its records (also those of this one).
		if (Omega::instance().isRunning() && std::this_thread::get_id() != loop->loopThread)
			throw std::runtime_error("Interaction.geom/phys while the simulation runs (O.run()): PendularLoop makes the objects of the "
			                         "interactions it computes from its own records between steps; call O.pause() or O.wait() first");
		if (!I->geom || !pendular::holdsPlaceholders(*I)) return;
		if (loop->state.records.makeObjects(I, loop->state.pairs.slots, loop->state.snapshot.particles)) return;
	}
	if (!I->geom || !pendular::holdsPlaceholders(*I)) return; // no records: its own objects
	throw std::runtime_error("Interaction " + std::to_string(I->getId1()) + "-" + std::to_string(I->getId2())
	                         + " holds PendularLoop's placeholders, but no PendularLoop of the current scene has its record");
}

void PendularLoop::syncScene(Scene* scene, bool drop, bool all)
{
	if (!scene) return;
	for (const auto& e : scene->engines) {
		auto* loop = dynamic_cast<PendularLoop*>(e.get());
		if (!loop) continue;
		// Whatever may have changed the container (drop) ends the list of entries to visit, also
		// without records and from another thread (an atomic flag).
		if (drop) loop->state.pairs.workValid = false;
		if (loop->state.records.live() == 0) continue;
		if (Omega::instance().isRunning() && std::this_thread::get_id() != loop->loopThread) {
			// The objects that Python holds keep their last values; nothing may make or write them now.
			if (drop || all)
				throw std::runtime_error("this reads or changes the interactions while the simulation runs (O.run()): PendularLoop writes its "
				                         "records into them between steps; call O.pause() or O.wait() first");
			continue;
		}
		loop->syncObjects(drop, all);
	}
}

void PendularLoop::syncCurrent(bool drop, bool all) { syncScene(Omega::instance().getScene().get(), drop, all); }

void PendularLoop::forgetPotential(Scene* scene)
{
	for (const auto& e : scene->engines) {
		auto* loop = dynamic_cast<PendularLoop*>(e.get());
		if (!loop) continue;
		for (auto& slot : loop->state.pairs.slots)
			if (slot.potential()) {
				slot.record   = Slot::none;
				slot.gapBound = -std::numeric_limits<float>::infinity();
			}
		loop->state.pairs.workValid = false;
	}
}

boost::python::dict PendularLoop::memory() const { return pendular::loopMemory(); }

} // namespace yade