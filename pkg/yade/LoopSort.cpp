// PendularLoop's container sort, out of line (see LoopSort.hpp): the counting sort of YADE's interaction
// container by (id1, id2), with its slots.
#include "LoopSort.hpp"

#include <algorithm>
#include <utility>

namespace yade {
namespace pendular {
	namespace {
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
	} // namespace

	void sortContainer(InteractionContainer& container, std::vector<Slot>& slots, uint64_t bodies)
	{
		const size_t n = container.size();
		slots.resize(n);
		std::vector<std::pair<uint64_t, size_t>> order(n); // key, entry before the sort
		for (size_t i = 0; i < n; ++i) {
			const auto& I = container[i];
			if (!slots[i].same(I)) { // new since the last pass (reconcile has placed the records), the pass decides
				slots[i]             = Slot {};
				slots[i].interaction = I;
				slots[i].id1         = I->getId1();
				slots[i].id2         = I->getId2();
			}
			order[i] = { slots[i].key(), i };
		}
		sortByKey(order, bodies);
		std::vector<shared_ptr<Interaction>> sorted(n);
		std::vector<Slot>                    sortedSlots(n);
		for (size_t k = 0; k < n; ++k) {
			sorted[k]      = std::move(container[order[k].second]);
			sortedSlots[k] = std::move(slots[order[k].second]);
		}
		for (size_t k = 0; k < n; ++k) {
			// Every Interaction gets its new place: a miss each, overlapped by the prefetch.
			if (k + prefetchAhead < n) __builtin_prefetch(sorted[k + prefetchAhead].get(), 1);
			container[k]        = std::move(sorted[k]);
			container[k]->linIx = int(k);
		}
		slots.swap(sortedSlots);
	}
} // namespace pendular
} // namespace yade
