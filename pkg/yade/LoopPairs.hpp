// PendularLoop's pairs: what the loop knows of each entry of YADE's interaction container between two
// passes, the bound on potential pairs' gaps, and the list of the entries a pass must visit (skipFar).
// A Slot per entry holds the interaction seen there, its ids, its record or whether it is a potential
// pair, and for a potential pair a lower bound of its gap. The bound holds within an epoch: a pair
// checked at step s with gap g(s) stores g(s) - 2 D(s), where D is the largest distance of a body from
// its position at the start of the epoch; either body moved at most D(s) + D(t) between s and t, so
// g(t) >= g(s) - 2 D(s) - 2 D(t), and the pair is still apart at step t if its bound exceeds 2 D(t). The
// epoch starts again (every potential pair checked) when a body has moved epochMove of the smallest
// radius, and when any body's radius, film reach, material kind or subdomain changed (Near.radius
// encodes them), so that the bound holds for the radii it was computed with; films that reach beyond
// the surface (formation='films') change every step: no bound then. The gathering checks this per body
// (startScan, observe, endScan). A potential pair whose bound exceeds twice the largest move an epoch
// allows stays apart for the whole epoch: after a full pass the list holds every other entry, and until
// the collider runs again, the epoch ends or anything changes the container, a pass visits only those.
// Pairs owns the slots, the bodies as of the start of the epoch, the epoch's scalars, and the list with
// what it was built for. The per-entry and per-body functions are inline.
#pragma once

#include "LoopBodies.hpp"

#include <core/InteractionContainer.hpp>

#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

namespace yade {
namespace pendular {
	// An epoch of the bound ends when a body has moved this fraction of the smallest sphere radius from
	// where it was at its start.
	constexpr Real epochMove = 0.1;
	// Entries of the container per chunk of the pass's static schedule: small enough that the threads
	// get nearly equal shares of a short list (with a few chunks per thread, one chunk more is a large
	// share), large enough that a thread's entries stay mostly contiguous.
	constexpr long passChunk = 256;

	// Per entry of the interaction container, what the last step saw: the interaction, its ids and
	// whether it was potential. Held by a weak_ptr and compared by owner (control block), not by
	// address: a new interaction allocated where an erased one was is still another owner.
	struct Slot {
		boost::weak_ptr<Interaction> interaction;
		Body::id_t                   id1 = 0, id2 = 0;
		// >= 0: index in records; none: a real interaction without record (or not yet seen); potentialPair.
		int record = none;
		// potentialPair: a lower bound of the surface gap minus 2 epochDisplacement at the start of the
		// epoch [m], -inf if unknown; rounded down to float to keep the slot at 32 B.
		float                gapBound = -std::numeric_limits<float>::infinity();
		static constexpr int none = -1, potentialPair = -2;
		bool                 potential() const { return record == potentialPair; }
		bool                 recorded() const { return record >= 0; }
		bool same(const shared_ptr<Interaction>& I) const { return !interaction.owner_before(I) && !I.owner_before(interaction); }
		// The order of the container sort: by id1, then id2 (ids are >= 0).
		uint64_t key() const { return (uint64_t(uint32_t(id1)) << 32) | uint32_t(id2); }
	};
	static_assert(sizeof(Slot) == 32, "a Slot is 32 B: two per cache line");

