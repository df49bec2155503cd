// What the per-body and per-interaction passes of PendularLoop and PendularIntegrator share: the
// prefetch and the number of OpenMP threads.
#pragma once

#include <cstddef>

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
