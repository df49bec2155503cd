// PendularLoop's work partition: which thread does what. After each full pass that lists the entries
// (see Pairs), share() cuts the bodies by id into one part per thread (bodyParts) and the list into the
// entries whose first body is in each part (workParts), each part's entries that reach another part
// first (up to workBorders), and notes the bodies of each part that other parts' entries reach
// (borders, sharedBodies). A thread then gathers, computes the entries of, hands the forces over for
// and moves (PendularIntegrator) the bodies of its part: a body's data stays in the cache of one core
// except at the parts' borders. The cut shares the bodies' estimated costs in inverse proportion to
// the threads' measured paces (PendularLoop.threadPace). A pass on the list by parts signals through
// handOffs when a thread has computed its entries that reach other parts. Owns those arrays and the
// pace measurements; share() runs once per full pass (out of line), the checks per pass are inline.
#pragma once

#include "LoopPairs.hpp"

#include <atomic>
#include <cstdint>
#include <vector>

namespace yade {
namespace pendular {
	class WorkPartition {
	public:
		// The threads' parts of the bodies and of the list (empty: even parts, see partOf); borders[k][t]:
		// the bodies of part t that the entries of part k reach (ascending). Part k of the list holds first
		// its entries that reach another part, up to workBorders[k], then those within the part.
		std::vector<long>                                 bodyParts, workParts, workBorders;
		std::vector<std::vector<std::vector<Body::id_t>>> borders;
		// Per body: reached by the entries of another thread's part of the list, so gathered with streaming
		// stores (see BodySnapshot::store); empty: none.
		std::vector<uint8_t> sharedBodies;
		// Per thread of a pass on the list by parts, the last pass (handOffPass) whose entries that reach
		// other parts it has computed: the owners of those bodies then hand them over while it computes the
		// rest of its part. One cache line each: the others spin on it.
		struct alignas(64) HandOff {
			std::atomic<long> pass { 0 };
		};
		std::vector<HandOff> handOffs; // made whole for a team (HandOff is not movable), never resized
		long                 handOffPass = 0;
		// Each thread's pace is measured in the passes on the list since the last share: the wall time of its
		// own entries and of its hand-over where the pass does it, without its waits (paceTime, over
		// paceSteps passes), per unit of the estimated cost of its part (partCost).
		std::vector<float>    partCost;
		std::vector<double>   paceTime;
		long                  paceSteps    = 0;
		static constexpr long minPaceSteps = 8; // passes measured before a share follows them
		static constexpr Real maxPace      = 4; // at most this many times the others' (a thread held up by others' processes)

		// Shares `work` (the list, reordered by part) and n bodies between `threads` threads, from the slots
		// of the listed entries and the measured paces, which it updates (threadPace).
		void share(std::vector<long>& work, const std::vector<Slot>& slots, long n, int threads, std::vector<Real>& threadPace);
		// The parts are those of a list of m entries, `threads` threads and n bodies (share made them for
		// this list and these bodies; a pass does not change them). A thread that waits for another's hand-off
		// relies on that thread's part holding its workBorders (workParts as partOf takes it).
		bool valid(long m, int threads, long n) const
		{
			return long(workParts.size()) == threads + 1 && workParts.front() == 0 && workParts.back() == m && long(borders.size()) == threads
			        && long(workBorders.size()) == threads && long(bodyParts.size()) == threads + 1 && bodyParts.back() == n;
		}
		// The number of a pass on the list by parts, whose hand-offs the threads signal with it.
		long nextHandOff(int threads)
		{
			if (long(handOffs.size()) != threads) handOffs = std::vector<HandOff>(std::size_t(threads));
			return ++handOffPass;
		}
		long heldBytes() const;

	private:
		// What share computes the parts from, kept between its calls: each body's estimated cost and part,
		// and the parts whose entries reach it from another part (a bit per part).
		std::vector<float>    shareCost;
		std::vector<int>      bodyPart;
		std::vector<uint64_t> reachedBy;
		void                  clear(std::vector<Real>& threadPace);
		float                 estimateCosts(const std::vector<long>& work, const std::vector<Slot>& slots, long n);
		void                  updatePaces(int threads, std::vector<Real>& threadPace);
		void                  cutBodies(float total, long n, int threads, const std::vector<Real>& threadPace);
		void                  orderWork(std::vector<long>& work, const std::vector<Slot>& slots, long n, int threads);
		void                  findBorders(long n, int threads);
	};
} // namespace pendular
} // namespace yade
