// PendularLoop's pass over the interaction container (see PendularLoop.hpp): the threads' shares of
// a pass (on the list of entries to visit, or over the whole container), one entry at a time (a record,
// a potential pair's distance check, the fused sphere-sphere step, or YADE's dispatch for the interactions
// the loop does not fuse), and the law inline into the thread's force arrays. One translation unit, so that
// the per-entry functions inline into the pass.
#include "PendularLoop.hpp"
#include "LoopSort.hpp"

#include <limits>
#include <typeinfo>

#ifdef YADE_OPENMP
#include <omp.h>
#endif

namespace yade {

namespace {
	using pendular::prefetchAhead;
	using pendular::prefetchObject;
	using Clock = pendular::Clock;

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

PendularLoop::PassCounts PendularLoop::pass(const PassPlan& plan, const Resolved& r)
{
	long fused = 0, dispatchedCount = 0, apart = 0, recorded = 0, bounded = 0, disorder = 0;
	// teamComplete: each thread computed its part of the list (then the flush reads only parts and borders).
	bool teamComplete = true;
#ifdef YADE_OPENMP
#pragma omp parallel num_threads(plan.threads) reduction(+ : fused, dispatchedCount, apart, recorded, bounded, disorder) reduction(&& : teamComplete)
#endif
	{
		Counts c;
		c.thread     = pendular::threadNumber();
		teamComplete = pendular::teamSize() == plan.threads;
		if (plan.summed.forces) {
			const auto part                       = pendular::partOf(state.partition.bodyParts, plan.bodies, c.thread, pendular::teamSize());
			state.forces.direct[size_t(c.thread)] = pendular::DirectPart { plan.summed.forces, plan.summed.torques, part.first, part.second };
		}
		if (plan.fast) passOnList(plan, r, c);
		else
			disorder = passAll(plan, r, c);
		fused += c.fused;
		dispatchedCount += c.dispatched;
		apart += c.apart;
		recorded += c.recorded;
		bounded += c.bounded;
	}
	return PassCounts { fused, dispatchedCount, apart, recorded, bounded, disorder, teamComplete };
}

// One thread's part of a pass on the list (workParts): the entries whose first body is in its part of
// the bodies, which it gathered and will move. Every thread of the team takes this way or none (the same
// team size). Each computes first its entries that reach other parts and says so (handOffs), then the
// rest of its part; then it adds what the others computed for the bodies of its part, as soon as they
// have said so. Behind a barrier instead, a thread whose part the others reach waits for them and then
// hands over alone (in a cell whose ids grow with height, the part of the lower ids reaches the other,
// not the reverse; docs/performance.md, "Hand-over without a barrier").
void PendularLoop::passOnList(const PassPlan& plan, const Resolved& r, Counts& c)
{
	const auto                 started      = Clock::now();
	const auto&                interactions = *scene->interactions;
	const auto&                work         = state.pairs.work;
	pendular::WorkPartition&   partition    = state.partition;
	const auto                 part         = pendular::partOf(partition.workParts, plan.m, c.thread, pendular::teamSize());
	const long                 end          = part.second;
	const bool                 handing      = plan.partsReady && pendular::teamSize() == plan.threads;
	pendular::WorkPartition::HandOff* own   = handing ? &partition.handOffs[c.thread] : nullptr;
	const long handAt = handing ? partition.workBorders[size_t(c.thread)] : -1; // after the entries that reach other parts
	if (handAt == part.first) own->pass.store(plan.handOffAt, std::memory_order_release);
	for (long k = part.first; k < end; ++k) {
		// A third level for the list: its entries are not contiguous, so the hardware does not
		// fetch the slots and container entries that the prefetches of visit() read.
		if (k + 4 * prefetchAhead < end) {
			__builtin_prefetch(&state.pairs.slots[work[k + 4 * prefetchAhead]]);
			__builtin_prefetch(&interactions[work[k + 4 * prefetchAhead]]);
		}
		visit(work[k], k + prefetchAhead < end ? work[k + prefetchAhead] : -1, k + 2 * prefetchAhead < end ? work[k + 2 * prefetchAhead] : -1, r,
		      plan.skipApart, plan.recording, c);
		if (k + 1 == handAt) own->pass.store(plan.handOffAt, std::memory_order_release);
	}
	// The pace counts the thread's own work, not its waits for the others.
	auto busy = Clock::now() - started;
	if (handing) {
		for (int k = 0; k < plan.threads; ++k)
			if (k != c.thread && !partition.borders[size_t(k)][size_t(c.thread)].empty())
				pendular::waitFor(partition.handOffs[k].pass, plan.handOffAt);
		const auto handing0 = Clock::now();
		state.forces.handOverBorders(c.thread, plan.summed, partition.borders);
		busy += Clock::now() - handing0;
	}
	const Real busyNs = pendular::nanoseconds(busy);
	if (plan.partsValid && pendular::teamSize() == plan.threads && long(partition.paceTime.size()) == plan.threads)
		partition.paceTime[size_t(c.thread)] += busyNs;
	plan.trace.record(busyTimes, c.thread, busyNs);
}

// One thread's chunks of a full pass (a worksharing loop of the caller's parallel region), listing the
// entries as it visits them (plan.listing). Returns the entries of its chunks out of order.
long PendularLoop::passAll(const PassPlan& plan, const Resolved& r, Counts& c)
{
	const long              size     = plan.size;
	long                    disorder = 0;
	pendular::DisorderCount order;
#ifdef YADE_OPENMP
#pragma omp for schedule(static, pendular::passChunk)
#endif
	for (long i = 0; i < size; ++i) {
		visit(i, i + prefetchAhead < size ? i + prefetchAhead : -1, i + 2 * prefetchAhead < size ? i + 2 * prefetchAhead : -1, r, plan.skipApart,
		      plan.recording, c);
		const Slot& slot = state.pairs.slots[i];
		order.see(i, slot, disorder);
		if (plan.listing) state.pairs.list(i, slot, plan.threshold, c.thread, size);
	}
	return disorder;
}

// One entry of the container; after it, its slot holds its ids whichever way it went. ahead1, ahead2:
// the entries the pass visits prefetchAhead and 2 prefetchAhead after this one (-1: none).
void PendularLoop::visit(long i, long ahead1, long ahead2, const Resolved& r, bool skipApart, bool recording, Counts& c)
{
	prefetchEntries(ahead1, ahead2, skipApart, c.thread);
	const shared_ptr<Interaction>& I    = (*scene->interactions)[i];
	Slot&                          slot = state.pairs.slots[i];
	// Another interaction than in the last step: new (reconcile has given an interaction that an erasure
	// moved here the slot of its record).
	if (!slot.same(I)) slot.record = Slot::none;
	if (slot.same(I)) {
		if (slot.recorded()) {
			if (visitRecorded(I, slot, r, c)) return;
		} else if (skipApart && slot.potential() && checkApart(slot, c))
			return;
	}
	step(I, r, c);
	// Assigned only for another interaction: a weak_ptr copy is two atomic operations on the control
	// block, one more cache line per interaction and step.
	if (!slot.same(I)) slot.interaction = I;
	slot.id1      = I->getId1();
	slot.id2      = I->getId2();
	slot.record   = I->isReal() ? Slot::none : Slot::potentialPair;
	slot.gapBound = -std::numeric_limits<float>::infinity();
	if (recording && !slot.potential() && recordable(*I, r)) state.records.toRecord[c.thread].push_back(i);
}

// Two levels: the record or Interaction (unless a potential one seen before), then, once it is
// cached, the bodies of a record or the geometry and physics of a real interaction without one.
// Led by the slots alone (a slot that no longer matches its entry prefetches the wrong lines, which
// costs nothing but the prefetch; checking costs two more reads per entry).
__attribute__((always_inline)) inline void PendularLoop::prefetchEntries(long ahead1, long ahead2, bool skipApart, int thread) const
{
	const auto&                  interactions = *scene->interactions;
	const std::vector<Particle>& particles    = state.snapshot.particles;
	if (ahead2 >= 0) {
		const Slot& ahead = state.pairs.slots[ahead2];
		if (ahead.recorded()) {
			if (size_t(ahead.record) < state.records.records.size()) prefetchObject(&state.records.records[ahead.record]);
		} else if (!ahead.potential())
			prefetchObject(interactions[ahead2].get());
	}
	if (ahead1 >= 0) {
		const Slot& ahead = state.pairs.slots[ahead1];
		if (ahead.recorded()) { // its bodies and their force sums (the slot has the ids; torques only with friction, not prefetched)
			if (size_t(math::max(ahead.id1, ahead.id2)) < particles.size()) {
				prefetchObject(&particles[ahead.id1]);
				prefetchObject(&particles[ahead.id2]);
				state.forces.prefetch(thread, ahead.id1);
				state.forces.prefetch(thread, ahead.id2);
			}
		} else if (ahead.record == Slot::none) {
			const auto& J = interactions[ahead1];
			if (J->geom) prefetchObject(static_cast<const ScGeom*>(J->geom.get()));
			if (J->phys) prefetchObject(static_cast<const PendularPhys*>(J->phys.get()));
		} else if (skipApart && !state.pairs.apartByBound(ahead)) { // a potential pair to check: its bodies
			if (size_t(math::max(ahead.id1, ahead.id2)) < particles.size()) {
				__builtin_prefetch(&particles[ahead.id1]);
				__builtin_prefetch(&particles[ahead.id2]);
			}
		}
	}
}

// A recorded entry (the slot matches its interaction): its step from the record; false if a body is
// gone or has changed (material, shape, subdomain), then the interaction has its objects again and the
// caller steps it through them.
__attribute__((always_inline)) inline bool PendularLoop::visitRecorded(const shared_ptr<Interaction>& I, Slot& slot, const Resolved& r, Counts& c)
{
	pendular::RecordStore& records = state.records;
	Record&                rec     = records.records[slot.record];
	// The record's bodies (the body container may have shrunk: O.bodies.replace). kindsKept: no body
	// changed since the last pass, in which the record's were such spheres.
	if (state.snapshot.kindsKept
	    || (size_t(math::max(slot.id1, slot.id2)) < state.snapshot.particles.size() && sphereHere(slot.id1) && sphereHere(slot.id2))) {
		++c.fused;
		++c.recorded;
		if (!recordStep(rec, r, c.thread)) {
			scene->interactions->requestErase(I);
			records.toForget[c.thread].push_back(slot.record);
			slot.record   = Slot::potentialPair;
			slot.gapBound = -std::numeric_limits<float>::infinity();
		}
		return true;
	}
	// Its own objects again (made in this thread: the record is forgotten after the pass).
	records.store(rec, *I, state.snapshot.previous);
	records.toForget[c.thread].push_back(slot.record);
	slot.record = Slot::none;
	return false;
}

// A potential interaction of two PendularMat spheres seen in an earlier step (same object, so the same
// ids; it became real only in this loop, which updates the slot): true if it is still apart. Apart by
// more than the bodies can have moved since its last check: nothing to read but the slot (see Pairs).
// Else one distance check on the gathered data, without reading the Interaction.
__attribute__((always_inline)) inline bool PendularLoop::checkApart(Slot& slot, Counts& c) const
{
	const pendular::Pairs& pairs = state.pairs;
	if (pairs.apartByBound(slot)) {
		++c.fused;
		++c.apart;
		++c.bounded;
		return true;
	}
	const pendular::Near q1 = pendular::nearOf(state.snapshot.particles[slot.id1], scene->subdomain, pairs.films);
	const pendular::Near q2 = pendular::nearOf(state.snapshot.particles[slot.id2], scene->subdomain, pairs.films);
	if (q1.radius != 0 && q2.radius != 0 && (q1.radius > 0 || q2.radius > 0)) {
		const Real sumR = math::abs(q1.radius) + math::abs(q2.radius);
		const Real d2   = (q2.pos - q1.pos).squaredNorm();
		if (d2 > sumR * sumR) {
			slot.gapBound = pendular::roundedDown(math::sqrt(d2) - sumR - 2 * pairs.epochDisplacement);
			++c.fused;
			++c.apart;
			return true;
		}
	}
	return false;
}

// Inlined into visit: one call per bridge-step saved (the pass is bound by its instructions, not memory).
__attribute__((always_inline)) inline bool PendularLoop::recordStep(Record& rec, const Resolved& r, int thread)
{
	const Particle& p1     = state.snapshot.particles[rec.id1];
	const Particle& p2     = state.snapshot.particles[rec.id2];
	Vector3r        normal = p2.pos - p1.pos;
	const Real      norm   = normal.norm();
	normal /= norm;
	const Vector3r    zero = Vector3r::Zero();
	const pendular::Invariants& inv = state.records.invariants[rec.invariants];
	pendular::RecordGeom geom { rec.normal, rec.shearInc, rec.penetrationDepth, zero, 0, 0 };
	pendular::RecordPhys phys { rec.normalForce, rec.shearForce, rec.Fcap, rec.active, inv.bridge, inv.kn, inv.cn, inv.ks, inv.cs, inv.tangensOfFrictionAngle,
                      inv.Vb, inv.wet, inv.forceInContact };
	const Real        depth = p1.radius + p2.radius - norm;
	// Separating: the shearInc of the last step in contact, which the objects keep while separated.
	if (depth < 0 && rec.penetrationDepth >= 0) rec.shearInc = state.records.shearIncOf(rec, state.snapshot.previous);
	const pendular::Rotation rotation = pendular::sphereGeometry(geom, p1, p2, normal, depth, zero, zero, false, *scene, r.ig2, true, inv.tangensOfFrictionAngle > 0);
	return applyLaw(rec.id1, rec.id2, rec.isActive, geom, phys, r, zero, zero, rotation, thread);
}

void PendularLoop::step(const shared_ptr<Interaction>& I, const Resolved& r, Counts& c)
{
	const Body::id_t id1 = I->getId1(), id2 = I->getId2();
	if (removeUnseen && !I->isReal() && I->iterLastSeen < scene->iter) return;
	const Particle* p1 = size_t(id1) < state.snapshot.particles.size() ? &state.snapshot.particles[id1] : nullptr;
	const Particle* p2 = size_t(id2) < state.snapshot.particles.size() ? &state.snapshot.particles[id2] : nullptr;
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
	const Particle& p1 = state.snapshot.particles[I->getId1()];
	const Particle& p2 = state.snapshot.particles[I->getId2()];
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

template <class Geom, class Phys, class Rotate>
bool PendularLoop::applyLaw(Body::id_t id1, Body::id_t id2, bool isActive, const Geom& geom, Phys& phys, const Resolved& r, const Vector3r& shift2,
                            const Vector3r& shiftVel, const Rotate& rotate, int thread)
{
	const Particle&          p1 = state.snapshot.particles[id1];
	const Particle&          p2 = state.snapshot.particles[id2];
	const PendularKinematics k { p1.pos, p1.vel, p1.angVel, p2.pos, p2.vel, p2.angVel, shift2, shiftVel,
		                     pendularOwner(scene->subdomain, p1.subdomain, p2.subdomain), id1, id2 };
	pendular::ForceAccumulator& forces = state.forces;
	ThreadSink                  sink { forces.direct[size_t(thread)], forces.force[thread].data(), forces.torque[thread].data(), id1, id2, isActive };
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

// A real sphere-sphere interaction of the fused pass whose state fits a Record: a fixed-volume
// inviscid bridge (or none) on ScGeom, with valid contact parameters and the default contact law
// (a record's law has no rolling friction nor Richefeu2008 options, so that the records' pass does not test for them).
bool PendularLoop::recordable(const Interaction& I, const Resolved& r) const
{
	if (!r.fused || !sphereHere(I.getId1()) || !sphereHere(I.getId2())) return false;
	if (!I.geom || !I.phys || typeid(*I.geom) != typeid(ScGeom) || typeid(*I.phys) != typeid(PendularPhys)) return false;
	const auto& phys = static_cast<const PendularPhys&>(*I.phys);
	return !phys.film && !phys.viscous && !phys.approachDamping && !phys.viscousFriction && !(phys.rollingFriction > 0) && phys.kn > 0;
}

} // namespace yade
