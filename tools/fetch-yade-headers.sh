#!/usr/bin/env bash
# Put the YADE headers needed to compile the plugin (core/ lib/ pkg/common/ pkg/dem/) into DEST.
# Sources, in order: $YADE_SOURCE (a tarball or a source tree of the user's choice); Debian's
# yade source package fetched with apt (checksum verified); ../shared/cache as an offline
# fallback. Prints which source was used. Touches no system file: apt runs with a private
# source list, list directory and cache.
set -euo pipefail
DEST=$1
ROOT=$(cd "$(dirname "$0")/.." && pwd)
say() { printf '[yade-headers] %s\n' "$*"; }
# Debian's source package: yade 2025.2.0 (trixie), the newest tarball the archive serves.
TARBALL=yade_2025.2.0.orig.tar.bz2
SHA256=42702372251bf5e8f07a364bdf30533a1318947e4db90435b1f89293dc029156
PARTS=(core lib pkg/common pkg/dem)

if [[ -f "$DEST/.source" ]]; then say "using headers already in $DEST ($(cat "$DEST/.source"))"; exit 0; fi

unpack_tarball() { # $1 tarball, $2 description
  local tmp; tmp=$(mktemp -d)
  tar -xjf "$1" -C "$tmp" --wildcards $(printf "*/%s/ " "${PARTS[@]}") 2>/dev/null || tar -xf "$1" -C "$tmp"
  local top; top=$(find "$tmp" -mindepth 1 -maxdepth 1 -type d | head -n1)
  copy_tree "$top" "$2"; rm -rf "$tmp"
}
copy_tree() { # $1 source root, $2 description
  for p in "${PARTS[@]}"; do
    [[ -d "$1/$p" ]] || { say "error: $1 has no $p/ - not a YADE source tree"; exit 1; }
  done
  rm -rf "$DEST"; mkdir -p "$DEST"
  for p in "${PARTS[@]}"; do mkdir -p "$DEST/$(dirname "$p")"; cp -r "$1/$p" "$DEST/$p"; done
  echo "$2" > "$DEST/.source"; say "headers from: $2"
}
verify() { echo "$SHA256  $1" | sha256sum -c --status; }

if [[ -n "${YADE_SOURCE:-}" ]]; then
  if [[ -d "$YADE_SOURCE" ]]; then copy_tree "$YADE_SOURCE" "user source tree $YADE_SOURCE"
  else unpack_tarball "$YADE_SOURCE" "user tarball $YADE_SOURCE"; fi
  exit 0
fi

work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
if [[ $(id -u) -eq 0 ]] || [[ -w /var/cache ]]; then
  mkdir -p "$work/parts" "$work/lists/partial" "$work/cache/archives/partial" "$work/dl"
  cat > "$work/parts/yade-src.sources" <<SRC
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: trixie
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  opts=(-o Dir::Etc::SourceList=/dev/null -o "Dir::Etc::SourceParts=$work/parts" -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache")
  say "fetching Debian's yade source package with apt (private source list, suite trixie)"
  if apt-get update -qq "${opts[@]}" >/dev/null 2>&1; then
    # apt reports 404 for the .dsc/.debian.tar.xz on this mirror; the orig tarball is what we need.
    (cd "$work/dl" && apt-get source --download-only -qq "${opts[@]}" yade >/dev/null 2>&1 || true)
  fi
  if [[ -f "$work/dl/$TARBALL" ]] && verify "$work/dl/$TARBALL"; then
    unpack_tarball "$work/dl/$TARBALL" "Debian source package $TARBALL via apt (sha256 verified)"; exit 0
  fi
  say "apt did not deliver a verified $TARBALL"
fi
for cand in "$ROOT/../shared/cache/$TARBALL"; do
  if [[ -f "$cand" ]] && verify "$cand"; then
    unpack_tarball "$cand" "offline fallback $cand (sha256 verified)"; exit 0
  fi
done
say "error: no YADE headers. Set YADE_SOURCE to a YADE source tarball or tree."; exit 1
