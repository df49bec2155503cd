// PendularLoop's pairs, their once-per-full-pass part (see LoopPairs.hpp): the list of entries to visit
// merged from the threads' lists, and the bytes the pairs hold.
#include "LoopPairs.hpp"
#include "LoopInstrumentation.hpp"

namespace yade {
namespace pendular {
	bool Pairs::buildList(bool use, long colliderRuns, InteractionContainer& container)
	{
		work.clear();
		workValid = use;
		if (!use) return false;
		std::vector<long> from(listed.size(), 0);
		for (const ChunkEnd& chunk : chunkEnds) {
			const auto& list = listed[std::size_t(chunk.thread)];
			work.insert(work.end(), list.begin() + from[std::size_t(chunk.thread)], list.begin() + chunk.end);
			from[std::size_t(chunk.thread)] = chunk.end;
		}
		workEpoch        = epochCount;
		workColliderRuns = colliderRuns;
		workContainer    = &container;
		workSize         = container.size();
		return true;
	}

	long Pairs::heldBytes() const { return capacityBytes(slots) + capacityBytes(epoch) + capacityBytes(work) + capacityBytes(listed) + capacityBytes(chunkEnds); }
} // namespace pendular
} // namespace yade