	// A body as the check of a potential pair sees it: the centre and the radius plus the reach, signed:
	// > 0 a PendularMat sphere of this subdomain, < 0 (negated) one of another subdomain, 0 any other body.
	// films: some sphere has a reach (else it is 0 and not read: it is on the particle's second line).
	struct Near {
		Vector3r pos;
		Real     radius;
	};
	inline Near nearOf(const Particle& p, int subdomain, bool films)
	{
		if (p.kind != Particle::pendularSphere) return Near { Vector3r::Zero(), 0 };
		const Real r = films ? p.radius + p.reach : p.radius;
		return Near { p.pos, p.subdomain == subdomain ? r : -r };
	}
	// The largest float not above x: a lower bound that fits the 32-byte slot.
	inline float roundedDown(Real x)
	{
		float f = float(x);
		if (Real(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
		return f;
	}

	// An atomic flag that the per-scene state can be assigned with (its value is copied).
	struct SharedFlag {
		std::atomic<bool> value { false };
		SharedFlag() = default;
		SharedFlag(const SharedFlag& other)
		        : value(other.value.load())
		{
		}
		SharedFlag& operator=(const SharedFlag& other)
		{
			value = other.value.load();
			return *this;
		}
		SharedFlag& operator=(bool v)
		{
			value = v;
			return *this;
		}
		operator bool() const { return value; }
	};

	class Pairs {
	public:
		std::vector<Slot> slots;

		// The bound. The bodies as of the start of the epoch; the largest distance a body has moved since
		// [m], the smallest sphere radius of the epoch [m] and the epoch's number; fullCheck: every potential
		// pair is checked this step; epochPending: the last pass started an epoch, whose bodies the next
		// gathering takes from the particles of that pass (previous); films: some sphere gathered by the last
		// gathering has a film's reach.
		std::vector<Near> epoch;
		Real              epochDisplacement = 0, epochRmin = 0;
		long              epochCount        = 0;
		bool              fullCheck = true, epochPending = false, films = false;

		// A potential pair apart by the bound alone: its gap at its last check, less what the bodies can have
		// moved since, is still positive, so nothing of it is read but the slot.
		bool apartByBound(const Slot& slot) const { return !fullCheck && slot.gapBound > 2 * epochDisplacement; }
		// A gathering of n bodies starts (comparable: the last pass's particles are of the same bodies).
		// Returns the first value of its `restart`; takeEpoch: its bodies start the epoch (epochPending).
		int startScan(std::size_t n, bool comparable, bool& takeEpoch)
		{
			takeEpoch         = epochPending && comparable;
			const int restart = epochPending ? !comparable : epoch.size() != n;
			epoch.resize(n);
			return restart;
		}
		// One body of the gathering: p as gathered, last as the last pass gathered it; into the gathering's
		// reduction of restart, films, the smallest radius and the largest squared move.
		__attribute__((always_inline)) void observe(std::size_t id, const Particle& p, const Particle& last, bool takeEpoch, int subdomain, int& restart,
		                                            int& films, Real& rmin, Real& move2)
		{
			if (takeEpoch) epoch[id] = nearOf(last, subdomain, true);
			if (p.kind != Particle::pendularSphere) {
				restart = math::max(restart, int(epoch[id].radius != 0));
				return;
			}
			const Near q = nearOf(p, subdomain, true);
			films        = math::max(films, int(p.reach != 0));
			rmin         = math::min(rmin, p.radius);
			restart      = math::max(restart, int(epoch[id].radius != q.radius));
			move2        = math::max(move2, (p.pos - epoch[id].pos).squaredNorm());
		}
		// After the gathering, from its reductions (move: the largest distance from the epoch's start).
		void endScan(int restart, int anyFilms, Real move, Real rmin)
		{
			fullCheck    = restart || anyFilms || !(move < epochMove * rmin);
			films        = anyFilms;
			epochPending = fullCheck;
			if (fullCheck) {
				epochDisplacement = 0;
				epochRmin         = rmin;
				++epochCount;
			} else
				epochDisplacement = math::max(epochDisplacement, move);
		}

		// The list: the container entries a pass of this epoch may have to visit (valid: what it was built for
		// below). Atomic validity: the wrapped Python paths drop it from other threads.
		std::vector<long>           work;
		SharedFlag                  workValid;
		long                        workEpoch = -1, workColliderRuns = -1;
		const InteractionContainer* workContainer = nullptr;
		std::size_t                 workSize      = 0;
		// Whether the list holds every entry that this pass must visit: the same epoch, collider runs and
		// container as it was built for. Behind that, the first and last entries must be the interactions of
		// the last pass (an erasure moves the last entry into its hole, an insertion appends: erasing and
		// inserting one keeps the size, not the last entry).
		bool listValid(long colliderRuns, InteractionContainer& container) const
		{
			const long size = long(container.size());
			return workValid && workEpoch == epochCount && workColliderRuns == colliderRuns && workContainer == &container && long(workSize) == size
			        && (size == 0 || (slots[0].same(container[0]) && slots[size - 1].same(container[size - 1])));
		}
		// What a full pass leaves out of the list: the potential pairs whose bound on the gap exceeds twice
		// the largest move of the epoch (epochMove of its smallest radius, before which the epoch ends).
		Real threshold() const { return 2 * (epochMove * epochRmin); }
		// A full pass of `size` entries on `threads` threads lists the entries as it visits them (list), each
		// thread those of its chunks of the schedule.
		void startListing(int threads, long size)
		{
			listed.resize(std::size_t(threads));
			for (auto& list : listed)
				list.clear();
			chunkEnds.resize(std::size_t((size + passChunk - 1) / passChunk));
		}
		// Entry i, just visited by `thread` (its slot holds its interaction).
		__attribute__((always_inline)) void list(long i, const Slot& slot, Real threshold, int thread, long size)
		{
			if (!(slot.potential() && Real(slot.gapBound) >= threshold)) listed[std::size_t(thread)].push_back(i);
			if ((i + 1) % passChunk == 0 || i + 1 == size) chunkEnds[std::size_t(i / passChunk)] = ChunkEnd { thread, long(listed[std::size_t(thread)].size()) };
		}
		// After a full pass: the list from the threads' lists, chunk by chunk in the container's order, for
		// `container` as it is; use = false: no list (the next pass is a full one). Returns use.
		bool buildList(bool use, long colliderRuns, InteractionContainer& container);

		long heldBytes() const;

	private:
		// What a full pass lists: per thread, the entries it listed; per chunk of the pass's schedule, the
		// thread that visited it and the end of the chunk's entries in that thread's list.
		struct ChunkEnd {
			int  thread = 0;
			long end    = 0;
		};
		std::vector<std::vector<long>> listed;
		std::vector<ChunkEnd>          chunkEnds;
	};
} // namespace pendular
} // namespace yade
