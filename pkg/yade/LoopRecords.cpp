// PendularLoop's record store, out of line (see LoopRecords.hpp): loading and storing a record, the
// shared invariants and their key, reconciling the records with the container, the sync with YADE's objects.
#include "LoopRecords.hpp"
#include "LoopInstrumentation.hpp"

#include <boost/python/converter/shared_ptr_deleter.hpp>
#include <algorithm>
#include <array>
#include <type_traits>

namespace yade {
namespace pendular {
	void RecordStore::load(Record& rec, const shared_ptr<Interaction>& I)
	{
		const auto& geom     = static_cast<const ScGeom&>(*I->geom);
		const auto& phys     = static_cast<const PendularPhys&>(*I->phys);
		rec.id1              = I->getId1();
		rec.id2              = I->getId2();
		rec.invariants       = invariantsOf(phys);
		rec.isActive         = I->isActive;
		rec.normal           = geom.normal;
		rec.shearInc         = geom.shearInc;
		rec.penetrationDepth = geom.penetrationDepth;
		forEachRecordedPhys([&](auto recorded, auto own) { rec.*recorded = phys.*own; });
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
			KeyArchive(std::string& key, const std::array<const void*, recordedPhysCount()>& skip)
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
					              "an attribute of PendularPhys whose type RecordStore::invariantsKey cannot compare: add the type to KeyArchive");
					if (std::find(skip.begin(), skip.end(), static_cast<const void*>(&value)) == skip.end())
						key.append(reinterpret_cast<const char*>(&value), sizeof(T));
				}
			}
			std::string&                                       key;
			const std::array<const void*, recordedPhysCount()> skip;
		};
	} // namespace

	// The entry of `invariants` for the bridge and contact parameters of `phys`. PendularPhys makes its
	// bridge from its own members (Ip2, and again when loaded), so physics with the same members, bit for
	// bit, have the same bridge: they share an entry (the bridge is checked as well, cheaply). The members
	// are those that serialize() names (KeyArchive), so that an attribute added to PendularPhys is part of
	// the key without being listed here.
	std::string RecordStore::invariantsKey(const PendularPhys& phys)
	{
		const Real  bridge[] = { phys.bridge.rupture, phys.bridge.force0, phys.bridge.force_rupture };
		const int   model    = int(phys.bridge.m.index());
		std::string key(reinterpret_cast<const char*>(bridge), sizeof(bridge));
		key.append(reinterpret_cast<const char*>(&model), sizeof(model));
		// Every attribute but those of the record: the entry's prototype stands for the physics of all its
		// records when their objects are made again (store).
		std::array<const void*, recordedPhysCount()> skip {};
		std::size_t                                  skipped = 0;
		forEachRecordedPhys([&](auto, auto own) { skip[skipped++] = &(phys.*own); });
		KeyArchive archive(key, skip);
		boost::serialization::access::serialize(archive, const_cast<PendularPhys&>(phys), 0u);
		return key;
	}

	int RecordStore::invariantsOf(const PendularPhys& phys)
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

	void RecordStore::release(int index)
	{
		Invariants& entry = invariants[index];
		if (--entry.users > 0) return;
		invariantsIndex.erase(invariantsKey(*entry.prototype)); // a copy of the physics it was made from: the same key
		entry.prototype.reset();
		freeInvariants.push_back(index);
	}

	void RecordStore::forget(int index)
	{
		release(records[index].invariants);
		interactions[index].reset();
		freeRecords.push_back(index);
	}

	// What a step changes: the geometry, the forces and whether the bridge exists. The contact point and
	// the radii, which the record does not keep, follow from the bodies as gathered for the record's last
	// step (the particles, not gathered again before the objects are brought up to date), by the
	// arithmetic of sphereGeometry. An interaction that holds the placeholders gets a new ScGeom (all its
	// attributes are the record's or follow from the bodies; the axes of ScGeom::rotate are computed
	// before any use) and a copy of its invariants' prototype physics.
	bool RecordStore::store(const Record& rec, Interaction& I, const std::vector<Particle>& seen) const
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
		geom.shearInc         = shearIncOf(rec, seen);
		geom.penetrationDepth = rec.penetrationDepth;
		if (size_t(math::max(rec.id1, rec.id2)) < seen.size()) {
			const Particle& p1 = seen[rec.id1];
			geom.contactPoint  = contactPointOf(p1, rec.normal, rec.penetrationDepth);
			geom.radius1       = p1.radius;
			geom.radius2       = seen[rec.id2].radius;
		} else if (make) { // a body that is gone: nothing to complete the new object from
			geom.contactPoint = Vector3r::Constant(NaN);
			geom.radius1 = geom.radius2 = NaN;
		}
		forEachRecordedPhys([&](auto recorded, auto own) { phys.*own = rec.*recorded; });
		return make;
	}

	void RecordStore::settle(const InteractionContainer& container, std::vector<Slot>& slots)
	{
		for (auto& list : toForget) {
			for (const int index : list)
				forget(index);
			list.clear();
		}
		for (auto& list : toRecord) {
			for (const long i : list) {
				int index;
				if (freeRecords.empty()) {
					index = int(records.size());
					records.emplace_back();
					interactions.emplace_back();
				} else {
					index = freeRecords.back();
					freeRecords.pop_back();
				}
				const shared_ptr<Interaction>& I = container[i];
				load(records[index], I);
				interactions[index] = I;
				slots[i].record     = index;
				withObjects.push_back(index);
			}
			list.clear();
		}
		dropObjects();
	}

	void RecordStore::dropObjects()
	{
		size_t kept = 0;
		for (const int index : withObjects) {
			const auto& I = interactions[index];
			if (!I || !I->geom || holdsPlaceholders(*I)) continue; // forgotten, reset, or listed twice
			// An object that Python assigned has a control block of its own, which holds the Python object
			// (boost::python's deleter): Python may hold it though the count is 1.
			const bool fromPython = boost::get_deleter<boost::python::converter::shared_ptr_deleter>(I->geom)
			        || boost::get_deleter<boost::python::converter::shared_ptr_deleter>(I->phys);
			if (!fromPython && I->geom.use_count() == 1 && I->phys.use_count() == 1) {
				I->geom      = placeholderGeom();
				I->phys      = placeholderPhys();
				placeholders = true;
			} else
				withObjects[kept++] = index; // held by Python: written by the next sync
		}
		withObjects.resize(kept);
	}

	// The collider erases the potential interactions whose bounding boxes parted (an erasure moves the last
	// entry of the container into the hole) and appends new ones: each recorded interaction is found at its
	// place in the container (Interaction::linIx), where its slot now is. One that is no longer in the
	// container (none should be: the collider erases only potential interactions, the Python paths that erase
	// drop the records first) goes back to its objects.
	void RecordStore::reconcile(long colliderRuns, InteractionContainer& container, std::vector<Slot>& slots, const std::vector<Particle>& particles)
	{
		const bool moved = colliderRuns != reconciledRuns || &container != reconciledContainer || container.size() != reconciledSize;
		reconciledRuns      = colliderRuns;
		reconciledContainer = &container;
		reconciledSize      = container.size();
		if (live() == 0 || !moved) return;
		const long size = long(container.size());
		slots.resize(size_t(size));
		const size_t n = records.size();
		for (size_t index = 0; index < n; ++index) {
			// The Interaction is read for its place only: a miss per record, overlapped by the prefetch.
			if (index + prefetchAhead < n && interactions[index + prefetchAhead]) __builtin_prefetch(interactions[index + prefetchAhead].get());
			const shared_ptr<Interaction>& I = interactions[index];
			if (!I) continue;
			const long at = I->linIx;
			if (at >= 0 && at < size && container[at] == I) {
				Slot& slot = slots[at];
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
			store(records[index], *I, particles);
			forget(int(index));
		}
	}

	void RecordStore::reorder(std::vector<Slot>& slots, const std::vector<Particle>& particles)
	{
		if (records.empty()) return;
		const std::size_t n = slots.size();
		std::vector<Record>                  ordered;
		std::vector<shared_ptr<Interaction>> orderedInteractions;
		ordered.reserve(records.capacity()); // room for the next steps' new records without moving them all again
		orderedInteractions.reserve(records.capacity());
		std::vector<bool> placed(records.size(), false);
		for (size_t k = 0; k < n; ++k) {
			Slot& slot = slots[k];
			if (!slot.recorded()) continue;
			placed[slot.record] = true;
			ordered.push_back(records[slot.record]);
			orderedInteractions.push_back(std::move(interactions[slot.record]));
			slot.record = int(ordered.size()) - 1;
		}
		// A record whose interaction is no longer in the container (reconcile has handed them back) goes
		// back to its objects.
		for (size_t index = 0; index < records.size(); ++index)
			if (!placed[index] && interactions[index]) {
				store(records[index], *interactions[index], particles);
				release(records[index].invariants);
			}
		records.swap(ordered);
		interactions.swap(orderedInteractions);
		freeRecords.clear();
		withObjects.clear();
		for (size_t index = 0; index < records.size(); ++index) {
			if (index + prefetchAhead < records.size()) __builtin_prefetch(interactions[index + prefetchAhead].get());
			if (!holdsPlaceholders(*interactions[index])) withObjects.push_back(int(index));
		}
	}

	void RecordStore::sync(bool drop, bool all, std::vector<Slot>& slots, const std::vector<Particle>& particles)
	{
		if ((all || drop) && (stale || placeholders)) { // else nothing to write (a loop of Python calls asks at every call)
			for (size_t index = 0; index < records.size(); ++index) {
				const auto& I = interactions[index];
				if (I && (stale || holdsPlaceholders(*I)) && store(records[index], *I, particles)) withObjects.push_back(int(index));
			}
			placeholders = false;
		} else if (!(all || drop) && stale)
			for (const int index : withObjects)
				if (interactions[index]) store(records[index], *interactions[index], particles);
		stale = false;
		if (!drop) return;
		records.clear();
		interactions.clear();
		invariants.clear();
		invariantsIndex.clear();
		freeRecords.clear();
		freeInvariants.clear();
		withObjects.clear();
		for (auto& slot : slots)
			if (slot.recorded()) slot.record = Slot::none;
	}

	Vector3r RecordStore::shearIncOf(const Record& rec, const std::vector<Particle>& seen) const
	{
		if (!(rec.penetrationDepth >= 0) || size_t(math::max(rec.id1, rec.id2)) >= seen.size()) return rec.shearInc;
		const Particle& p1           = seen[rec.id1];
		const Vector3r  contactPoint = contactPointOf(p1, rec.normal, rec.penetrationDepth);
		const Vector3r  zero         = Vector3r::Zero();
		return shearIncrement(p1, seen[rec.id2], rec.normal, rec.penetrationDepth, contactPoint, zero, zero, seenRatcheting, seenDt);
	}

	bool RecordStore::makeObjects(const shared_ptr<Interaction>& I, const std::vector<Slot>& slots, const std::vector<Particle>& particles)
	{
		// Its slot, unless the collider has moved it since the last pass (then a search).
		long       index = -1;
		const long at    = I->linIx;
		if (at >= 0 && std::size_t(at) < slots.size() && slots[at].same(I) && slots[at].recorded()) index = slots[at].record;
		for (std::size_t k = 0; index < 0 && k < records.size(); ++k)
			if (interactions[k] == I) index = long(k);
		if (index < 0 || interactions[index] != I) return false;
		if (store(records[index], *I, particles)) withObjects.push_back(int(index));
		return true;
	}

	long RecordStore::heldBytes() const
	{
		return capacityBytes(records) + capacityBytes(interactions) + capacityBytes(invariants) + capacityBytes(freeRecords) + capacityBytes(freeInvariants)
		        + capacityBytes(withObjects) + capacityBytes(toRecord) + capacityBytes(toForget);
	}
} // namespace pendular
} // namespace yade
