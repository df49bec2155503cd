#include "PendularLoop.hpp"
#include "LoopInstrumentation.hpp"
#include "Passes.hpp"

#include <pkg/common/Facet.hpp>
#include <pkg/common/InsertionSortCollider.hpp>
#include <pkg/common/Wall.hpp>
#include <pkg/dem/Ig2_Sphere_Sphere_ScGeom.hpp>

#include <pkg/dem/ViscoelasticCapillarPM.hpp>

#include <core/Omega.hpp>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <type_traits>
#include <typeinfo>

#ifdef YADE_OPENMP
#include <omp.h>
#endif

namespace yade {

YADE_PLUGIN((PendularLoop));
CREATE_LOGGER(PendularLoop);
bool PendularLoop::readersGuarded = false;

namespace {
	// An interaction is three heap objects (Interaction, ScGeom, PendularPhys, ~700 B over 11 cache
	// lines): prefetched this many interactions ahead, the Interaction itself twice as far.
	using pendular::prefetchObject;
	constexpr long prefetchAhead = 8;
	// Sorts (key, entry) pairs by key, key = id1 << 32 | id2 (see Slot::key), id1 below `bound` (the
	// number of bodies): a counting pass by id1, then by id2 within each id1 (a few entries each), in
	// linear time instead of std::sort's n log n at nearly every run of the collider (docs/performance.md,
	// "Counting sort"). Keys are unique pairs of ids, so the result is the one sorted order.
	void sortByKey(std::vector<std::pair<uint64_t, size_t>>& order, uint64_t bound)
	{
		uint64_t largest = 0;
		for (const auto& entry : order)
			largest = std::max(largest, entry.first >> 32);
		if (largest >= bound) { // not ids of the scene's bodies: no counting array that large
			std::sort(order.begin(), order.end());
			return;
		}
		std::vector<size_t> start(size_t(largest) + 2, 0);
		for (const auto& entry : order)
			++start[size_t(entry.first >> 32) + 1];
		for (size_t id = 1; id < start.size(); ++id)
			start[id] += start[id - 1];
		std::vector<std::pair<uint64_t, size_t>> byId1(order.size());
		for (const auto& entry : order)
			byId1[start[size_t(entry.first >> 32)]++] = entry;
		for (size_t first = 0, id = 0; id + 1 < start.size(); ++id) { // start[id] is now the end of id1 = id
			std::sort(byId1.begin() + long(first), byId1.begin() + long(start[id]));
			first = start[id];
		}
		order.swap(byId1);
	}

	// What a recorded interaction holds instead of its own ScGeom and PendularPhys: one pair for all,
	// never read or written by the loop (the record is the state). YADE's collider only asks whether an
	// interaction has both (Interaction::isReal); a law that ever read them would find kn = 0 and reset
	// the interaction (our law's check of rejected contact parameters) rather than compute with them.
	const shared_ptr<IGeom>& placeholderGeom()
	{
		static const shared_ptr<IGeom> geom(new ScGeom());
		return geom;
	}
	const shared_ptr<IPhys>& placeholderPhys()
	{
		static const shared_ptr<IPhys> phys(new PendularPhys());
		return phys;
	}
	bool holdsPlaceholders(const Interaction& I) { return I.geom == placeholderGeom(); }

	// The force and torques of one interaction, into its thread's direct part or arrays (see
	// pendular::ForceAccumulator). In this unnamed namespace: the law's apply instantiated with it has
	// internal linkage, so that GCC inlines it into the pass (as a function with external linkage, it
	// stays a call per bridge-step).
	struct ThreadSink {
		const pendular::DirectPart& direct;
		Vector3r *        forces, *torques;
		Body::id_t        id1, id2;
		bool              enabled; // Interaction::isActive
		__attribute__((always_inline)) Vector3r& forceOf(Body::id_t id) const { return direct.has(id) ? direct.forces[id] : forces[id]; }
		__attribute__((always_inline)) Vector3r& torqueOf(Body::id_t id) const { return direct.has(id) ? direct.torques[id] : torques[id]; }
		// Inlined: called once per bridge-step, a call cost more than the six additions.
		__attribute__((always_inline)) void force1(const Vector3r& f) const
		{
			forceOf(id1) -= f;
			forceOf(id2) += f;
		}
		__attribute__((always_inline)) void forceTorque(const Vector3r& f, const Vector3r& t1, const Vector3r& t2) const
		{
			if (!enabled) return;
			force1(f);
			torqueOf(id1) += t1;
			torqueOf(id2) += t2;
		}
		__attribute__((always_inline)) void force(const Vector3r& f) const
		{
			if (enabled) force1(f);
		}
	};

} // namespace

// The functors YADE's dispatchers choose for two PendularMat spheres, resolved once per step with
// sample objects (a dispatcher resolves by class only). The fused pass is used only when they are
// exactly the functors it reproduces.
struct PendularLoop::Resolved {
	const Ig2_Sphere_Sphere_ScGeom*          ig2 = nullptr;
	Ip2_PendularMat_PendularMat_PendularPhys* ip2 = nullptr;
	Law2_ScGeom_PendularPhys_Bridge*         law = nullptr; // also for walls and facets
	bool                                     fused = false;
	vector<IntrCallback::FuncPtr>            callbacks;
};

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
	snapshot.begin(n, partition.bodyParts);
	forceSums.fitBodies(n);
	// The gap bound's check of every body (see Pairs), in the same pass as the gathering. The bodies of an
	// epoch are those of the pass that started it: taken here, by each thread for its part, from that pass's
	// particles (previous), instead of copied by one thread after it. (A reduction's private copies start at
	// its identity, not at this value: every iteration computes its part.)
	const bool comparable = snapshot.previous.size() == n;
	bool       takeEpoch  = false;
	int        restart = pairs.startScan(n, comparable, takeEpoch), films = 0;
	// The force container's reset handed over by PendularForceResetter (takeReset): each thread zeroes the
	// summed forces and torques of its part of the bodies below (the cache lines it writes in the pass and
	// reads in PendularIntegrator), the entries of no body after it.
	const pendular::ForceReset reset = forceSums.takeReset(scene, scene->iter);
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
	const auto part = pendular::partOf(partition.bodyParts, long(n), pendular::threadNumber(), pendular::teamSize());
	reset.zero(part.first, part.second);
	// The bodies that other threads' entries reach (sharedBodies, made by shareWork for these parts): see streamStore.
	const bool streaming = partition.sharedBodies.size() == n;
	bool       streamed  = false;
	for (size_t id = size_t(part.first); id < size_t(part.second); ++id) {
		pendular::BodySnapshot::prefetch(bodies, id, prefetchAhead);
		// The last pass's particle: a streamed one is in memory only.
		if (streaming && comparable && id + prefetchAhead < n) {
			if (takeEpoch) prefetchObject(&snapshot.previous[id + prefetchAhead]);
			else __builtin_prefetch(&snapshot.previous[id + prefetchAhead]);
		}
		const auto& b = bodies[id];
		// What PendularIntegrator reads of every body (see pendular::BodyPointers).
		pendular::readBody(b.get(), scene->subdomain, snapshot.pointers.states[id], snapshot.pointers.bounds[id], clumps, aspherical, subdomains);
		const Particle  p    = reader.read(b.get()); // made in registers, stored once
		const Particle& last = snapshot.previous[id];
		streamed |= snapshot.store(id, p, streaming && partition.sharedBodies[id]);
		kindsChanged = math::max(kindsChanged, int(!comparable || p.kind != last.kind || p.subdomain != last.subdomain));
		pairs.observe(id, p, last, takeEpoch, scene->subdomain, restart, films, rmin, move2);
	}
	if (streamed) pendular::streamFence(); // before the region's barrier, after which other threads read them
	}
	reset.zero(long(n), reset.size);
	snapshot.finish(scene, scene->iter, clumps, aspherical, subdomains);
	snapshot.kindsKept = !kindsChanged;
	pairs.endScan(restart, films, math::sqrt(move2), rmin);
}

