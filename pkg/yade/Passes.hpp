// What the per-body and per-interaction passes of PendularLoop and PendularIntegrator share: the
// prefetch, the bodies' pointers of a step and the number of OpenMP threads.
#pragma once

#include <core/Body.hpp>
#include <core/Bound.hpp>
#include <core/Engine.hpp>
#include <core/ForceContainer.hpp>
#include <core/State.hpp>

#include <boost/weak_ptr.hpp>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#ifdef YADE_OPENMP
#include <omp.h>
#endif

namespace yade {
namespace pendular {
	// The passes are bound by memory latency: a body or an interaction is several heap objects reached
	// through pointers. Prefetching them a few entries ahead overlaps the misses with the arithmetic
	// of the current one. write = 1: the object will be written.
	template <int write = 0, class T> void prefetchObject(const T* p)
	{
		const char* c = reinterpret_cast<const char*>(p);
		for (std::size_t offset = 0; offset < sizeof(T); offset += 64)
			__builtin_prefetch(c + offset, write);
	}
	// What a pass over the bodies read of each one, for a later pass of the same step: the State and
	// Bound of every body by id (nullptr: erased body), and whether any body is a clump or a clump's member,
	// aspherical (Body::isAspherical), or of another subdomain (yade.mpy). Filled by PendularLoop's gathering
	// and used by PendularIntegrator in the same step (see PendularIntegrator::unsupported), so that a
	// step reads each Body once.
	// parts: the ids of each thread in the per-body passes, thread t of T has [parts[t], parts[t + 1]) (see
	// partOf; PendularLoop chooses them so that a thread moves the bodies whose interactions it computes).
	struct BodyPointers {
		const void*                   scene = nullptr; // the Scene and its iteration they were read in
		long                          iter  = -1;
		std::vector<State*>           states;
		std::vector<const Bound*>     bounds;
		int                           clumps = 0, aspherical = 0, subdomains = 0;
		std::vector<long>             parts;
	};
	// The range [first, second) of indices 0..n-1 that thread `thread` of `threads` takes in a pass shared
	// out by `parts` (threads + 1 ascending bounds from 0 to n), else an even share (as schedule(static)).
	// Every index belongs to exactly one thread whatever parts holds: only the speed depends on it.
	inline std::pair<long, long> partOf(const std::vector<long>& parts, long n, int thread, int threads)
	{
		if (long(parts.size()) == long(threads) + 1 && parts.front() == 0 && parts.back() == n) return { parts[thread], parts[thread + 1] };
		const long share = n / threads, rest = n % threads;
		const long first = thread * share + std::min<long>(thread, rest);
		return { first, first + share + (thread < rest) };
	}
	// OpenMP's thread number and team size in a parallel region (0 and 1 without OpenMP).
	inline int threadNumber()
	{
#ifdef YADE_OPENMP
		return omp_get_thread_num();
#else
		return 0;
#endif
	}
	inline int teamSize()
	{
#ifdef YADE_OPENMP
		return omp_get_num_threads();
#else
		return 1;
#endif
	}
	// One body's entry of BodyPointers (b: nullptr for an erased body): its State and Bound, and its part
	// of the flags (or-ed into the pass's reduction variables). subdomain: the scene's.
	inline void readBody(const Body* b, int subdomain, State*& state, const Bound*& bound, int& clumps, int& aspherical, int& subdomains)
	{
		state = b ? b->state.get() : nullptr;
		bound = b ? b->bound.get() : nullptr;
		if (!b) return;
		clumps |= !b->isStandalone();
		aspherical |= b->isAspherical();
		subdomains |= b->subdomain != subdomain || b->getIsSubdomain() || b->getIsFluidDomainBbox();
	}
	// Whether `engines` is the engine list remembered in `scanned`, its engines compared by owner (so that a
	// new engine made where a freed one was is another engine); if not, remembers it. An engine that looks
	// for others in O.engines does so again only when the list changed.
	inline bool sameEngines(std::vector<boost::weak_ptr<Engine>>& scanned, const std::vector<shared_ptr<Engine>>& engines)
	{
		bool same = scanned.size() == engines.size();
		for (std::size_t i = 0; same && i < scanned.size(); ++i)
			same = !scanned[i].owner_before(engines[i]) && !engines[i].owner_before(scanned[i]);
		if (!same) scanned.assign(engines.begin(), engines.end());
		return same;
	}
	// The force container's summed force and torque entries (its _force and _torque, std::vectors of
	// Vector3r: getForceUnsynced returns the entry itself) of ids 0..size-1 as two arrays, to be written
	// as ForceContainer's addForceUnsynced and reset write them, without a call into libyade per body;
	// nullptrs if the container is not synced, has fewer entries or they are not contiguous.
	struct SummedArrays {
		Vector3r *forces = nullptr, *torques = nullptr;
	};
	inline SummedArrays summedArrays(ForceContainer& container, long size)
	{
		if (size <= 0 || !container.synced) return {};
		const auto last = Body::id_t(size - 1);
		// getForce gives the container's zero beyond its entries
		if (&container.getForce(last) == &container.getForce(std::numeric_limits<Body::id_t>::max())) return {};
		SummedArrays a { const_cast<Vector3r*>(&container.getForceUnsynced(0)), const_cast<Vector3r*>(&container.getTorqueUnsynced(0)) };
		if (&container.getForceUnsynced(last) != a.forces + last || &container.getTorqueUnsynced(last) != a.torques + last) return {};
		return a;
	}
	// stored = value with streaming stores, which bypass the caches: for data that another core reads after
	// this step's barrier. A plain store to a line that the other core read in the last step waits for that
	// copy to be invalidated, a round trip between the cores, which on virtual machines can take several
	// hundred ns (docs/performance.md, "Method" and "Bodies that another thread reads gathered with streaming
	// stores"). The other core then reads the line from memory. The writer calls streamFence before the
	// barrier (streaming stores are not ordered with the others). A plain copy where there are no SSE2
	// streaming stores.
	template <class T> inline void streamStore(T& stored, const T& value)
	{
#ifdef __SSE2__
		static_assert(sizeof(T) % 64 == 0 && alignof(T) >= 64, "whole cache lines");
		const __m128i* from = reinterpret_cast<const __m128i*>(&value);
		__m128i*       to   = reinterpret_cast<__m128i*>(&stored);
		for (std::size_t k = 0; k < sizeof(T) / sizeof(__m128i); ++k)
			_mm_stream_si128(to + k, _mm_load_si128(from + k));
#else
		stored = value;
#endif
	}
	inline void streamFence()
	{
#ifdef __SSE2__
		_mm_sfence();
#endif
	}
	// Entries [first, last) of v set to zero, as the Reals they are (YADE asserts sizeof(Vector3r) == 3 sizeof(Real)),
	// which the compiler makes one memset as ForceContainer::reset's (a fill by Vector3r is a loop of three stores per entry).
	inline void zeroEntries(Vector3r* v, long first, long last)
	{
		if (last > first) std::fill_n(v[first].data(), 3 * (last - first), Real(0));
	}
	// Waits until `flag` holds `value` (stored with release by another thread): spins with the core told
	// so (no flood of loads on the other core's cache line), then yields the core after spinLimit rounds,
	// so that a thread descheduled by the system (processes sharing the cores, OMP_WAIT_POLICY=passive)
	// gets it back instead of waiting out the spinning thread's time slice.
	inline void waitFor(const std::atomic<long>& flag, long value)
	{
		constexpr int spinLimit = 4096; // about 0.1-0.2 ms of pauses, longer than a step's waits on free cores (under 0.1 ms)
		for (int spins = 0; flag.load(std::memory_order_acquire) != value; ++spins) {
			if (spins < spinLimit) {
#if defined(__x86_64__) || defined(__i386__)
				__builtin_ia32_pause();
#elif defined(__aarch64__)
				asm volatile("yield");
#endif
			} else
				std::this_thread::yield();
		}
	}
	// The threads of an engine's passes: its ompThreads if set (> 0), at most OpenMP's maximum.
	inline int passThreads(int ompThreads)
	{
#ifdef YADE_OPENMP
		return ompThreads > 0 && ompThreads < omp_get_max_threads() ? ompThreads : omp_get_max_threads();
#else
		(void)ompThreads;
		return 1;
#endif
	}
} // namespace pendular
} // namespace yade
