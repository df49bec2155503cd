# Speed of the wet (13.6 nl) shear cell: YADE's built-in Law2_ScGeom_ViscElCapPhys_Basic
# (Willett_numeric, the baseline), our Law2 (willett_full) in YADE's InteractionLoop and in
# PendularLoop (with PendularIntegrator, with both engines' parallelBodies at 20000 instead of 1000, and with YADE's
# NewtonIntegrator instead of PendularIntegrator), same positions and
# time step, on one and on two OpenMP threads, interleaved in one
# run. A benchmark, not a test.
# Run:  build/yade-capillary -j2 -n -x scripts/benchmark_shear_cell.py [config] [steps] [cache]
#   config: ci (default) or validation_probe (the validation cell, about 15 000 flowing spheres);
#   cache: file of the prepared cell, made if missing.
# Each run is printed with the core-to-core round trip measured just before it (build/core_latency):
# this VM has a mode in which two threads gain far less (round trip 300-420 ns instead of 55-110), and
# a ratio of thread counts holds only between runs of the same mode; and with the machine's parallel
# speed just before it (core_latency --parallel: 1 when two threads get two cores' worth of private
# work, 0.5 when each runs at half speed, which this VM also does at times, at any round trip).
import sys

from yade import O

from yade_capillary import benchmark

config = sys.argv[1] if len(sys.argv) > 1 else "ci"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
cache = sys.argv[3] if len(sys.argv) > 3 else None
threads = tuple(range(1, O.numThreads + 1))
NAMES = ("YADE built-in law", "ours, Law2 in InteractionLoop", "ours, PendularLoop", "ours, parallelBodies = 20000", "ours, NewtonIntegrator")  # the order of benchmark.shear_cell's results
results = benchmark.shear_cell(steps, config=config, cache=cache, threads=threads)
print("(b) shear cell %s, wet13.6nl, %d steps, particle-steps/s (ratio to the built-in law on as many threads):" % (config, steps))
for t in threads:
    base = results[t][0]["particle_steps_per_s"]
    for name, r in zip(NAMES, results[t]):
        trip = "" if r["round_trip_ns"] is None else "  core round trip %.0f ns, parallel speed %.2f" % (r["round_trip_ns"], r["parallel"])
        print("  %d thread(s)  %-32s %10.3g  (%.2f)%s" % (t, name, r["particle_steps_per_s"], r["particle_steps_per_s"] / base, trip))
print("  where the time goes, ours with PendularLoop, ns per step (engines; PendularLoop's phases indented):")
print("    %-40s %s" % ("", "  ".join("%10s" % ("%d thread(s)" % t) for t in threads)))
for key in results[threads[0]][2]["phases"]:
    print("    %-40s %s" % (key, "  ".join("%10.0f" % results[t][2]["phases"][key] for t in threads)))
for k, name in enumerate(NAMES):
    print("  speed-up from %d threads, %-32s %.2f" % (threads[-1], name, results[threads[-1]][k]["particle_steps_per_s"] / results[1][k]["particle_steps_per_s"]))
sys.exit(0)
