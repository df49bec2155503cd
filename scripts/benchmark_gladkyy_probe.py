# Speed probe of a Gladkyy-size wet shear cell (about 170 000 flowing spheres, R = 2.381 mm, the
# validation cell enlarged 2.2 times): 1000 timed steps with PendularLoop (with its defaults, without skipFar
# and without its records, in interleaved chunks), and the projected wall
# time of Gladkyy's 5 s of rotation at the configuration's time step (tc/20). By default the probe
# starts from the committed final state of the wet (13.6 nl, willett_full) run at his scale, a settled
# packing sheared for 5 s with its bridges; `lattice` builds the cell touching instead (spheres still
# collapsing, so the collider runs more often than in a run). A benchmark, not a test. Run with the threads
# to project for, e.g.
#   build/yade-capillary -j2 -n -x scripts/benchmark_gladkyy_probe.py [steps [STATE.npz | lattice]]
import os
import sys

from yade_capillary import benchmark

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
start = sys.argv[2] if len(sys.argv) > 2 else os.path.join("data", "shear_cell_runs", "gladkyy_size", "wet13.6nl", "state.npz")
if start != "lattice" and not os.path.exists(start):
    raise ValueError("STATE: %r does not exist (a state.npz of shearcell.save_state, or 'lattice')" % start)
r = benchmark.gladkyy_probe(steps, state=None if start == "lattice" else start)
print("(d) Gladkyy-size cell from the %s: %d spheres (%d flowing), %d real of %d interactions, %d thread(s)"
      % (r["start"], r["spheres"], r["flowing"], r["real_interactions"], r["interactions"], r["threads"]))
print("    %.3f s per step, %.3g particle-steps/s; %g s of rotation at dt = %.3g s: projected %.1f h"
      % (r["s_per_step"], r["particle_steps_per_s"], r["run_s"], r["dt"], r["projected_h"]))
if "s_per_step_without_records" in r:
    print("    without PendularLoop's records (keepRecords=False, chunks interleaved): %.3f s per step; with/without %.2f"
          % (r["s_per_step_without_records"], r["s_per_step"] / r["s_per_step_without_records"]))
    print("    without the list of entries to visit (skipFar=False): %.3f s per step; with/without %.2f"
          % (r["s_per_step_without_skip"], r["s_per_step"] / r["s_per_step_without_skip"]))
    print("    PendularLoop, last step: %s; sorting the container %.2f ms per step" % (", ".join("%s %d" % kv for kv in r["counts"].items()), r["sort_ms_per_step"]))
print("    the collider ran in %.3f of the steps" % r["collider_runs_per_step"])
total = sum(r["engines_ns_per_step"].values())
for name, ns in sorted(r["engines_ns_per_step"].items(), key=lambda kv: -kv[1]):
    print("    %-40s %8.1f ms per step (%4.1f %%)" % (name, ns / 1e6, 100 * ns / total))
sys.exit(0)
