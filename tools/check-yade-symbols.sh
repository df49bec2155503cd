#!/usr/bin/env bash
# Fail with a clear message if the plugin refers to a yade:: symbol that the installed YADE
# libraries do not define (class-layout or API drift between the headers and the binary).
set -euo pipefail
plugin=$1; libdir=$2
defined=$(mktemp); trap 'rm -f "$defined"' EXIT
find "$libdir" -name '*.so*' -type f -print0 | xargs -0 nm -D --defined-only 2>/dev/null | awk '{print $NF}' | sort -u > "$defined"
missing=$(nm -D --undefined-only "$plugin" | awk '{print $NF}' | grep '4yade' | sort -u | comm -23 - "$defined" || true)
if [[ -n "$missing" ]]; then
  echo "ERROR: $(basename "$plugin") needs yade:: symbols that the YADE in $libdir does not define:" >&2
  echo "$missing" | c++filt | sed 's/^/  /' >&2
  echo "The YADE headers used for the build do not match the installed YADE (see docs/design.md)." >&2
  rm -f "$plugin"; exit 1
fi
echo "all $(nm -D --undefined-only "$plugin" | grep -c '4yade') yade:: symbols of $(basename "$plugin") found in $libdir"
