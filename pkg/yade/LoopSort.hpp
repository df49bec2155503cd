// PendularLoop's container sort: YADE's interaction container sorted by (id1, id2), its slots with it.
// The collider appends new interactions and an erasure moves the last entry into the hole, so the
// container drifts out of any order and the pass reads the bodies, slots and records of consecutive
// entries from scattered places; body ids of a packing built layer by layer are close in space, so in
// id order a pair's bodies and those of its neighbours in the container share cache lines (and the
// records, which RecordStore::reorder puts in the same order, are read in their order in memory). The
// container's order is only the order of the loop (and of the force sums); InteractionContainer finds
// an interaction through its bodies, and linIx is its back-reference. A full pass counts the entries
// out of order as it visits them (DisorderCount, inline); the sort itself is out of line. Owns nothing
// between steps.
#pragma once

#include "LoopPairs.hpp"

#include <core/InteractionContainer.hpp>

#include <cstdint>
#include <vector>

namespace yade {
namespace pendular {
	// Sorts `container` and `slots` (made for the entries new since the last pass) by (id1, id2), and sets
	// each Interaction's linIx; bodies: the number of bodies, above every id.
	void sortContainer(InteractionContainer& container, std::vector<Slot>& slots, uint64_t bodies);

	// Counts, in one thread's chunks of a full pass, the entries that follow an entry of the same chunk
	// with a larger (id1, id2) (see PendularLoop.sortDisorder).
	struct DisorderCount {
		long     before    = -2; // the entry before, and its key
		uint64_t beforeKey = 0;
		__attribute__((always_inline)) void see(long i, const Slot& slot, long& disorder)
		{
			const uint64_t key = slot.key();
			if (i == before + 1 && key < beforeKey) ++disorder;
			before    = i;
			beforeKey = key;
		}
	};
} // namespace pendular
} // namespace yade
