# Speed of the fused loop alone, for comparing two builds (bench/compare_builds.sh runs it under each in
# turn): PendularLoop on the 16^3 wet packing (frictionless and with friction 0.5 rad; ns per bridge-step of
# the interaction loop, fastest of `repeats`) and on the prepared ci shear cell (particle-steps/s on one and
# on two threads, fastest of `repeats`). Prints one JSON line: a benchmark, not a test.
# Run:  build/yade-capillary -j2 -n -x bench/benchmark_fused.py CELL_CACHE [repeats] [cell_steps]
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # bench/benchmark.py; yade does not put the script's folder on sys.path
import benchmark  # noqa: E402

cache = sys.argv[1]
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 2
cell_steps = int(sys.argv[3]) if len(sys.argv) > 3 else 2000
out = {}
for friction, key in ((0.0, "packing_ns"), (0.5, "packing_friction_ns")):
    out[key] = min(benchmark.ours_run("willett_full", "fused", friction, 16, 1000, 1, 0.005)["ns_per_bridge_step"] for _ in range(repeats))
cell = benchmark._Cell("ci", "wet13.6nl", cache)
flowing = len(cell.info["flowing"])
for threads in (1, 2):
    rates = []
    for _ in range(repeats):
        cell.build(cell.our_material(), "fused", threads)
        rates.append(flowing * cell_steps / benchmark.timed_steps(cell_steps))
    out["ci_%dthread" % threads] = max(rates)
print("FUSED " + json.dumps(out))