void PendularLoop::action()
{
	geomDispatcher->scene = physDispatcher->scene = lawDispatcher->scene = scene;
	geomDispatcher->updateScenePtr();
	physDispatcher->updateScenePtr();
	lawDispatcher->updateScenePtr();
	Resolved r;
	resolve(r);
	for (const auto& cb : callbacks) {
		cb->scene = scene;
		r.callbacks.push_back(cb->stepInit());
	}
	cellHsize       = scene->isPeriodic ? scene->cell->hSize : Matrix3r::Zero();
	using Clock     = std::chrono::steady_clock;
	const auto ns   = [](Clock::time_point a, Clock::time_point b) { return Real(std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count()); };
	const auto t0   = Clock::now();
	const int threads = pendular::passThreads(ompThreads);
	// The records belong to one scene, and only to the steps where nothing else reads the objects.
	// Handed back before the gathering: what the objects get from the records is completed from the
	// bodies as the records' last step saw them (store).
	const bool recording = recordsAllowed(r);
	if (!records.empty() && (!recording || known.recordScene != scene)) syncObjects(true, true);
	known.recordScene       = scene;
	loopThread              = std::this_thread::get_id();
	const long colliderRuns = colliderRunCount();
	if (liveRecords() > 0
	    && (colliderRuns != known.reconciledRuns || scene->interactions.get() != known.reconciledContainer
	        || scene->interactions->size() != known.reconciledSize))
		reconcile();
	known.reconciledRuns      = colliderRuns;
	known.reconciledContainer = scene->interactions.get();
	known.reconciledSize      = scene->interactions->size();
	if (sortPending && sortDisorder > 0 && ownsStep(r)) {
		const auto ts = Clock::now();
		sortInteractions();
		pairs.workValid = false;
		sortTime += ns(ts, Clock::now());
	}
	sortPending = false;
	forceSums.useThreads(threads);
	gather(threads); // also zeroes the force arrays after a step that ended before its flush
	// The force container covers every body and its per-thread entries are summed (addMaxId, sync): the
	// pass adds the forces of each thread's part of the bodies into its summed arrays (see ThreadSink).
	const long bodies = long(snapshot.particles.size());
	if (bodies > 0) {
		scene->forces.addMaxId(Body::id_t(bodies - 1));
		scene->forces.sync();
	}
	const pendular::SummedArrays summed = pendular::summedArrays(scene->forces, bodies);
	forceSums.direct.assign(size_t(threads), pendular::DirectPart {});
	const auto t1 = Clock::now();

	// As InteractionLoop: with a collider that does not erase interactions itself, the potential
	// interactions it did not see in this step are skipped.
	removeUnseen = scene->interactions->iterColliderLastRun >= 0 && scene->interactions->iterColliderLastRun == scene->iter;
	const auto&      interactions = *scene->interactions;
	const long       size         = scene->interactions->size();
	long             fused = 0, dispatchedCount = 0, apart = 0, recorded = 0, bounded = 0;
	pairs.slots.resize(size);
	toRecord.resize(threads);
	toForget.resize(threads);
	const bool skipApart = r.fused && !removeUnseen && !scene->isPeriodic;
	forceSums.pending    = true; // until the flush has read and zeroed the force arrays
	// Between two runs of the collider and within one epoch of the bound on potential pairs' gaps
	// (see gather), the container is the one of the last pass, and a potential pair whose bound exceeds
	// what the bodies can move in the whole epoch is skipped at every step: the pass visits only the
	// entries of `work` (built after the last full pass), in the same order at every step (the container's
	// order on one thread, see shareWork on several), so that the forces are summed in the same order, and
	// the skipped entries are counted as the full pass counts them.
	// Anything else that changes the container drops the list: the Python paths through syncScene,
	// sorting, another scene. Behind that, the first and last entries must be the interactions of the
	// last pass (an erasure moves the last entry into its hole, an insertion appends: erasing and
	// inserting one keeps the size, not the last entry).
	const bool fast = skipFar && recording && skipApart && !pairs.fullCheck && pairs.listValid(colliderRuns, *scene->interactions);
	long       disorder = 0;
	const long m        = fast ? long(pairs.work.size()) : size;
	// The parts of the bodies and of the list, and the borders, are those of this pass (shareWork made
	// them for this list and these bodies; the pass does not change them). Then a pass on the list whose
	// threads add their own bodies' forces into the container hands the borders over in its own parallel
	// region (partsReady, see handOverBorders), if the whole team runs it.
	// (workParts as partOf takes it: a thread that waits for another's hand-off relies on that thread's part
	// holding its workBorders.)
	const bool partsValid = fast && partition.valid(m, threads, bodies);
	const bool partsReady = partsValid && summed.forces;
	const long handOffAt  = partsReady ? partition.nextHandOff(threads) : 0;
	// Shares fixed between two full passes, so that each thread sums the forces on its bodies in the same
	// order at every step of an epoch. The list is shared by the parts of the bodies (shareWork, which
	// follows the threads' measured paces: two runs on several threads may differ by round-off, as YADE's
	// collider already makes them on several threads by its parallel insertion); a full pass
	// in interleaved chunks of the container: real and potential interactions are not spread evenly over
	// it (one half per thread left one thread idle a third of the time).
	// A full pass lists the entries that the passes of this epoch may have to visit (see buildWork) as it
	// visits them, each thread those of its chunks (a list made after the pass would read every slot again,
	// on several threads half of them from another core; docs/performance.md, "The list of a full pass made
	// during the pass").
	// gather ends an epoch unless move < epochMove * rmin, the same product: each slot left out has
	// gapBound >= 2 (epochMove rmin) > 2 epochDisplacement at every step of the epoch.
	const bool listing   = !fast && skipFar && recording && skipApart;
	const Real threshold = pairs.threshold();
	if (listing) pairs.startListing(threads, size);
	// teamComplete: each thread computed its part of the list (then the flush reads only parts and borders).
	bool teamComplete = true;
	// This pass's entries of busyTimes (see traceBusy), one per thread, written by each thread.
	const size_t traceAt = busyTimes.size();
	const bool   tracing = fast && traceBusy > 0;
	if (tracing) busyTimes.resize(traceAt + size_t(threads), NaN);
#ifdef YADE_OPENMP
#pragma omp parallel num_threads(threads) reduction(+ : fused, dispatchedCount, apart, recorded, bounded, disorder) reduction(&& : teamComplete)
#endif
	{
		Counts c;
		c.thread     = pendular::threadNumber();
		teamComplete = pendular::teamSize() == threads;
		if (summed.forces) {
			const auto part              = pendular::partOf(partition.bodyParts, bodies, c.thread, pendular::teamSize());
			forceSums.direct[size_t(c.thread)] = pendular::DirectPart { summed.forces, summed.torques, part.first, part.second };
		}
		if (fast) {
			const auto started = Clock::now();
			const auto& work   = pairs.work;
			// Each thread its part of the list (workParts): the entries whose first body is in its part of
			// the bodies, which it gathered and will move.
			const auto part = pendular::partOf(partition.workParts, m, c.thread, pendular::teamSize());
			const long end  = part.second;
			// Every thread of the team takes this branch or none (the same team size). Each computes first its
			// entries that reach other parts and says so (handOffs), then the rest of its part; then it adds
			// what the others computed for the bodies of its part, as soon as they have said so. Behind a
			// barrier instead, a thread whose part the others reach waits for them and then hands over alone
			// (in a cell whose ids grow with height, the part of the lower ids reaches the other, not the
			// reverse; docs/performance.md, "Hand-over without a barrier").
			const bool handing = partsReady && pendular::teamSize() == threads;
			pendular::WorkPartition::HandOff* own = handing ? &partition.handOffs[c.thread] : nullptr;
			const long handAt  = handing ? partition.workBorders[size_t(c.thread)] : -1; // after the entries that reach other parts
			if (handAt == part.first) own->pass.store(handOffAt, std::memory_order_release);
			for (long k = part.first; k < end; ++k) {
				// A third level for the list: its entries are not contiguous, so the hardware does not
				// fetch the slots and container entries that the prefetches of visit() read.
				if (k + 4 * prefetchAhead < end) {
					__builtin_prefetch(&pairs.slots[work[k + 4 * prefetchAhead]]);
					__builtin_prefetch(&interactions[work[k + 4 * prefetchAhead]]);
				}
				visit(work[k], k + prefetchAhead < end ? work[k + prefetchAhead] : -1, k + 2 * prefetchAhead < end ? work[k + 2 * prefetchAhead] : -1,
				      r, skipApart, recording, c);
				if (k + 1 == handAt) own->pass.store(handOffAt, std::memory_order_release);
			}
			// The pace counts the thread's own work, not its waits for the others.
			auto busy = Clock::now() - started;
			if (handing) {
				for (int k = 0; k < threads; ++k)
					if (k != c.thread && !partition.borders[size_t(k)][size_t(c.thread)].empty())
						pendular::waitFor(partition.handOffs[k].pass, handOffAt);
				const auto handing0 = Clock::now();
				forceSums.handOverBorders(c.thread, summed, partition.borders);
				busy += Clock::now() - handing0;
			}
			const Real busyNs = Real(std::chrono::duration_cast<std::chrono::nanoseconds>(busy).count());
			if (partsValid && pendular::teamSize() == threads && long(partition.paceTime.size()) == threads) partition.paceTime[size_t(c.thread)] += busyNs;
			if (tracing) busyTimes[traceAt + size_t(c.thread)] = busyNs;
		} else {
			// The (id1, id2) of the entry before, in this thread's chunk: counts the entries out of order (see sortInteractions).
			long     before    = -2;
			uint64_t beforeKey = 0;
#ifdef YADE_OPENMP
#pragma omp for schedule(static, pendular::passChunk)
#endif
			for (long i = 0; i < size; ++i) {
				visit(i, i + prefetchAhead < size ? i + prefetchAhead : -1, i + 2 * prefetchAhead < size ? i + 2 * prefetchAhead : -1, r, skipApart,
				      recording, c);
				const Slot&    slot = pairs.slots[i];
				const uint64_t key  = slot.key();
				if (i == before + 1 && key < beforeKey) ++disorder;
				before    = i;
				beforeKey = key;
				if (listing) {
					pairs.list(i, slot, threshold, c.thread, size);
				}
			}
		}
		fused += c.fused;
		dispatchedCount += c.dispatched;
		apart += c.apart;
		recorded += c.recorded;
		bounded += c.bounded;
	}
	// The skipped entries, counted as the full pass counts them (apart by the bound).
	// The flush may read the arrays by parts and borders (see flushForces).
	const bool parted = partsValid && teamComplete;
	if (parted) ++partition.paceSteps;
	if (tracing) --traceBusy;
	nSkipped = size - m;
	fused += nSkipped;
	apart += nSkipped;
	bounded += nSkipped;
	if (fast) {
		++nFastPasses;
		disorder = nDisorder; // the container's order has not changed
	}
	nDisorder            = disorder;
	sortPending          = sortDisorder > 0 && Real(disorder) > sortDisorder * Real(size);
	nFused               = fused;
	nDispatched          = dispatchedCount;
	nApart               = apart;
	nRecorded            = recorded;
	nBounded             = bounded;
	known.seenDt         = scene->dt; // what the records' shearInc now follows from (recordShearInc)
	known.seenRatcheting = r.ig2 ? r.ig2->avoidGranularRatcheting : true;
	settleRecords();
	if (!fast && pairs.buildList(listing, colliderRuns, *scene->interactions))
		partition.share(pairs.work, pairs.slots, long(snapshot.particles.size()), threads, threadPace);
	known.stale   = liveRecords() > 0;
	const auto t2 = Clock::now();
	forceSums.flush(scene->forces, long(snapshot.particles.size()), threads, parallelBodies, parted, summed.forces != nullptr, partsReady && teamComplete,
	                partition.bodyParts, partition.borders);
	gatherTime += ns(t0, t1);
	passTime += ns(t1, t2);
	flushTime += ns(t2, Clock::now());
}

