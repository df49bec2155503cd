// PendularLoop's record store: the state of each recorded sphere-sphere bridge between two steps, and
// its sync with YADE's objects. A Record holds what a step changes of ScGeom and PendularPhys, under
// their names, in two cache lines, so that a step reads and writes those two lines per interaction
// instead of the Interaction, ScGeom and PendularPhys objects (about 12, scattered over the heap). What
// a step does not change (the bridge's invariants and the contact parameters) is shared by every record
// with the same ones (Invariants, one entry for all the bridges of a monodisperse material); what
// follows from the record and the bodies (the contact point, the radii) is written only into the
// objects. A recorded interaction holds two placeholders shared by all (so that YADE's collider sees
// it real) instead of its own ScGeom and PendularPhys, which are made from the record when something
// reads them (store) and dropped again after the next pass if nothing else holds them (dropObjects).
// RecordStore owns the records, their interactions, the invariants, the free entries, the per-thread
// lists of a pass and what the records were last matched to; it is changed only between passes (the
// pass reads and writes records in place). Loading, storing and matching are out of line; the
// record's views for the law (RecordGeom, RecordPhys) are inline.
#pragma once

#include "LoopGeometry.hpp"
#include "LoopPairs.hpp"

#include <core/Interaction.hpp>
#include <pkg/dem/ScGeom.hpp>

#include <string>
#include <unordered_map>
#include <vector>

namespace yade {
namespace pendular {
	struct alignas(64) Record {
		Body::id_t id1, id2;    // first: what the pass reads first
		int        invariants;  // index in RecordStore::invariants
		bool       active;      // PendularPhys
		bool       isActive;    // Interaction::isActive
		// ScGeom
		Vector3r normal, shearInc;
		Real     penetrationDepth;
		// PendularPhys
		Vector3r normalForce, shearForce;
		Real     Fcap;
	};
	static_assert(sizeof(Record) == 128 && alignof(Record) == 64, "a Record is two whole cache lines: keep it so");
	// The members of PendularPhys that a Record holds, each with its own: the one list that loading and
	// storing a record and RecordStore::invariantsKey (which leaves them out) follow.
	template <class Visit> constexpr void forEachRecordedPhys(Visit&& visit)
	{
		visit(&Record::active, &PendularPhys::active);
		visit(&Record::Fcap, &PendularPhys::Fcap);
		visit(&Record::normalForce, &PendularPhys::normalForce);
		visit(&Record::shearForce, &PendularPhys::shearForce);
	}
	constexpr std::size_t recordedPhysCount()
	{
		std::size_t n = 0;
		forEachRecordedPhys([&n](auto, auto) { ++n; });
		return n;
	}

	// The members of PendularPhys that a step of a record reads and does not change, and the whole
	// physics they came from (every member but those of the record), from which the objects of a
	// record are made again when something reads them (see RecordStore::store).
	struct Invariants {
		capillary::Bridge              bridge;
		Real                           kn, cn, ks, cs, tangensOfFrictionAngle, Vb;
		bool                           wet, forceInContact;
		shared_ptr<const PendularPhys> prototype;
		long                           users = 0; // records that use it; freed at 0 (see release)
	};

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

	// What a recorded interaction holds instead of its own ScGeom and PendularPhys: one pair for all,
	// never read or written by the loop (the record is the state). YADE's collider only asks whether an
	// interaction has both (Interaction::isReal); a law that ever read them would find kn = 0 and reset
	// the interaction (our law's check of rejected contact parameters) rather than compute with them.
	inline const shared_ptr<IGeom>& placeholderGeom()
	{
		static const shared_ptr<IGeom> geom(new ScGeom());
		return geom;
	}
	inline const shared_ptr<IPhys>& placeholderPhys()
	{
		static const shared_ptr<IPhys> phys(new PendularPhys());
		return phys;
	}
	inline bool holdsPlaceholders(const Interaction& I) { return I.geom == placeholderGeom(); }

