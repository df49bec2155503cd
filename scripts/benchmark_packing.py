# Speed: one wet packing (16^3 touching spheres, ~11 500 bridges) with YADE's built-in capillary
# law and with ours, same model, in one run. Prints ns per bridge-step of the interaction loop
# and the ratio. A benchmark, not a test: timings on shared machines are noisy.
# Run:  build/yade-capillary -j1 -n -x scripts/benchmark_packing.py [n] [steps]
import sys

from yade_capillary import benchmark

n = int(sys.argv[1]) if len(sys.argv) > 1 else 16
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
builtin, floor, ours = benchmark.run(n=n, steps=steps)
print("%-62s %14s %12s %16s" % ("law", "interactions", "ns/bridge-step", "particle-steps/s"))
for r in (builtin, floor, ours):
    print("%-62s %14d %12.1f %16.3g" % (r["law"], r["interactions"], r["ns_per_bridge_step"], r["particle_steps_per_s"]))
print("ratio ours / built-in (interaction loop per bridge-step): %.3f" % (ours["ns_per_bridge_step"] / builtin["ns_per_bridge_step"]))
print("above the zero-force floor: ours %.1f ns, built-in %.1f ns" % (ours["ns_per_bridge_step"] - floor["ns_per_bridge_step"],
                                                                    builtin["ns_per_bridge_step"] - floor["ns_per_bridge_step"]))
sys.exit(0)
