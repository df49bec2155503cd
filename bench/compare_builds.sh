#!/usr/bin/env bash
# Compares the fused loop's speed of two builds (for instance a change and the commit before it), for a
# change of the hot paths: bench/benchmark_fused.py under build A, then under build B, PAIRS times in turn
# (the machine's speed drifts within minutes, so each pair is taken close in time), then the ratio A/B of
# each figure pair by pair, its median and range. The figures: packing ns per bridge-step (lower is faster)
# and ci-cell particle-steps/s on one and two threads (higher is faster); the ratios are given as speed A /
# speed B, so > 1 means A is faster. Each build prepares its own ci cell once (BUILD/bench/ci_fused.yade.gz).
# Run:  bench/compare_builds.sh BUILD_A BUILD_B [PAIRS]   (for instance build ../before/build 5)
set -euo pipefail
A=$(realpath "$1"); B=$(realpath "$2"); PAIRS=${3:-5}
HERE=$(dirname "$(realpath "$0")")
LOG=$(mktemp -d)/compare
for build in "$A" "$B"; do mkdir -p "$build/bench"; done
for i in $(seq 1 "$PAIRS"); do
  for side in A B; do
    build=$([ $side = A ] && echo "$A" || echo "$B")
    line=$(OMP_NUM_THREADS=2 "$build/yade-capillary" -j2 -n -x "$HERE/benchmark_fused.py" "$build/bench/ci_fused.yade.gz" 2>&1 | grep '^FUSED ' | cut -c7-)
    echo "$side $line" | tee -a "$LOG"
  done
done
/usr/bin/python3 - "$LOG" <<'PY'
import json, statistics, sys
rows = {"A": [], "B": []}
for line in open(sys.argv[1]):
    side, data = line.split(" ", 1)
    rows[side].append(json.loads(data))
print("speed A / speed B, pair by pair (> 1: A faster)")
for key in rows["A"][0]:
    lower_is_faster = key.endswith("_ns")
    r = [(b[key] / a[key]) if lower_is_faster else (a[key] / b[key]) for a, b in zip(rows["A"], rows["B"])]
    print("  %-22s median %.3f  range %.3f-%.3f  (%s)" % (key, statistics.median(r), min(r), max(r), " ".join("%.3f" % x for x in r)))
PY
