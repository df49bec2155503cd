#!/usr/bin/env bash
# Build an overlay YADE prefix (symlinks to every file of the system yade-double folder except an
# installed copy of our plugin, plus this build's plugin) and the launcher build/yade-capillary,
# which runs the system yade with that prefix and build/python (the package yade_capillary as the
# build assembles it) on PYTHONPATH.
set -euo pipefail
build=$1; src=$2; libdir=$3; yade=$4
overlay="$build/prefix/lib/x86_64-linux-gnu/yade-double"
rm -rf "$build/prefix"; mkdir -p "$overlay"
# An installed yade-capillary package puts its own libyadecapillary.so into the system folder: it is
# left out, so the launcher loads this build's plugin only (the build's Python package likewise comes
# first on PYTHONPATH, before the installed one in dist-packages).
for f in "$libdir"/*; do
  [[ $(basename "$f") == libyadecapillary.so ]] && continue
  ln -s "$f" "$overlay/$(basename "$f")"
done
ln -s "$build/lib/libyadecapillary.so" "$overlay/libyadecapillary.so"
cat > "$build/yade-capillary" <<SH
#!/bin/sh
# Debian's YADE with the yade-capillary plugin loaded; takes the same arguments as yade.
export YADE_PREFIX="$build/prefix"
export PYTHONPATH="$build/python\${PYTHONPATH:+:\$PYTHONPATH}"
exec "$yade" "\$@"
SH
chmod +x "$build/yade-capillary"
