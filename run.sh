#!/usr/bin/env bash
# yade-capillary entry point. Sets up (installs, fetches headers, builds) when needed, then:
#   ./run.sh validate   pull-off validations: two spheres (Gladkyy 2014, Table 1; results/two_sphere/),
#                       sphere-wall and viscous pull-off (Elskamp 2018 Fig. 5a, 5b; results/sphere_wall/,
#                       results/viscous_pull_off/), and a short liquid migration in a drum
#                       (film mode; results/liquid_migration_quick/): summary tables, CSV, PNG and VTK
#   ./run.sh test       all tests (kernel unit tests, Python tests, in-YADE tests); further arguments
#                       go to ctest, e.g. ./run.sh test -L fast (all but the slow shear-cell regression)
#   ./run.sh bench      speed benchmarks against YADE's built-in capillary law (about 20 min): the
#                       interaction pass and bytes per bridge (packing), the ci and validation
#                       shear cells on one and two threads, a Gladkyy-size cell probe on two
#   ./run.sh setup      only set up and build
set -euo pipefail
ROOT=$(cd "$(dirname "$0")" && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build}
cmd=${1:-}
case "$cmd" in
  setup|validate|test|bench) ;;
  *) echo "usage: $0 {validate|test|bench|setup}"; exit 2 ;;
esac
BUILD_DIR=$BUILD_DIR "$ROOT/tools/setup.sh"
cd "$ROOT"
case "$cmd" in
  validate)
    "$BUILD_DIR/yade-capillary" -j1 -n -x scripts/two_sphere.py results/two_sphere
    "$BUILD_DIR/yade-capillary" -j1 -n -x scripts/sphere_wall.py results/sphere_wall
    "$BUILD_DIR/yade-capillary" -j1 -n -x scripts/viscous_pull_off.py results/viscous_pull_off
    "$BUILD_DIR/yade-capillary" -j1 -n -x scripts/liquid_migration.py results/liquid_migration_quick --quick ;;
  test) shift; ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" "$@" ;;
  bench)
    Y="$BUILD_DIR/yade-capillary"
    rm -rf "$BUILD_DIR/bench" && mkdir -p "$BUILD_DIR/bench"  # cells prepared by this build
    "$Y" -j1 -n -x scripts/benchmark_packing.py
    for config in ci validation_probe; do "$Y" -j2 -n -x scripts/benchmark_shear_cell.py $config 1000 "$BUILD_DIR/bench/$config.yade.gz"; done
    "$Y" -j2 -n -x scripts/benchmark_gladkyy_probe.py ;;
  setup) ;;
esac
