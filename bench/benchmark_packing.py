# Speed: one wet packing (16^3 touching spheres, ~11 500 bridges) with YADE's built-in capillary
# law (the baseline), its zero-force variant, our Law2 in YADE's InteractionLoop and our
# PendularLoop (frictionless, with friction, and frictionless with a viscous liquid, eta = 1 mPa s, with
# and without the dynamic rupture rule, with the liquid on the particles, liquid="film", and without its records), same model, in one run;
# then PendularLoop with records and sorting, with records without sorting, and with neither on a
# 40^3 packing. Prints ns per
# bridge-step of the interaction loop, ratios to the baseline, PendularLoop's phases and the
# bytes per bridge. A benchmark, not a test: timings on shared machines are noisy.
# Run:  build/yade-capillary -j1 -n -x bench/benchmark_packing.py [n] [steps]
import os
import sys

from yade import O

sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # bench/benchmark.py; yade does not put the script's folder on sys.path
import benchmark  # noqa: E402

n = int(sys.argv[1]) if len(sys.argv) > 1 else 16
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
results = benchmark.packing(n=n, steps=steps)
base = results[0]
print("(a) interaction pass, %d^3 wet packing, %d steps, %d thread(s)" % (n, steps, O.numThreads))
print("%-72s %12s %14s %10s %16s" % ("loop and law", "interactions", "ns/bridge-step", "vs built-in", "particle-steps/s"))
for r in results:
    print("%-72s %12d %14.1f %10.3f %16.3g" % (r["law"], r["interactions"], r["ns_per_bridge_step"], r["ns_per_bridge_step"] / base["ns_per_bridge_step"],
                                            r["particle_steps_per_s"]))
for r in results:
    if "pass" in r:
        print("  %s: gather %.1f + pass %.1f + forces %.1f ns per bridge-step" % (r["law"], r["gather"], r["pass"], r["flush"]))
big = benchmark.records_effect()
print("PendularLoop's records and sorting on a packing too large for the caches (40^3 spheres, %d bridges, 200 steps):" % big[0]["interactions"])
for r in big:
    print("  %-85s %8.1f ns/bridge-step (pass %.1f) %10.3g particle-steps/s" % (r["law"], r["ns_per_bridge_step"], r["pass"], r["particle_steps_per_s"]))
print("  records and sorting / records without sorting / neither: 1 / %.2f / %.2f"
      % (big[1]["ns_per_bridge_step"] / big[0]["ns_per_bridge_step"], big[2]["ns_per_bridge_step"] / big[0]["ns_per_bridge_step"]))
mem = benchmark.memory()
theirs, objects = mem["ScGeom"] + mem["ViscElCapPhys"], mem["ScGeom"] + mem["PendularPhys"]
fused = results[3]  # PendularLoop, frictionless, at the end of its run
real, recorded = fused["interactions"], fused["recorded"]
ours = (recorded * (mem["slot"] + mem["record"]) + fused["with_objects"] * objects + fused["invariants"] * mem["invariants"]
        + (real - recorded) * (mem["slot"] + objects)) / real
print("(c) bytes per bridge (sizeof; plus the Interaction, %d B, the same for both laws, and the shared_ptr control blocks of the objects):"
      % mem["Interaction"])
print("  built-in: ScGeom %d + ViscElCapPhys %d = %d B" % (mem["ScGeom"], mem["ViscElCapPhys"], theirs))
print("  ours, PendularLoop at the end of its run: %d real interactions, %d recorded (slot %d + record %d B; %d of them with their own ScGeom %d + "
      "PendularPhys %d B), %d sets of invariants (%d B each); %.0f B per bridge, ratio %.2f" %
      (real, recorded, mem["slot"], mem["record"], fused["with_objects"], mem["ScGeom"], mem["PendularPhys"], fused["invariants"], mem["invariants"],
       ours, ours / theirs))
print("  ours, a bridge with objects (not recorded, or read by Python): %d B, ratio %.2f" % (mem["slot"] + objects, (mem["slot"] + objects) / theirs))
print("  PendularLoop per body: gathered data (two steps) %d + %d B, forces %d B per thread" % (mem["particle"], mem["epoch"], mem["forces"]))
sys.exit(0)
