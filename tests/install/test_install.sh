#!/usr/bin/env bash
# ctest `install`: the Debian package of this build works with plain /usr/bin/yade and leaves no
# trace. Builds the .deb (cpack), installs it with apt, runs two_spheres.py with Debian's yade from
# an empty temporary folder (no launcher, no build directory on any path), purges the package and
# compares the listings of YADE's plugin folder and of dist-packages with those taken before.
# Exit 77 (skipped): not root, or yade-capillary already installed (a user's install is never
# removed), or no package rules in the build (no dpkg-installed yade).
# Usage: test_install.sh BUILD_DIR. BUILD_LOCK, if set, is a lock file the build and cpack wait for.
set -euo pipefail
BUILD_DIR=$(cd "$1" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
PKG=yade-capillary
say() { printf '[install test] %s\n' "$*"; }
skip() { say "skipped: $*"; exit 77; }

[[ $(id -u) -eq 0 ]] || skip "needs root (apt installs into system folders)"
status=$(dpkg-query -W -f='${db:Status-Status}' "$PKG" 2>/dev/null || true)
[[ -z $status || $status == not-installed ]] || skip "$PKG is already on this machine ($status); it is left alone"
[[ -f "$BUILD_DIR/CPackConfig.cmake" ]] || skip "no package rules in $BUILD_DIR (no dpkg-installed yade)"
plugin_dir=$(sed -n 's/^YADE_LIBDIR:PATH=//p' "$BUILD_DIR/CMakeCache.txt")
python_dir=/usr/$(sed -n 's/^YADE_CAPILLARY_PYTHON_INSTALL_DIR:STRING=//p' "$BUILD_DIR/CMakeCache.txt")
[[ -d $plugin_dir && -d $python_dir ]] || { say "plugin folder '$plugin_dir' or Python folder '$python_dir' missing"; exit 1; }

tmp=$(mktemp -d)
installed=0
cleanup() {
  if ((installed)); then say "purging $PKG after a failure"; DEBIAN_FRONTEND=noninteractive apt-get purge -y -q "$PKG" >/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
locked() { if [[ -n ${BUILD_LOCK:-} ]]; then flock "$BUILD_LOCK" "$@"; else "$@"; fi; }

# 1. The package, from this build (a no-op build when it is current).
locked cmake --build "$BUILD_DIR" -j "$(nproc)" >/dev/null
locked cpack --config "$BUILD_DIR/CPackConfig.cmake" -B "$tmp/deb" >"$tmp/cpack.log" || { cat "$tmp/cpack.log"; exit 1; }
deb=$(echo "$tmp"/deb/"$PKG"_*.deb)
[[ -f $deb ]] || { say "cpack made no $PKG .deb"; cat "$tmp/cpack.log"; exit 1; }
say "package $(basename "$deb"): Depends: $(dpkg-deb -f "$deb" Depends)"
yade_version=$(dpkg-query -W -f='${Version}' yade)
dpkg-deb -f "$deb" Depends | grep -qF "yade (= $yade_version)" || { say "Depends does not name yade (= $yade_version)"; exit 1; }

# 2. No file of the package may exist yet (dpkg would overwrite a file no package owns).
files=$(dpkg-deb -c "$deb" | awk '$1 !~ /^d/ {print substr($6, 2)}')
for f in $files; do [[ ! -e $f ]] || { say "$f exists already: it would be overwritten"; exit 1; }; done
say "$(echo "$files" | wc -l) files, none present before:"; echo "$files" | sed 's/^/    /'

# 3. Install next to Debian's yade; apt must not pull anything else in (the purge would leave it).
listing() { find "$plugin_dir" "$python_dir" -printf '%p %y %s\n' | LC_ALL=C sort; }
listing >"$tmp/before"
extra=$(apt-get install -s --no-install-recommends "$deb" 2>/dev/null | awk '$1 == "Inst" && $2 != "'"$PKG"'" {print $2}')
[[ -z $extra ]] || skip "installing $PKG would also install: $extra"
installed=1
DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends -o DPkg::Lock::Timeout=120 "$deb" >"$tmp/apt.log" 2>&1 ||
  { cat "$tmp/apt.log"; exit 1; }
say "installed; byte code from postinst: $(ls "$python_dir/yade_capillary/__pycache__" 2>/dev/null | wc -l) files"

# 4. Plain yade, from an empty folder, with nothing of the build on any path. No byte code is
#    written by this run (YADE's own modules would otherwise get a __pycache__ as root).
mkdir "$tmp/run" && cp "$HERE/two_spheres.py" "$tmp/run/"
set +e
(cd "$tmp/run" && env -u PYTHONPATH -u YADE_PREFIX PYTHONDONTWRITEBYTECODE=1 /usr/bin/yade -j1 -n -x two_spheres.py "$plugin_dir" "$python_dir") >"$tmp/yade.log" 2>&1
rc=$?
set -e
if ((rc == 0)); then grep -E '^(ok|FAIL) ' "$tmp/yade.log"; else cat "$tmp/yade.log"; fi

# 5. Purge, and the machine is as before.
DEBIAN_FRONTEND=noninteractive apt-get purge -y -q -o DPkg::Lock::Timeout=120 "$PKG" >"$tmp/apt.log" 2>&1 || { cat "$tmp/apt.log"; exit 1; }
installed=0
listing >"$tmp/after"
if ! diff "$tmp/before" "$tmp/after" >"$tmp/diff"; then say "folders differ after the purge:"; cat "$tmp/diff"; exit 1; fi
say "purged; $plugin_dir and $python_dir as before ($(wc -l <"$tmp/before") entries)"
((rc == 0)) || { say "two_spheres.py failed (exit $rc)"; exit 1; }
say "passed"
