# Speed of the wet (13.6 nl) shear cell: YADE's built-in Law2_ScGeom_ViscElCapPhys_Basic
# (Willett_numeric, the baseline), our Law2 (willett_full) in YADE's InteractionLoop and in
# PendularLoop, same positions and time step, in one run; threads as given by -j.
# A benchmark, not a test.
# Run:  build/yade-capillary -j1 -n -x scripts/benchmark_shear_cell.py [config] [steps] [cache]
#   config: ci (default) or validation_probe (the validation cell, about 15 000 flowing spheres);
#   cache: file of the prepared cell, made if missing, so that runs with -j1 and -j2 share it.
import sys

from yade import O

from yade_capillary import benchmark

config = sys.argv[1] if len(sys.argv) > 1 else "ci"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
cache = sys.argv[3] if len(sys.argv) > 3 else None
builtin, standard, fused = benchmark.shear_cell(steps, config=config, cache=cache)
print("(b) shear cell %s, wet13.6nl, %d steps, %d thread(s), particle-steps/s (ratio to the built-in law):" % (config, steps, O.numThreads))
for name, r in (("YADE built-in law", builtin), ("ours, Law2 in InteractionLoop", standard), ("ours, PendularLoop", fused)):
    print("  %-32s %10.3g  (%.2f)" % (name, r["particle_steps_per_s"], r["particle_steps_per_s"] / builtin["particle_steps_per_s"]))
sys.exit(0)
