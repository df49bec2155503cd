// PendularLoop's work partition, out of line (see LoopPartition.hpp): the cut of the bodies and of the
// list into the threads' parts after a full pass, from the estimated costs and the measured paces.
#include "LoopPartition.hpp"
#include "LoopInstrumentation.hpp"

#include <algorithm>

namespace yade {
namespace pendular {
	// Each thread computes the listed entries whose first body is in its part of the bodies, and gathers,
	// hands over the forces of and moves (PendularIntegrator) the bodies of its part: a body's data then
	// stays in the cache of one core, except for the interactions that cross a part's border (few where ids
	// follow space, as in a packing built layer by layer). Without it, every step moves most bodies' lines
	// from the core that wrote them to the other one and back (docs/performance.md, "Parts of the bodies,
	// one per thread"). The bodies are cut where the estimated cost of the bodies and their entries is
	// shared in inverse proportion to the threads' paces (threadPace). Each part of the list holds first the
	// entries that reach another part, then the others, each group in the container's order: the same order
	// at every step of the epoch, so that each thread sums the forces on a body in the same order (on one
	// thread, the container's order: InteractionLoop's sums).
	void WorkPartition::share(std::vector<long>& work, const std::vector<Slot>& slots, long n, int threads, std::vector<Real>& threadPace)
	{
		if (threads < 2 || n == 0) {
			clear(threadPace);
			return;
		}
		const float total = estimateCosts(work, slots, n);
		updatePaces(threads, threadPace);
		cutBodies(total, n, threads, threadPace);
		orderWork(work, slots, n, threads);
		findBorders(n, threads);
	}

	void WorkPartition::clear(std::vector<Real>& threadPace)
	{
		bodyParts.clear();
		workParts.clear();
		workBorders.clear();
		borders.clear();
		sharedBodies.clear();
		threadPace.clear();
		partCost.clear();
		paceTime.clear();
		paceSteps = 0;
	}

	// Estimated cost of a body and its entries, in steps of a record: a body's gathering, hand-over and
	// move together take about as long as a record's step (a few cache lines and a few dozen operations
	// each), a potential pair a distance check, an interaction through the dispatchers more than a record.
	// Returns the total.
	float WorkPartition::estimateCosts(const std::vector<long>& work, const std::vector<Slot>& slots, long n)
	{
		shareCost.assign(std::size_t(n), 1.f);
		float total = float(n);
		for (const long i : work) {
			const Slot& slot = slots[i];
			const float c    = slot.recorded() ? 1.f : slot.potential() ? 0.25f : 2.f;
			if (slot.id1 >= 0 && slot.id1 < n) shareCost[std::size_t(slot.id1)] += c;
			total += c;
		}
		return total;
	}

	// Each thread's pace, from the passes on the list since the last share (see threadPace), smoothed (half the
	// last one's): its share of the estimated cost is inversely proportional to it. The estimate alone misses
	// what differs between the parts (moving bodies with more bridges in one, a fixed floor in the other) and
	// between the cores (one shared with other processes, or slowed by its virtual machine, for seconds; see
	// docs/performance.md, "Parts that follow the threads' measured paces").
	void WorkPartition::updatePaces(int threads, std::vector<Real>& threadPace)
	{
		if (long(threadPace.size()) != threads) threadPace.assign(std::size_t(threads), 1);
		if (paceSteps >= minPaceSteps && long(partCost.size()) == threads && long(paceTime.size()) == threads) {
			std::vector<double> perCost(static_cast<std::size_t>(threads));
			double              mean     = 0;
			bool                measured = true;
			for (int k = 0; k < threads; ++k) {
				measured = measured && partCost[std::size_t(k)] > 0 && paceTime[std::size_t(k)] > 0;
				perCost[std::size_t(k)] = paceTime[std::size_t(k)] / double(partCost[std::size_t(k)]);
				mean += perCost[std::size_t(k)] / threads;
			}
			for (int k = 0; measured && k < threads; ++k)
				threadPace[std::size_t(k)]
				        = math::min(maxPace, math::max(1 / maxPace, 0.5 * threadPace[std::size_t(k)] + 0.5 * Real(perCost[std::size_t(k)] / mean)));
		}
		paceTime.assign(std::size_t(threads), 0);
		paceSteps = 0;
	}