// One entry of the container; after it, its slot holds its ids whichever way it went. ahead1, ahead2:
// the entries the pass visits prefetchAhead and 2 prefetchAhead after this one (-1: none).
void PendularLoop::visit(long i, long ahead1, long ahead2, const Resolved& r, bool skipApart, bool recording, Counts& c)
{
	const auto& interactions = *scene->interactions;
	// Two levels: the record or Interaction (unless a potential one seen before), then, once it is
	// cached, the bodies of a record or the geometry and physics of a real interaction without one.
	// Led by the slots alone (a slot that no longer matches its entry prefetches the wrong lines, which
	// costs nothing but the prefetch; checking costs two more reads per entry).
	if (ahead2 >= 0) {
		const Slot& ahead = pairs.slots[ahead2];
		if (ahead.recorded()) {
			if (size_t(ahead.record) < records.size()) prefetchObject(&records[ahead.record]);
		} else if (!ahead.potential())
			prefetchObject(interactions[ahead2].get());
	}
	if (ahead1 >= 0) {
		const Slot& ahead = pairs.slots[ahead1];
		if (ahead.recorded()) { // its bodies and their force sums (the slot has the ids; torques only with friction, not prefetched)
			if (size_t(math::max(ahead.id1, ahead.id2)) < snapshot.particles.size()) {
				prefetchObject(&snapshot.particles[ahead.id1]);
				prefetchObject(&snapshot.particles[ahead.id2]);
				forceSums.prefetch(c.thread, ahead.id1);
				forceSums.prefetch(c.thread, ahead.id2);
			}
		} else if (ahead.record == Slot::none) {
			const auto& J = interactions[ahead1];
			if (J->geom) prefetchObject(static_cast<const ScGeom*>(J->geom.get()));
			if (J->phys) prefetchObject(static_cast<const PendularPhys*>(J->phys.get()));
		} else if (skipApart && !pairs.apartByBound(ahead)) { // a potential pair to check: its bodies
			if (size_t(math::max(ahead.id1, ahead.id2)) < snapshot.particles.size()) {
				__builtin_prefetch(&snapshot.particles[ahead.id1]);
				__builtin_prefetch(&snapshot.particles[ahead.id2]);
			}
		}
	}
	const shared_ptr<Interaction>& I    = interactions[i];
	Slot&                          slot = pairs.slots[i];
	// Another interaction than in the last step: new (reconcile has given an interaction that an erasure
	// moved here the slot of its record).
	if (!slot.same(I)) slot.record = Slot::none;
	if (slot.same(I)) {
		if (slot.recorded()) {
			Record& rec = records[slot.record];
			// The record's bodies (the body container may have shrunk: O.bodies.replace).
			// bodiesKept: no body changed since the last pass, in which the record's were such spheres.
			if (snapshot.kindsKept
			    || (size_t(math::max(slot.id1, slot.id2)) < snapshot.particles.size() && sphereHere(slot.id1) && sphereHere(slot.id2))) {
				++c.fused;
				++c.recorded;
				if (!recordStep(rec, r, c.thread)) {
					scene->interactions->requestErase(I);
					toForget[c.thread].push_back(slot.record);
					slot.record   = Slot::potentialPair;
					slot.gapBound = -std::numeric_limits<float>::infinity();
				}
				return;
			}
			// A body is gone or has changed (material, shape, subdomain): the objects decide again.
			store(rec, *I, snapshot.previous); // its own objects again (made in this thread: the record is forgotten after the pass)
			toForget[c.thread].push_back(slot.record);
			slot.record = Slot::none;
		} else if (skipApart && slot.potential()) {
			// A potential interaction of two PendularMat spheres seen in an earlier step (same object, so
			// the same ids; it became real only in this loop, which updates the slot). Apart by more than
			// the bodies can have moved since its last check: nothing to read but the slot (see gather).
			if (pairs.apartByBound(slot)) {
				++c.fused;
				++c.apart;
				++c.bounded;
				return;
			}
			// Else one distance check on the gathered data, without reading the Interaction.
			const pendular::Near q1 = pendular::nearOf(snapshot.particles[slot.id1], scene->subdomain, pairs.films);
			const pendular::Near q2 = pendular::nearOf(snapshot.particles[slot.id2], scene->subdomain, pairs.films);
			if (q1.radius != 0 && q2.radius != 0 && (q1.radius > 0 || q2.radius > 0)) {
				const Real sumR = math::abs(q1.radius) + math::abs(q2.radius);
				const Real d2   = (q2.pos - q1.pos).squaredNorm();
				if (d2 > sumR * sumR) {
					slot.gapBound = pendular::roundedDown(math::sqrt(d2) - sumR - 2 * pairs.epochDisplacement);
					++c.fused;
					++c.apart;
					return;
				}
			}
		}
	}
	step(I, r, c);
	// Assigned only for another interaction: a weak_ptr copy is two atomic operations on the control
	// block, one more cache line per interaction and step.
	if (!slot.same(I)) slot.interaction = I;
	slot.id1      = I->getId1();
	slot.id2      = I->getId2();
	slot.record   = I->isReal() ? Slot::none : Slot::potentialPair;
	slot.gapBound = -std::numeric_limits<float>::infinity();
	if (recording && !slot.potential() && recordable(*I, r)) toRecord[c.thread].push_back(i);
}

