// PendularLoop's force accumulation, its once-per-step parts (see LoopForces.hpp): the hand-over of the
// border bodies' forces during a pass and the flush into YADE's force container after it.
#include "LoopForces.hpp"
#include "LoopInstrumentation.hpp"

#include <core/Scene.hpp>

namespace yade {
namespace pendular {
	void ForceAccumulator::handOverBorders(int thread, const SummedArrays& summed, const std::vector<std::vector<std::vector<Body::id_t>>>& borders)
	{
		for (size_t k = 0; k < force.size(); ++k) {
			if (int(k) == thread) continue;
			for (const Body::id_t id : borders[k][size_t(thread)]) {
				Vector3r &f = force[k][id], &t = torque[k][id];
				if (f != Vector3r::Zero()) summed.forces[id] += f;
				if (t != Vector3r::Zero()) summed.torques[id] += t;
				f = t = Vector3r::Zero();
			}
		}
	}

	void ForceAccumulator::flush(ForceContainer& forces, long n, int threads, long parallelBodies, bool parted, bool directDone, bool bordersDone,
	                             const std::vector<long>& bodyParts, const std::vector<std::vector<std::vector<Body::id_t>>>& borders)
	{
		// Into the force container's summed arrays, not through addForce: addForce writes the container's
		// shared flag and its per-thread maximum ids at every call, and two threads doing so contend for those
		// cache lines. sync() first adds what the dispatched functors of this pass added through addForce (as
		// the integrator's sync would). directDone: each thread of the pass added the forces of its part of the
		// bodies straight into the summed arrays (see ThreadSink), which cover every body (the pass's addMaxId
		// and sync).
		if (n == 0) return;
		forces.sync();
		const long arrays = long(force.size());
		// One thread that added every body's forces straight into the summed arrays: nothing in its arrays;
		// several whose pass handed the borders over (bordersDone): nothing left in theirs.
		if (directDone && (arrays == 1 || bordersDone)) {
			team    = int(arrays);
			pending = false;
			return;
		}
		const SummedArrays summed = summedArrays(forces, n);
		// Through the calls only if the summed arrays are not at hand (a call into libyade per body and array,
		// which the compiler cannot inline).
		const auto add = [&forces, &summed](long id, const Vector3r& f, const Vector3r& t) {
			if (f != Vector3r::Zero()) {
				if (summed.forces) summed.forces[id] += f;
				else
					forces.addForceUnsynced(Body::id_t(id), f);
			}
			if (t != Vector3r::Zero()) {
				if (summed.torques) summed.torques[id] += t;
				else
					forces.addTorqueUnsynced(Body::id_t(id), t);
			}
		};
		// Each thread the bodies of its part (bodyParts), whose entries of every thread's arrays it zeroes once
		// read: the arrays are zero for the next pass, and what a thread wrote only for its own bodies stays in
		// its cache. After a pass by parts (parted), array k holds forces only on the bodies of part k and of its
		// borders, or only on its borders if that pass added part k's straight into the summed arrays (direct):
		// the other entries are exact zeros, and are neither read nor written (reading them moved every line of
		// every array from the core that zeroed it to the other one at every step). In one thread the sum per
		// body is that of InteractionLoop's: the thread's sum.
#ifdef YADE_OPENMP
#pragma omp parallel num_threads(threads) if (n >= parallelBodies)
#endif
		{
			const int  thread  = threadNumber();
			const auto part    = partOf(bodyParts, n, thread, teamSize());
			const bool byParts = parted && teamSize() == arrays;
			if (thread == 0) team = teamSize();
			if (arrays == 1) // one thread's arrays: no other to look into
				for (long id = part.first; id < part.second; ++id) {
					const Vector3r f = force[0][id], t = torque[0][id];
					force[0][id] = torque[0][id] = Vector3r::Zero();
					add(id, f, t);
				}
			else {
				// Per array, the next of its border bodies in this part.
				std::vector<const Body::id_t*> next(size_t(arrays), nullptr), last(size_t(arrays), nullptr);
				if (byParts)
					for (long k = 0; k < arrays; ++k)
						if (k != thread) {
							const auto& ids = borders[size_t(k)][size_t(thread)];
							next[size_t(k)] = ids.data();
							last[size_t(k)] = ids.data() + ids.size();
						}
				for (long id = part.first; id < part.second; ++id) {
					Vector3r f = Vector3r::Zero(), t = Vector3r::Zero();
					for (long k = 0; k < arrays; ++k) {
						if (byParts && k != thread) {
							if (next[size_t(k)] == last[size_t(k)] || *next[size_t(k)] != id) continue;
							++next[size_t(k)];
						}
						f += force[k][id];
						t += torque[k][id];
						force[k][id] = torque[k][id] = Vector3r::Zero();
					}
					add(id, f, t);
				}
			}
		}
		pending = false;
	}

	long ForceAccumulator::heldBytes() const { return capacityBytes(force) + capacityBytes(torque) + capacityBytes(direct); }
} // namespace pendular
} // namespace yade
