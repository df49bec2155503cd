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
#   ./run.sh install    (as root) set up, build, make the Debian package yade-capillary with cpack
#                       (build/deb/) and install it with apt next to Debian's yade: the plugin into
#                       YADE's plugin folder, the Python package into dist-packages, so that plain
#                       `yade` loads them; the package depends on the exact yade version built against
#   ./run.sh uninstall  (as root) remove the package again (apt-get purge yade-capillary)
# Environment: BUILD_DIR (default build/); BUILD_LOCK, a lock file that builds and packaging wait
# for (flock) when several people share one build directory.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")" && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build}
cmd=${1:-}
case "$cmd" in
  setup|validate|test|bench|install|uninstall) ;;
  *) echo "usage: $0 {validate|test|bench|setup|install|uninstall}"; exit 2 ;;
esac
if [[ $cmd == install || $cmd == uninstall ]] && [[ $(id -u) -ne 0 ]]; then
  echo "$0 $cmd changes system folders through apt: run it as root (sudo $0 $cmd)"; exit 1
fi
if [[ $cmd == uninstall ]]; then
  DEBIAN_FRONTEND=noninteractive apt-get purge -y yade-capillary; exit 0
fi
locked() { if [[ -n ${BUILD_LOCK:-} ]]; then flock "$BUILD_LOCK" "$@"; else "$@"; fi; }
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
    export BUILD_DIR  # bench/benchmark.py runs $BUILD_DIR/core_latency
    rm -rf "$BUILD_DIR/bench" && mkdir -p "$BUILD_DIR/bench"  # cells prepared by this build
    "$Y" -j1 -n -x bench/benchmark_packing.py
    for config in ci validation_probe; do "$Y" -j2 -n -x bench/benchmark_shear_cell.py $config 1000 "$BUILD_DIR/bench/$config.yade.gz"; done
    "$Y" -j2 -n -x bench/benchmark_gladkyy_probe.py ;;
  install)
    [[ -f "$BUILD_DIR/CPackConfig.cmake" ]] || { echo "no package rules in $BUILD_DIR: Debian's yade is not installed with dpkg"; exit 1; }
    rm -rf "$BUILD_DIR/deb"  # one .deb only, of this build
    locked cpack --config "$BUILD_DIR/CPackConfig.cmake" -B "$BUILD_DIR/deb"
    # --reinstall: a package of changed, uncommitted sources has the version of the installed one.
    cd "$BUILD_DIR/deb" && DEBIAN_FRONTEND=noninteractive apt-get install -y --reinstall ./yade-capillary_*.deb ;;
  setup) ;;
esac