// How many times the scene's colliders have run (InsertionSortCollider::numAction counts the steps it
// is activated in): the only engine that recordsAllowed lets change the container during a run.
long PendularLoop::colliderRunCount() const
{
	long runs = 0;
	for (const auto& e : scene->engines)
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

// A real sphere-sphere interaction of the fused pass whose state fits a Record: a fixed-volume
// inviscid bridge (or none) on ScGeom, with valid contact parameters.
bool PendularLoop::recordable(const Interaction& I, const Resolved& r) const
{
	if (!r.fused || !sphereHere(I.getId1()) || !sphereHere(I.getId2())) return false;
	if (!I.geom || !I.phys || typeid(*I.geom) != typeid(ScGeom) || typeid(*I.phys) != typeid(PendularPhys)) return false;
	const auto& phys = static_cast<const PendularPhys&>(*I.phys);
	return !phys.film && !phys.viscous && phys.kn > 0;
}

void PendularLoop::load(Record& rec, const shared_ptr<Interaction>& I)
{
	const auto& geom     = static_cast<const ScGeom&>(*I->geom);
	const auto& phys     = static_cast<const PendularPhys&>(*I->phys);
	rec.id1              = I->getId1();
	rec.id2              = I->getId2();
	rec.invariants       = invariantsOf(phys);
	rec.active           = phys.active;
	rec.isActive         = I->isActive;
	rec.normal           = geom.normal;
	rec.shearInc         = geom.shearInc;
	rec.penetrationDepth = geom.penetrationDepth;
	rec.normalForce      = phys.normalForce;
	rec.shearForce       = phys.shearForce;
	rec.Fcap             = phys.Fcap;
}

namespace {
	// A boost.serialization saving archive that appends to `key` the bytes of every attribute that a
	// PendularPhys's serialize() names, but those at the addresses in `skip`: the attribute lists of its
	// YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY and of its bases' (attributes flagged noSave are not named; none of
	// PendularPhys's is). An attribute of a type it cannot add fails to compile here.
	class KeyArchive {
	public:
		using is_loading = boost::mpl::false_;
		using is_saving  = boost::mpl::true_;
		KeyArchive(std::string& key, const std::array<const void*, 4>& skip)
		        : key(key)
		        , skip(skip)
		{
		}
		template <class T> KeyArchive& operator&(const boost::serialization::nvp<T>& member)
		{
			add(member.const_value());
			return *this;
		}

	private:
		template <class T> void add(const T& value)
		{
			if constexpr (std::is_base_of<Serializable, T>::value) boost::serialization::access::serialize(*this, const_cast<T&>(value), 0u);
			else {
				static_assert(std::is_arithmetic<T>::value || std::is_same<T, Vector3r>::value,
				              "an attribute of PendularPhys whose type PendularLoop::invariantsKey cannot compare: add the type to KeyArchive");
				if (std::find(skip.begin(), skip.end(), static_cast<const void*>(&value)) == skip.end())
					key.append(reinterpret_cast<const char*>(&value), sizeof(T));
			}
		}
		std::string&                     key;
		const std::array<const void*, 4> skip;
	};
} // namespace

// The entry of `invariants` for the bridge and contact parameters of `phys`. PendularPhys makes its
// bridge from its own members (Ip2, and again when loaded), so physics with the same members, bit for
// bit, have the same bridge: they share an entry (the bridge is checked as well, cheaply). The members
// are those that serialize() names (KeyArchive), so that an attribute added to PendularPhys is part of
// the key without being listed here.
std::string PendularLoop::invariantsKey(const PendularPhys& phys)
{
	const Real  bridge[] = { phys.bridge.rupture, phys.bridge.force0, phys.bridge.force_rupture };
	const int   model    = int(phys.bridge.m.index());
	std::string key(reinterpret_cast<const char*>(bridge), sizeof(bridge));
	key.append(reinterpret_cast<const char*>(&model), sizeof(model));
	// Every attribute but those of the record (active, Fcap, normalForce, shearForce): the entry's
	// prototype stands for the physics of all its records when their objects are made again (store).
	KeyArchive archive(key, { &phys.active, &phys.Fcap, &phys.normalForce, &phys.shearForce });
	boost::serialization::access::serialize(archive, const_cast<PendularPhys&>(phys), 0u);
	return key;
}

int PendularLoop::invariantsOf(const PendularPhys& phys)
{
	const std::string key   = invariantsKey(phys);
	const auto        found = invariantsIndex.find(key);
	if (found != invariantsIndex.end()) {
		++invariants[found->second].users;
		return found->second;
	}
	const Invariants entry { phys.bridge, phys.kn, phys.cn, phys.ks, phys.cs, phys.tangensOfFrictionAngle, phys.Vb, phys.wet, phys.forceInContact,
		                 shared_ptr<const PendularPhys>(new PendularPhys(phys)), 1 };
	int index;
	if (freeInvariants.empty()) {
		index = int(invariants.size());
		invariants.push_back(entry);
	} else {
		index = freeInvariants.back();
		freeInvariants.pop_back();
		invariants[index] = entry;
	}
	return invariantsIndex[key] = index;
}

void PendularLoop::release(int index)
{
	Invariants& entry = invariants[index];
	if (--entry.users > 0) return;
	invariantsIndex.erase(invariantsKey(*entry.prototype)); // a copy of the physics it was made from: the same key
	entry.prototype.reset();
	freeInvariants.push_back(index);
}

void PendularLoop::forget(int index)
{
	release(records[index].invariants);
	recordInteractions[index].reset();
	freeRecords.push_back(index);
}

// What a step changes: the geometry, the forces and whether the bridge exists. The contact point and
// the radii, which the record does not keep, follow from the bodies as gathered for the record's last
// step (the particles, not gathered again before the objects are brought up to date), by the
// arithmetic of sphereGeometry. An interaction that holds the placeholders gets a new ScGeom (all its
// attributes are the record's or follow from the bodies; the axes of ScGeom::rotate are computed
// before any use) and a copy of its invariants' prototype physics.
bool PendularLoop::store(const Record& rec, Interaction& I, const std::vector<Particle>& seen) const
{
	if (!I.geom || !I.phys) return false; // reset by the law in this step
	const bool make = holdsPlaceholders(I);
	if (make) {
		I.geom = shared_ptr<IGeom>(new ScGeom());
		I.phys = shared_ptr<IPhys>(new PendularPhys(*invariants[rec.invariants].prototype));
	}
	auto& geom            = static_cast<ScGeom&>(*I.geom);
	auto& phys            = static_cast<PendularPhys&>(*I.phys);
	geom.normal           = rec.normal;
	geom.shearInc         = recordShearInc(rec, seen);
	geom.penetrationDepth = rec.penetrationDepth;
	if (size_t(math::max(rec.id1, rec.id2)) < seen.size()) {
		const Particle& p1 = seen[rec.id1];
		geom.contactPoint  = pendular::contactPointOf(p1, rec.normal, rec.penetrationDepth);
		geom.radius1       = p1.radius;
		geom.radius2       = seen[rec.id2].radius;
	} else if (make) { // a body that is gone: nothing to complete the new object from
		geom.contactPoint = Vector3r::Constant(NaN);
		geom.radius1 = geom.radius2 = NaN;
	}
	phys.normalForce = rec.normalForce;
	phys.shearForce  = rec.shearForce;
	phys.Fcap        = rec.Fcap;
	phys.active      = rec.active;
	return make;
}

namespace {
	// A record seen as the ScGeom and PendularPhys that sphereGeometry and the law read and write: the
	// members of the record by reference, those it does not keep as values of this step, the
	// invariants shared.
	struct RecordGeom {
		Vector3r& normal;
		Vector3r& shearInc;
		Real&     penetrationDepth;
		Vector3r  contactPoint;
		Real      radius1, radius2;
	};
	struct RecordPhys {
		Vector3r&                normalForce;
		Vector3r&                shearForce;
		Real&                    Fcap;
		bool&                    active;
		const capillary::Bridge& bridge;
		const Real &             kn, &cn, &ks, &cs, &tangensOfFrictionAngle, &Vb;
		const bool &             wet, &forceInContact;
	};
} // namespace

// Inlined into visit: one call per bridge-step saved (the pass is bound by its instructions, not memory).
__attribute__((always_inline)) inline bool PendularLoop::recordStep(Record& rec, const Resolved& r, int thread)
{
	const Particle& p1     = snapshot.particles[rec.id1];
	const Particle& p2     = snapshot.particles[rec.id2];
	Vector3r        normal = p2.pos - p1.pos;
	const Real      norm   = normal.norm();
	normal /= norm;
	const Vector3r    zero = Vector3r::Zero();
	const Invariants& inv  = invariants[rec.invariants];
	RecordGeom        geom { rec.normal, rec.shearInc, rec.penetrationDepth, zero, 0, 0 };
	RecordPhys        phys { rec.normalForce, rec.shearForce, rec.Fcap, rec.active, inv.bridge, inv.kn, inv.cn, inv.ks, inv.cs, inv.tangensOfFrictionAngle,
                      inv.Vb, inv.wet, inv.forceInContact };
	const Real        depth = p1.radius + p2.radius - norm;
	// Separating: the shearInc of the last step in contact, which the objects keep while separated.
	if (depth < 0 && rec.penetrationDepth >= 0) rec.shearInc = recordShearInc(rec, snapshot.previous);
	const pendular::Rotation rotation = pendular::sphereGeometry(geom, p1, p2, normal, depth, zero, zero, false, *scene, r.ig2, true, inv.tangensOfFrictionAngle > 0);
	return applyLaw(rec.id1, rec.id2, rec.isActive, geom, phys, r, zero, zero, rotation, thread);
}

// After the pass, in one thread: frees the records of the interactions reset or handed back to the
// objects, records the interactions that qualified (their objects replaced by the placeholders unless
// something else holds them: Python) and drops the objects made since the last pass (dropObjects).
void PendularLoop::settleRecords()
{
	for (auto& list : toForget) {
		for (const int index : list)
			forget(index);
		list.clear();
	}
	const auto& interactions = *scene->interactions;
	for (auto& list : toRecord) {
		for (const long i : list) {
			int index;
			if (freeRecords.empty()) {
				index = int(records.size());
				records.emplace_back();
				recordInteractions.emplace_back();
			} else {
				index = freeRecords.back();
				freeRecords.pop_back();
			}
			const shared_ptr<Interaction>& I = interactions[i];
			load(records[index], I);
			recordInteractions[index] = I;
			pairs.slots[i].record           = index;
			withObjects.push_back(index);
		}
		list.clear();
	}
	dropObjects();
}

void PendularLoop::dropObjects()
{
	size_t kept = 0;
	for (const int index : withObjects) {
		const auto& I = recordInteractions[index];
		if (!I || !I->geom || holdsPlaceholders(*I)) continue; // forgotten, reset, or listed twice
		// An object that Python assigned has a control block of its own, which holds the Python object
		// (boost::python's deleter): Python may hold it though the count is 1.
		const bool fromPython = boost::get_deleter<boost::python::converter::shared_ptr_deleter>(I->geom)
		        || boost::get_deleter<boost::python::converter::shared_ptr_deleter>(I->phys);
		if (!fromPython && I->geom.use_count() == 1 && I->phys.use_count() == 1) {
			I->geom            = placeholderGeom();
			I->phys            = placeholderPhys();
			known.placeholders = true;
		} else
			withObjects[kept++] = index; // held by Python: written by the next sync
	}
	withObjects.resize(kept);
	nWithObjects = long(kept);
	nInvariants  = long(invariants.size()) - long(freeInvariants.size());
}

// The collider erases the potential interactions whose bounding boxes parted (an erasure moves the last
// entry of the container into the hole) and appends new ones: each recorded interaction is found at its
// place in the container (Interaction::linIx), where its slot now is. One that is no longer in the
// container (none should be: the collider erases only potential interactions, the Python paths that erase
// drop the records first) goes back to its objects.
void PendularLoop::reconcile()
{
	auto&       container = *scene->interactions;
	const long  size      = long(container.size());
	pairs.slots.resize(size_t(size));
	const size_t n = records.size();
	for (size_t index = 0; index < n; ++index) {
		// The Interaction is read for its place only: a miss per record, overlapped by the prefetch.
		if (index + prefetchAhead < n && recordInteractions[index + prefetchAhead]) __builtin_prefetch(recordInteractions[index + prefetchAhead].get());
		const shared_ptr<Interaction>& I = recordInteractions[index];
		if (!I) continue;
		const long at = I->linIx;
		if (at >= 0 && at < size && container[at] == I) {
			Slot& slot = pairs.slots[at];
			// Still in its slot (most are after a run of the collider): rewriting it would only count the
			// weak reference down and up again.
			if (slot.record == int(index) && slot.same(I) && slot.id1 == records[index].id1 && slot.id2 == records[index].id2) continue;
			slot             = Slot {};
			slot.interaction = I;
			slot.id1         = records[index].id1;
			slot.id2         = records[index].id2;
			slot.record      = int(index);
			continue;
		}
		store(records[index], *I);
		forget(int(index));
	}
}

// Sorts YADE's interaction container by (id1, id2), with the slots, and the records in the new
// order. The collider appends new interactions and an erasure moves the last entry into the hole,
// so the container drifts out of any order and the pass reads the bodies, slots and records of
// consecutive entries from scattered places; body ids of a packing built layer by layer are close
// in space, so in id order a pair's bodies and those of its neighbours in the container share cache
// lines and the records are read in their order in memory. The container's order is only the order
// of the loop (and of the force sums); InteractionContainer finds an interaction through its bodies,
// and linIx is its back-reference.
void PendularLoop::sortInteractions()
{
	auto&        container = *scene->interactions;
	const size_t n         = container.size();
	pairs.slots.resize(n);
	std::vector<std::pair<uint64_t, size_t>> order(n); // key, entry before the sort
	for (size_t i = 0; i < n; ++i) {
		const auto& I = container[i];
		if (!pairs.slots[i].same(I)) { // new since the last pass (reconcile has placed the records), the pass decides
			pairs.slots[i]             = Slot {};
			pairs.slots[i].interaction = I;
			pairs.slots[i].id1         = I->getId1();
			pairs.slots[i].id2         = I->getId2();
		}
		order[i] = { pairs.slots[i].key(), i };
	}
	sortByKey(order, uint64_t(scene->bodies->size()));
	std::vector<shared_ptr<Interaction>> sorted(n);
	std::vector<Slot>                    sortedSlots(n);
	for (size_t k = 0; k < n; ++k) {
		sorted[k]      = std::move(container[order[k].second]);
		sortedSlots[k] = std::move(pairs.slots[order[k].second]);
	}
	for (size_t k = 0; k < n; ++k) {
		// Every Interaction gets its new place: a miss each, overlapped by the prefetch.
		if (k + prefetchAhead < n) __builtin_prefetch(sorted[k + prefetchAhead].get(), 1);
		container[k]        = std::move(sorted[k]);
		container[k]->linIx = int(k);
	}
	pairs.slots.swap(sortedSlots);
	++nSorts;
	if (records.empty()) return;
	std::vector<Record>                  ordered;
	std::vector<shared_ptr<Interaction>> orderedInteractions;
	ordered.reserve(records.capacity()); // room for the next steps' new records without moving them all again
	orderedInteractions.reserve(records.capacity());
	std::vector<bool> placed(records.size(), false);
	for (size_t k = 0; k < n; ++k) {
		Slot& slot = pairs.slots[k];
		if (!slot.recorded()) continue;
		placed[slot.record] = true;
		ordered.push_back(records[slot.record]);
		orderedInteractions.push_back(std::move(recordInteractions[slot.record]));
		slot.record = int(ordered.size()) - 1;
	}
	// A record whose interaction is no longer in the container (reconcile has handed them back) goes
	// back to its objects.
	for (size_t index = 0; index < records.size(); ++index)
		if (!placed[index] && recordInteractions[index]) {
			store(records[index], *recordInteractions[index]);
			release(records[index].invariants);
		}
	records.swap(ordered);
	recordInteractions.swap(orderedInteractions);
	freeRecords.clear();
	withObjects.clear();
	for (size_t index = 0; index < records.size(); ++index) {
		if (index + prefetchAhead < records.size()) __builtin_prefetch(recordInteractions[index + prefetchAhead].get());
		if (!holdsPlaceholders(*recordInteractions[index])) withObjects.push_back(int(index));
	}
}

void PendularLoop::syncObjects(bool drop, bool all)
{
	if ((all || drop) && (known.stale || known.placeholders)) { // else nothing to write (a loop of Python calls asks at every call)
		for (size_t index = 0; index < records.size(); ++index) {
			const auto& I = recordInteractions[index];
			if (I && (known.stale || holdsPlaceholders(*I)) && store(records[index], *I)) withObjects.push_back(int(index));
		}
		known.placeholders = false;
	} else if (!(all || drop) && known.stale)
		for (const int index : withObjects)
			if (recordInteractions[index]) store(records[index], *recordInteractions[index]);
	known.stale = false;
	if (!drop) return;
	pairs.workValid = false;
	records.clear();
	recordInteractions.clear();
	invariants.clear();
	invariantsIndex.clear();
	freeRecords.clear();
	freeInvariants.clear();
	withObjects.clear();
	nWithObjects = 0;
	nInvariants  = 0;
	for (auto& slot : pairs.slots)
		if (slot.recorded()) slot.record = Slot::none;
}

PendularLoop::~PendularLoop() { syncObjects(true, true); }

namespace {
	template <class V> void freeVector(V& v) { V().swap(v); }
} // namespace

// Every array the loop holds for its scene, the one list heldBytes and freeArrays go through.
template <class Loop, class Visit> void PendularLoop::forEachArray(Loop& loop, Visit&& visit)
{
	visit(loop.snapshot.particles);
	visit(loop.snapshot.previous);
	visit(loop.threadPace);
	visit(loop.records);
	visit(loop.recordInteractions);
	visit(loop.invariants);
	visit(loop.freeRecords);
	visit(loop.freeInvariants);
	visit(loop.withObjects);
	visit(loop.toRecord);
	visit(loop.toForget);
	visit(loop.snapshot.pointers.states);
	visit(loop.snapshot.pointers.bounds);
	visit(loop.snapshot.pointers.parts);
}

long PendularLoop::heldBytes() const
{
	long bytes = 0;
	forEachArray(*this, [&bytes](const auto& v) { bytes += pendular::capacityBytes(v); });
	return bytes + pairs.heldBytes() + partition.heldBytes() + forceSums.heldBytes();
}

void PendularLoop::freeArrays()
{
	forEachArray(*this, [](auto& v) { freeVector(v); });
	invariantsIndex = {};
	// As a new loop: the gathering starts an epoch (epoch is empty), the pass visits every entry.
	known              = Known {};
	pairs              = pendular::Pairs {};
	partition          = pendular::WorkPartition {};
	forceSums          = pendular::ForceAccumulator {};
	snapshot.pointers.scene = nullptr;
}

void PendularLoop::releaseScene(Scene* scene)
{
	if (!scene) return;
	if (Omega::instance().isRunning())
		throw std::runtime_error("PendularLoop.release while the simulation runs (O.run()): call O.pause() or O.wait() first");
	syncScene(scene, true, true); // the records into the objects
	for (const auto& e : scene->engines)
		if (auto* loop = dynamic_cast<PendularLoop*>(e.get())) loop->freeArrays();
}

void PendularLoop::objectsOf(const shared_ptr<Interaction>& I)
{
	if (!I) return;
	const auto& scene = Omega::instance().getScene();
	for (const auto& e : scene->engines) {
		auto* loop = dynamic_cast<PendularLoop*>(e.get());
		if (!loop || loop->liveRecords() == 0) continue;
		// While it runs, the loop makes and drops the objects of its records (also those of this one).
		if (Omega::instance().isRunning() && std::this_thread::get_id() != loop->loopThread)
			throw std::runtime_error("Interaction.geom/phys while the simulation runs (O.run()): PendularLoop makes the objects of the "
			                         "interactions it computes from its own records between steps; call O.pause() or O.wait() first");
		if (!I->geom || !holdsPlaceholders(*I)) return;
		// Its slot, unless the collider has moved it since the last pass (then a search).
		long       index = -1;
		const long at    = I->linIx;
		if (at >= 0 && size_t(at) < loop->pairs.slots.size() && loop->pairs.slots[at].same(I) && loop->pairs.slots[at].recorded()) index = loop->pairs.slots[at].record;
		for (size_t k = 0; index < 0 && k < loop->records.size(); ++k)
			if (loop->recordInteractions[k] == I) index = long(k);
		if (index < 0 || loop->recordInteractions[index] != I) continue;
		if (loop->store(loop->records[index], *I)) loop->withObjects.push_back(int(index));
		return;
	}
	if (!I->geom || !holdsPlaceholders(*I)) return; // no records: its own objects
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
		if (drop) loop->pairs.workValid = false;
		if (loop->liveRecords() == 0) continue;
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

boost::python::dict PendularLoop::memory() const
{
	boost::python::dict d;
	d["Interaction"]   = sizeof(Interaction);
	d["ScGeom"]        = sizeof(ScGeom);
	d["PendularPhys"]  = sizeof(PendularPhys);
	d["ViscElCapPhys"] = sizeof(ViscElCapPhys);
	d["particle"]      = 2 * sizeof(Particle); // this step's and the last one's (see previous)
	d["epoch"]         = sizeof(pendular::Near);
	d["slot"]          = sizeof(Slot);
	d["record"]        = sizeof(Record) + sizeof(shared_ptr<Interaction>); // with its entry of recordInteractions
	d["invariants"]    = sizeof(Invariants) + sizeof(PendularPhys); // once per distinct set of bridge and contact parameters, with its prototype
	d["forces"]        = 2 * sizeof(Vector3r);
	return d;
}

void PendularLoop::step(const shared_ptr<Interaction>& I, const Resolved& r, Counts& c)
{
	const Body::id_t id1 = I->getId1(), id2 = I->getId2();
	if (removeUnseen && !I->isReal() && I->iterLastSeen < scene->iter) return;
	const Particle* p1 = size_t(id1) < snapshot.particles.size() ? &snapshot.particles[id1] : nullptr;
	const Particle* p2 = size_t(id2) < snapshot.particles.size() ? &snapshot.particles[id2] : nullptr;
	if (!p1 || !p2 || p1->kind == Particle::missing || p2->kind == Particle::missing) {
		scene->interactions->requestErase(I);
		return;
	}
	// yade.mpy: an interaction of two bodies of other subdomains is not this rank's.
	if (scene->subdomain != p1->subdomain && scene->subdomain != p2->subdomain) {
		scene->interactions->requestErase(I);
		return;
	}
	if (p1->kind == Particle::clump || p2->kind == Particle::clump) return;
	if (r.fused && p1->kind == Particle::pendularSphere && p2->kind == Particle::pendularSphere) {
		++c.fused;
		sphereSphere(I, r, c.thread);
	} else {
		++c.dispatched;
		dispatched(I, r, c.thread);
	}
}

void PendularLoop::sphereSphere(const shared_ptr<Interaction>& I, const Resolved& r, int thread)
{
	const Particle& p1 = snapshot.particles[I->getId1()];
	const Particle& p2 = snapshot.particles[I->getId2()];
	const Vector3r  shift2 = scene->isPeriodic ? Vector3r(cellHsize * I->cellDist.cast<Real>()) : Vector3r::Zero();
	Vector3r        normal = (p2.pos + shift2) - p1.pos;
	const Real      sumR   = p1.radius + p2.radius, reach = p1.reach + p2.reach;
	const bool      wasReal = I->isReal();
	// A potential interaction: one distance check. Ig2_Sphere_Sphere_ScGeom would make it real
	// within interactionDetectionFactor (r1 + r2), but apart and without a bridge the law gives no
	// force and resets it; so it becomes real at contact, where the bridge forms (or where the films
	// touch, with formation='films').
	if (!wasReal && normal.squaredNorm() > (sumR + reach) * (sumR + reach)) return;

	const bool isNew = !I->geom;
	if (isNew) I->geom = shared_ptr<ScGeom>(new ScGeom());
	ScGeom&    geom = static_cast<ScGeom&>(*I->geom);
	const Real norm = normal.norm();
	normal /= norm;
	const Real depth = sumR - norm;
	if (!wasReal && depth < -reach) { // touching within round-off of the squared check, not in depth
		I->geom.reset();
		return;
	}
	const Vector3r shiftVel = scene->isPeriodic ? scene->cell->intrShiftVel(I->cellDist) : Vector3r::Zero();
	const pendular::Rotation rotate = pendular::sphereGeometry(geom, p1, p2, normal, depth, shift2, shiftVel, isNew, *scene, r.ig2);
	if (!I->phys) {
		const auto& b1 = Body::byId(I->getId1(), scene);
		const auto& b2 = Body::byId(I->getId2(), scene);
		r.ip2->go(b1->material, b2->material, I);
	}
	if (!wasReal) I->iterMadeReal = scene->iter;
	if (!applyLaw(I->getId1(), I->getId2(), I->isActive, geom, static_cast<PendularPhys&>(*I->phys), r, shift2, shiftVel, rotate, thread)) {
		scene->interactions->requestErase(I);
		return;
	}
	callbacksOn(*I, r);
}

Vector3r PendularLoop::recordShearInc(const Record& rec, const std::vector<Particle>& seen) const
{
	if (!(rec.penetrationDepth >= 0) || size_t(math::max(rec.id1, rec.id2)) >= seen.size()) return rec.shearInc;
	const Particle& p1           = seen[rec.id1];
	const Vector3r  contactPoint = pendular::contactPointOf(p1, rec.normal, rec.penetrationDepth);
	const Vector3r  zero         = Vector3r::Zero();
	return pendular::shearIncrement(p1, seen[rec.id2], rec.normal, rec.penetrationDepth, contactPoint, zero, zero, known.seenRatcheting, known.seenDt);
}

template <class Geom, class Phys, class Rotate>
bool PendularLoop::applyLaw(Body::id_t id1, Body::id_t id2, bool isActive, const Geom& geom, Phys& phys, const Resolved& r, const Vector3r& shift2,
                            const Vector3r& shiftVel, const Rotate& rotate, int thread)
{
	const Particle&          p1 = snapshot.particles[id1];
	const Particle&          p2 = snapshot.particles[id2];
	const PendularKinematics k { p1.pos, p1.vel, p1.angVel, p2.pos, p2.vel, p2.angVel, shift2, shiftVel,
		                     pendularOwner(scene->subdomain, p1.subdomain, p2.subdomain), id1, id2 };
	ThreadSink sink { forceSums.direct[size_t(thread)], forceSums.force[thread].data(), forceSums.torque[thread].data(), id1, id2, isActive };
	return r.law->apply(geom, phys, k, scene->dt, rotate, sink);
}

void PendularLoop::callbacksOn(Interaction& I, const Resolved& r)
{
	for (size_t j = 0; j < r.callbacks.size(); ++j)
		if (r.callbacks[j]) (*r.callbacks[j])(callbacks[j].get(), &I);
}

// Every interaction that is not fused: the steps of InteractionLoop (geometry, physics and law
// functors chosen by the dispatchers and cached on the interaction), except that our own law runs
// inline into the thread's arrays, so that the forces of a body are summed in one place.
void PendularLoop::dispatched(const shared_ptr<Interaction>& I, const Resolved& r, int thread)
{
	const shared_ptr<Body>& b1_ = Body::byId(I->getId1(), scene);
	const shared_ptr<Body>& b2_ = Body::byId(I->getId2(), scene);
	if (!I->functorCache.geomExists || !b1_->shape || !b2_->shape) return;
	bool swap = false;
	if (!I->functorCache.geom) {
		I->functorCache.geom = geomDispatcher->getFunctor2D(b1_->shape, b2_->shape, swap);
		if (!I->functorCache.geom) {
			I->functorCache.geomExists = false;
			return;
		}
	}
	if (swap) I->swapOrder();
	const shared_ptr<Body>& b1      = swap ? b2_ : b1_;
	const shared_ptr<Body>& b2      = swap ? b1_ : b2_;
	const bool              wasReal = I->isReal();
	const Vector3r          shift2  = scene->isPeriodic ? Vector3r(cellHsize * I->cellDist.cast<Real>()) : Vector3r::Zero();
	if (!I->functorCache.geom->go(b1->shape, b2->shape, *b1->state, *b2->state, shift2, /*force*/ false, I)) {
		if (wasReal) {
			LOG_WARN("IGeomFunctor returned false on existing interaction " << I->getId1() << "-" << I->getId2());
			scene->interactions->requestErase(I);
		}
		return;
	}
	if (!I->functorCache.phys) {
		I->functorCache.phys = physDispatcher->getFunctor2D(b1->material, b2->material, swap);
		if (!I->functorCache.phys)
			throw std::runtime_error(
			        "Undefined or ambiguous IPhys dispatch for types " + b1->material->getClassName() + " and " + b2->material->getClassName() + ".");
	}
	I->functorCache.phys->go(b1->material, b2->material, I);
	if (!wasReal) I->iterMadeReal = scene->iter;
	if (!I->functorCache.constLaw) {
		I->functorCache.constLaw = lawDispatcher->getFunctor2D(I->geom, I->phys, swap);
		if (!I->functorCache.constLaw)
			throw std::runtime_error(
			        "No Law2 functor handles interaction " + std::to_string(I->getId1()) + "-" + std::to_string(I->getId2()) + " (geometry "
			        + I->geom->getClassName() + ", physics " + I->phys->getClassName() + ")");
	}
	bool keep;
	if (r.law && I->functorCache.constLaw.get() == r.law) {
		const ScGeom&  geom     = static_cast<const ScGeom&>(*I->geom);
		const Vector3r shiftVel = scene->isPeriodic ? scene->cell->intrShiftVel(I->cellDist) : Vector3r::Zero();
		keep = applyLaw(I->getId1(), I->getId2(), I->isActive, geom, static_cast<PendularPhys&>(*I->phys), r, shift2, shiftVel,
		                [&geom](Vector3r& v) { geom.rotate(v); }, thread);
	} else
		keep = I->functorCache.constLaw->go(I->geom, I->phys, I.get());
	if (!keep) scene->interactions->requestErase(I);
	if (I->isReal()) callbacksOn(*I, r);
}

} // namespace yade
