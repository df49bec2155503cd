// The prefetch of the per-body and per-interaction passes of PendularLoop and PendularIntegrator.
#pragma once

#include <cstddef>

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
} // namespace pendular
} // namespace yade
