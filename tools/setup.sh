#!/usr/bin/env bash
# Set up yade-capillary on Debian bookworm: install what is missing, obtain YADE headers,
# configure and build. Idempotent: a second run only rebuilds what changed.
#
# Environment:
#   YADE_SOURCE  a YADE source tarball (.tar.bz2/.tar.gz) or an unpacked YADE source tree to take
#                the headers from instead of Debian's source package.
#   BUILD_DIR    build directory (default: <repo>/build)
#   JOBS         parallel compile jobs (default: number of cores)
#   BUILD_LOCK   a lock file: the build waits for it (flock), so that builds of several people
#                sharing one build directory never overlap
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-$ROOT/build}
JOBS=${JOBS:-$(nproc)}
say() { printf '[setup] %s\n' "$*"; }

# --- 1. Debian packages --------------------------------------------------------------------
PKGS=(yade cmake g++ make libboost-all-dev libeigen3-dev python3-dev python3-numpy libopenmpi-dev
      libgl-dev libglu1-mesa-dev libcgal-dev libgmp-dev libmpfr-dev libgtest-dev libbenchmark-dev
      pybind11-dev python3-pytest python3-scipy python3-matplotlib python3-threadpoolctl binutils bzip2)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -ne 0 ]]; then
    say "missing Debian packages: ${missing[*]} (run this script as root once, or install them)"; exit 1
  fi
  say "installing: ${missing[*]}"
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# --- 2. YADE headers -----------------------------------------------------------------------
"$ROOT/tools/fetch-yade-headers.sh" "$BUILD_DIR/yade-headers"

# --- 3. configure and build ----------------------------------------------------------------
if [[ ! -f "$BUILD_DIR/CMakeCache.txt" ]]; then
  say "configuring in $BUILD_DIR"
  cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DYADE_HEADERS="$BUILD_DIR/yade-headers" >/dev/null
fi
say "building (${JOBS} jobs)"
if [[ -n ${BUILD_LOCK:-} ]]; then flock "$BUILD_LOCK" cmake --build "$BUILD_DIR" -j "$JOBS"
else cmake --build "$BUILD_DIR" -j "$JOBS"; fi
say "ready: $BUILD_DIR/yade-capillary"
