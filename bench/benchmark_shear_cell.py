# Speed of the wet (13.6 nl) shear cell: YADE's built-in Law2_ScGeom_ViscElCapPhys_Basic
# (Willett_numeric, the baseline), our Law2 (willett_full) in YADE's InteractionLoop and in
# PendularLoop (with PendularIntegrator, with both engines' parallelBodies at 20000 instead of 1000, and with YADE's
# NewtonIntegrator instead of PendularIntegrator), same positions and
# time step, on one and on two OpenMP threads, interleaved in one
# run. A benchmark, not a test.
# Then, on two threads or more, repeated pairs of PendularLoop runs, one thread then two, in turn on one scene:
# the spread and median of the gain from the second thread (one pair is as noisy as the machine).
# Run:  build/yade-capillary -j2 -n -x bench/benchmark_shear_cell.py [config] [steps] [cache] [pairs]
#   config: ci (default) or validation_probe (the validation cell for a short run, about 15 000 flowing spheres; benchmark.py);
#   cache: file of the prepared cell, made if missing ('' or none: a temporary file, removed at exit); pairs: 10 by default, 0 for none.
# Each run is printed with the core-to-core round trip measured just before it (build/core_latency):
# a virtual machine may have a mode in which two threads gain far less (a round trip several times longer), and
# a ratio of thread counts holds only between runs of the same mode; and with the machine's parallel
# speed just before it (core_latency --parallel: 1 when two threads get two cores' worth of private
# work, 0.5 when each runs at half speed, which such a VM also does at times, at any round trip).
import atexit
import os
import shutil
import statistics
import sys
import tempfile

from yade import O

sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # bench/benchmark.py; yade does not put the script's folder on sys.path
import benchmark  # noqa: E402

config = sys.argv[1] if len(sys.argv) > 1 else "ci"
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
# One prepared cell for the comparison and the pairs: without a cache given, a temporary file (removed at exit),
# so that the pairs do not prepare the cell again (minutes for the validation cell).
cache = sys.argv[3] if len(sys.argv) > 3 and sys.argv[3] else None
if cache is None:
    scratch = tempfile.mkdtemp()
    atexit.register(shutil.rmtree, scratch, ignore_errors=True)
    cache = os.path.join(scratch, "cell.yade.gz")
pairs = int(sys.argv[4]) if len(sys.argv) > 4 else 10
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
if pairs > 0 and threads[-1] >= 2:
    # Classed by what was measured just before the two-thread run: the round trip (above slow_mode [ns]: the slow
    # mode of a virtual machine) and the parallel speed (below 0.9: a stretch without two cores' worth).
    slow_mode, full_speed = 250, 0.9
    runs = benchmark.thread_pairs(pairs, steps, config=config, cache=cache)
    print("(b) shear cell %s, ours with PendularLoop, %d pairs of %d steps on one thread then two, in turn on one scene:" % (config, pairs, steps))
    ratios = {"all": [], "below": [], "above": [], "fast": []}
    for k, pair in enumerate(runs, 1):
        one, two = pair[1], pair[2]
        ratio = two["particle_steps_per_s"] / one["particle_steps_per_s"]
        trip = two["round_trip_ns"]
        print("  pair %2d: %.3g -> %.3g particle-steps/s, %.2fx  (before the two-thread run: core round trip %s ns, parallel speed %s)"
              % (k, one["particle_steps_per_s"], two["particle_steps_per_s"], ratio, "%.0f" % trip if trip is not None else "-",
                 "%.2f" % two["parallel"] if two["parallel"] is not None else "-"))
        ratios["all"].append(ratio)
        if trip is not None:
            ratios["below" if trip < slow_mode else "above"].append(ratio)
            if trip < slow_mode and two["parallel"] is not None and two["parallel"] >= full_speed:
                ratios["fast"].append(ratio)
    for key, label in (("all", "all pairs"), ("below", "round trip below %d ns" % slow_mode),
                       ("fast", "and parallel speed %.1f or more" % full_speed), ("above", "round trip %d ns or more" % slow_mode)):
        r = sorted(ratios[key])
        if r:
            print("  speed-up from 2 threads, %-31s median %.2f (%.2f-%.2f), %d of %d pairs at 1.7 or more"
                  % (label, statistics.median(r), r[0], r[-1], sum(x >= 1.7 for x in r), len(r)))
    # Why one pair differs from the next: each thread's time in the pass, step by step.
    noise = benchmark.thread_noise(steps, config=config, cache=cache)
    print("(b) shear cell %s, PendularLoop's pass on the list, each thread's busy time per step, %d passes (PendularLoop.traceBusy):" % (config, noise[2]["passes"]))
    for nthreads in (1, 2):
        stats = noise[nthreads]
        for k, (p, lag) in enumerate(zip(stats["percentiles"], stats["lag1"])):
            print("  %d thread(s), thread %d: %.1f / %.1f / %.1f / %.1f us (10th / 50th / 90th / 99th percentile), correlation with the step before %.2f"
                  % (nthreads, k, p[0], p[1], p[2], p[3], lag))
    print("  2 threads: correlation of the two threads' times in a step %.2f; the slower thread exceeds the mean of the two by %.1f us per step"
          % (noise[2]["between"], noise[2]["join_us"]))
sys.exit(0)
