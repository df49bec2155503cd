// PendularLoop's instrumentation: the wall times of its phases (gatherTime, passTime, flushTime,
// sortTime), each thread's busy time in traced passes (traceBusy, busyTimes), and what its arrays and
// objects take in memory (heldBytes through each part's capacityBytes, memory()). It changes nothing that
// the loop computes; the loop's attributes hold what it measures.
#pragma once

#include <lib/base/Math.hpp>

#include <boost/python/dict.hpp>
#include <chrono>
#include <cstddef>
#include <vector>

namespace yade {
namespace pendular {
	using Clock = std::chrono::steady_clock;
	inline Real nanoseconds(Clock::duration d) { return Real(std::chrono::duration_cast<std::chrono::nanoseconds>(d).count()); }
	inline Real nanoseconds(Clock::time_point a, Clock::time_point b) { return nanoseconds(b - a); }

	// A pass's entries of busyTimes, one per thread, each written by its thread (NaN: a thread OpenMP did not
	// give the pass); only in the passes on the list while traceBusy counts down.
	struct BusyTrace {
		std::size_t at = 0;
		bool        on = false;
		BusyTrace()    = default;
		BusyTrace(std::vector<Real>& busyTimes, long traceBusy, bool fast, int threads)
		        : at(busyTimes.size())
		        , on(fast && traceBusy > 0)
		{
			if (on) busyTimes.resize(at + std::size_t(threads), NaN);
		}
		void record(std::vector<Real>& busyTimes, int thread, Real ns) const
		{
			if (on) busyTimes[at + std::size_t(thread)] = ns;
		}
	};

	// Bytes an array holds (by capacity), with those of the arrays it holds.
	template <class T> long capacityBytes(const std::vector<T>& v) { return long(v.capacity() * sizeof(T)); }
	template <class T> long capacityBytes(const std::vector<std::vector<T>>& v)
	{
		long bytes = long(v.capacity() * sizeof(std::vector<T>));
		for (const auto& inner : v)
			bytes += capacityBytes(inner);
		return bytes;
	}

	// sizeof of what an interaction and a body cost (PendularLoop.memory).
	boost::python::dict loopMemory();
} // namespace pendular
} // namespace yade