	class RecordStore {
	public:
		// The records and their interactions (kept alive while recorded; read only when loaded, stored or
		// reset); withObjects lists the records that may have their own objects.
		std::vector<Record>                  records;
		std::vector<shared_ptr<Interaction>> interactions;
		std::vector<Invariants>              invariants;
		std::vector<int>                     withObjects;
		// Per thread of a pass: container entries to record, records to free after the pass (settle).
		std::vector<std::vector<long>> toRecord;
		std::vector<std::vector<int>>  toForget;
		// The scene of the records; stale: the records are newer than the objects; placeholders: some
		// recorded interaction may hold the placeholders.
		Scene* scene        = nullptr;
		bool   stale        = false;
		bool   placeholders = false;
		// The last pass's time step and Ig2's avoidGranularRatcheting: with the particles of that pass, what
		// the shearInc of a record in contact follows from (shearIncOf).
		Real seenDt         = 0;
		bool seenRatcheting = true;

		long live() const { return long(records.size()) - long(freeRecords.size()); }
		long liveInvariants() const { return long(invariants.size()) - long(freeInvariants.size()); }
		// The per-thread lists for a pass on `threads` threads.
		void useThreads(int threads)
		{
			toRecord.resize(std::size_t(threads));
			toForget.resize(std::size_t(threads));
		}
		// The shearInc of a record as of its last step, from `seen`, the particles that step read.
		Vector3r shearIncOf(const Record& rec, const std::vector<Particle>& seen) const;
		// Writes the record into its interaction's objects, made first if the interaction holds the
		// placeholders; true if they were made. seen: the particles of the record's last step (the particles
		// between two steps, the previous ones during a pass).
		bool store(const Record& rec, Interaction& I, const std::vector<Particle>& seen) const;
		// The objects of a recorded interaction I from its record, if it holds the placeholders; false if no
		// record of this store is I's.
		bool makeObjects(const shared_ptr<Interaction>& I, const std::vector<Slot>& slots, const std::vector<Particle>& particles);
		// After the collider may have changed `container` (another run, container or size than at the last
		// call): the slot of each record's interaction (Interaction::linIx); one that is no longer in the
		// container goes back to its objects.
		void reconcile(long colliderRuns, InteractionContainer& container, std::vector<Slot>& slots, const std::vector<Particle>& particles);
		// After the pass, in one thread: frees the records of the interactions reset or handed back to the
		// objects, records the interactions that qualified (their objects replaced by the placeholders unless
		// something else holds them: Python) and drops the objects made since the last pass (dropObjects).
		void settle(const InteractionContainer& container, std::vector<Slot>& slots);
		// Brings the objects up to date (see PendularLoop::syncScene); drop: and forgets every record.
		void sync(bool drop, bool all, std::vector<Slot>& slots, const std::vector<Particle>& particles);
		// After a sort of the container and its slots: the records in the slots' order, with room for more;
		// a record whose interaction is no longer in the container goes back to its objects.
		void reorder(std::vector<Slot>& slots, const std::vector<Particle>& particles);
		// The key of `phys`'s entry of invariants (see invariantsOf).
		static std::string invariantsKey(const PendularPhys& phys);
		long               heldBytes() const;

	private:
		// The distinct invariants of the records, and where each is, by the PendularPhys members they are
		// made from (see invariantsOf); the free entries of records and invariants.
		std::unordered_map<std::string, int> invariantsIndex;
		std::vector<int>                     freeRecords, freeInvariants;
		// The collider's runs and the container the slots of the records were last matched to (reconcile).
		long                        reconciledRuns      = -1;
		const InteractionContainer* reconciledContainer = nullptr;
		std::size_t                 reconciledSize      = 0;

		void load(Record& rec, const shared_ptr<Interaction>& I);
		int  invariantsOf(const PendularPhys& phys);
		// A record no longer uses entry `index` of invariants (freed when none does, so that a polydisperse
		// packing keeps only the entries of the bridges that exist).
		void release(int index);
		// Frees a record whose interaction is reset or has its own objects again.
		void forget(int index);
		// The recorded interactions whose objects nothing but the interaction holds get the placeholders.
		void dropObjects();
	};
} // namespace pendular
} // namespace yade
