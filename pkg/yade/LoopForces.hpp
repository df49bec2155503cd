// PendularLoop's force accumulation: where the forces and torques of a pass are summed and how they
// reach YADE's force container. A thread of the pass adds those of the bodies of its part (DirectPart)
// straight into the container's summed arrays (no other thread writes them), those of other bodies
// into arrays of its own indexed by body id; the owner of those bodies adds them into the container
// (handOverBorders during the pass, or flush after it) and zeroes them, so that the arrays are zero
// between steps (pending: a step ended between a pass and its flush). On one thread the sums are those
// of InteractionLoop, in the same order: the summed entries start from zero (ForceResetter, or the
// reset that PendularForceResetter hands to the gathering, ForceReset) as InteractionLoop's per-thread
// ones do, unless an engine between them added forces. Owns the per-thread arrays, the direct parts,
// the reset handed over and the team of the last flush. What adds one interaction's forces into them
// (ThreadSink) is defined where the law is called, in PendularLoop_Pass.cpp (see there); the hand-overs, once
// per step, are out of line.
#pragma once

#include "Passes.hpp"

#include <vector>

namespace yade {
class Scene;
namespace pendular {
	// What one thread of the pass adds straight into the force container's summed arrays: the forces and
	// torques of the bodies [first, last), its part (see partOf).
	struct DirectPart {
		Vector3r *forces = nullptr, *torques = nullptr;
		long      first = 0, last = 0;
		bool      has(Body::id_t id) const { return id >= first && id < last; }
	};

	// The force container's reset of a step (iter of scene), to be done by the gathering: each thread zeroes
	// its part of the bodies, then the entries of no body (up to size); summed: the container's summed arrays.
	struct ForceReset {
		const Scene*  scene = nullptr;
		long          iter  = -1;
		SummedArrays summed;
		long          size = 0;
		void          zero(long first, long last) const
		{
			if (!summed.forces) return;
			zeroEntries(summed.forces, first, last);
			zeroEntries(summed.torques, first, last);
		}
	};

	class ForceAccumulator {
	public:
		// Per OpenMP thread, per body id; zero between steps (the flush zeroes what it read, see pending).
		std::vector<std::vector<Vector3r>> force, torque;
		std::vector<DirectPart>            direct; // per OpenMP thread of the pass
		// A pass has added to the arrays and no flush has read them since (a step that ended in between).
		bool pending = false;
		// The threads of the last flush (0: none since the loop started; see PendularLoop::flushTeam).
		int team = 0;
		// The reset that PendularForceResetter handed to this step's gathering (scene nullptr: none).
		ForceReset reset;

		// Arrays for a pass on `threads` threads (their per-body entries follow in fitBodies).
		void useThreads(int threads)
		{
			force.resize(std::size_t(threads));
			torque.resize(std::size_t(threads));
		}
		// Each thread's arrays for n bodies, zero (a step that ended before its flush left values).
		void fitBodies(std::size_t n)
		{
			for (auto& f : force)
				f.resize(n, Vector3r::Zero());
			for (auto& t : torque)
				t.resize(n, Vector3r::Zero());
			if (pending)
				for (std::size_t k = 0; k < force.size(); ++k) {
					std::fill(force[k].begin(), force[k].end(), Vector3r::Zero());
					std::fill(torque[k].begin(), torque[k].end(), Vector3r::Zero());
				}
			pending = false;
		}
		// The reset handed over for step `iter` of `scene` (none if it was for another), and no reset after it.
		ForceReset takeReset(const Scene* scene, long iter)
		{
			const ForceReset taken = reset.scene == scene && reset.iter == iter ? reset : ForceReset {};
			reset                  = ForceReset {};
			return taken;
		}
		// Prefetches (for writing) where `thread` adds the force on body id.
		__attribute__((always_inline)) void prefetch(int thread, Body::id_t id) const
		{
			const DirectPart& part = direct[std::size_t(thread)];
			__builtin_prefetch(part.has(id) ? &part.forces[id] : &force[thread][id], 1);
		}
		// Thread `thread` of a pass by parts adds into the container's summed arrays what the other threads'
		// arrays hold for the bodies of its part (their borders with it, see WorkPartition), in the order of the
		// arrays, and zeroes those entries.
		void handOverBorders(int thread, const SummedArrays& summed, const std::vector<std::vector<std::vector<Body::id_t>>>& borders);
		// After the pass: the arrays' forces on the n bodies into the force container, each of `threads`
		// threads those of its part (bodyParts) if n >= parallelBodies. parted: the pass computed the parts of
		// the list, each on its thread; directDone: each thread added the forces of its part of the bodies into
		// the container itself; bordersDone: and handed the borders over in the pass's parallel region.
		void flush(ForceContainer& forces, long n, int threads, long parallelBodies, bool parted, bool directDone, bool bordersDone,
		           const std::vector<long>& bodyParts, const std::vector<std::vector<std::vector<Body::id_t>>>& borders);
		long heldBytes() const;
	};
} // namespace pendular
} // namespace yade