	// The bodies cut by id where the estimated costs (of `total`) are shared as the inverse paces.
	void WorkPartition::cutBodies(float total, long n, int threads, const std::vector<Real>& threadPace)
	{
		Real shares = 0;
		for (const Real p : threadPace)
			shares += 1 / p;
		bodyParts.assign(std::size_t(threads) + 1, n);
		bodyParts[0] = 0;
		float sum   = 0;
		Real  below = 1 / threadPace[0]; // the shares of the parts before bound t
		int   t     = 1;
		for (long id = 0; id < n && t < threads; ++id) {
			sum += shareCost[std::size_t(id)];
			while (t < threads && sum >= float(total * below / shares)) {
				bodyParts[std::size_t(t)] = id + 1;
				below += 1 / threadPace[std::size_t(t++)];
			}
		}
		partCost.assign(std::size_t(threads), 0);
		for (int k = 0; k < threads; ++k)
			for (long id = bodyParts[std::size_t(k)]; id < bodyParts[std::size_t(k) + 1]; ++id)
				partCost[std::size_t(k)] += shareCost[std::size_t(id)];
		// The part of each body, looked up once per entry and body below.
		bodyPart.resize(std::size_t(n));
		for (int k = 0; k < threads; ++k)
			std::fill(bodyPart.begin() + bodyParts[std::size_t(k)], bodyPart.begin() + bodyParts[std::size_t(k) + 1], k);
	}

	// The list, stably by the part of each entry's first body, each part's entries that reach another part
	// first (the pass hands them over as soon as they are computed, see handOffs); the parts whose entries
	// reach each body from another part, marked per body (one bit per part), so that findBorders gives the
	// borders in ascending order without sorting.
	void WorkPartition::orderWork(std::vector<long>& work, const std::vector<Slot>& slots, long n, int threads)
	{
		const auto        valid      = [n](Body::id_t id) { return id >= 0 && id < n; };
		const auto        partOfBody = [&](Body::id_t id) { return id < 0 ? 0 : id >= n ? threads - 1 : bodyPart[std::size_t(id)]; };
		const std::size_t words      = (std::size_t(threads) + 63) / 64;
		const auto        reaches    = [&](const Slot& slot, int k) {
                        return (valid(slot.id1) && bodyPart[std::size_t(slot.id1)] != k) || (valid(slot.id2) && bodyPart[std::size_t(slot.id2)] != k);
		};
		workParts.assign(std::size_t(threads) + 1, 0);
		workBorders.assign(std::size_t(threads), 0);
		for (const long i : work) {
			const int k = partOfBody(slots[i].id1);
			++workParts[std::size_t(k) + 1];
			workBorders[std::size_t(k)] += reaches(slots[i], k);
		}
		for (int k = 0; k < threads; ++k)
			workParts[std::size_t(k) + 1] += workParts[std::size_t(k)];
		std::vector<long> next(workParts.begin(), workParts.end() - 1), inner(next.size()), shared(work.size());
		for (int k = 0; k < threads; ++k)
			inner[std::size_t(k)] = workBorders[std::size_t(k)] += workParts[std::size_t(k)];
		reachedBy.assign(std::size_t(n) * words, 0);
		for (const long i : work) {
			const Slot& slot   = slots[i];
			const int   k      = partOfBody(slot.id1);
			const bool  border = reaches(slot, k);
			shared[std::size_t(border ? next[std::size_t(k)]++ : inner[std::size_t(k)]++)] = i;
			for (const Body::id_t id : { slot.id1, slot.id2 })
				if (valid(id) && bodyPart[std::size_t(id)] != k) reachedBy[std::size_t(id) * words + std::size_t(k) / 64] |= uint64_t(1) << (k % 64);
		}
		work.swap(shared);
	}

	// The borders and the shared bodies from reachedBy.
	void WorkPartition::findBorders(long n, int threads)
	{
		const std::size_t words = (std::size_t(threads) + 63) / 64;
		borders.resize(std::size_t(threads));
		for (auto& byPart : borders) {
			byPart.resize(std::size_t(threads));
			for (auto& ids : byPart)
				ids.clear();
		}
		sharedBodies.assign(std::size_t(n), 0);
		for (long id = 0; id < n; ++id)
			for (std::size_t w = 0; w < words; ++w)
				for (uint64_t mask = reachedBy[std::size_t(id) * words + w]; mask != 0; mask &= mask - 1) {
					borders[w * 64 + std::size_t(__builtin_ctzll(mask))][std::size_t(bodyPart[std::size_t(id)])].push_back(Body::id_t(id));
					sharedBodies[std::size_t(id)] = 1;
				}
	}

	long WorkPartition::heldBytes() const
	{
		return capacityBytes(bodyParts) + capacityBytes(workParts) + capacityBytes(workBorders) + capacityBytes(borders) + capacityBytes(sharedBodies)
		        + capacityBytes(handOffs) + capacityBytes(partCost) + capacityBytes(paceTime) + capacityBytes(shareCost) + capacityBytes(bodyPart)
		        + capacityBytes(reachedBy);
	}
} // namespace pendular
} // namespace yade
