#!/usr/bin/env bash
# Put the YADE headers needed to compile the plugin (core/ lib/ pkg/common/ pkg/dem/) into DEST.
# Sources, in order: $YADE_SOURCE (a tarball or a source tree of the user's choice); Debian's
# yade source package fetched with apt from the Debian mirror(s) the local apt is configured
# with (checksum verified); ../shared/cache as an offline fallback. Prints which source was used.
# Touches no system file: apt runs with a private source list, list directory and cache.
set -euo pipefail
DEST=$1
ROOT=$(cd "$(dirname "$0")/.." && pwd)
say() { printf '[yade-headers] %s\n' "$*"; }
# Debian's source package: yade 2025.2.0 (suite trixie), the newest tarball the archive serves.
VERSION=2025.2.0
SUITE=trixie
TARBALL=yade_$VERSION.orig.tar.bz2
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

# The Debian mirror(s) that the local apt configuration names (sources.list, .list and
# deb822 .sources files alike; `apt-get indextargets` reads them all): the repositories whose Release
# file is labelled Debian, and, where no Release file is known yet (no `apt-get update` so far),
# those configured for this release's own suite. Security and third-party repositories are left out.
debian_mirrors() {
  local codename; codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
  { apt-get indextargets --format 'K|$(LABEL)|$(REPO_URI)|$(SOURCESENTRY)' 2>/dev/null
    apt-get indextargets --no-release-info --format 'U|$(RELEASE)|$(REPO_URI)|$(SOURCESENTRY)' 2>/dev/null; } |
    awk -F'|' -v c="$codename" '
      $1 == "K" { known[$3] = 1; if ($2 == "Debian" && !seen[$3]++) print $3 "|" $4; next }
      !($3 in known) && c != "" && $2 == c && !seen[$3]++ { print $3 "|" $4 }'
}
# The keyring a sources entry names (Signed-By: in a deb822 stanza, [signed-by=...] on a one-line
# entry); empty when it names none or embeds the key. $1: file:n (stanza n or line n).
signed_by() {
  local file=${1%:*} n=${1##*:}
  [[ -r $file ]] || return 0
  if [[ $file == *.sources ]]; then
    awk -v n="$n" 'BEGIN { RS = ""; FS = "\n" }
      { real = 0; for (i = 1; i <= NF; i++) if ($i !~ /^#/) real = 1 }  # comment-only blocks are no stanza
      real && ++k == n { for (i = 1; i <= NF; i++) if ($i ~ /^Signed-By:[ \t]*[^ \t]/) { sub(/^Signed-By:[ \t]*/, "", $i); print $i } }' "$file"
  else
    sed -n "${n}s/.*signed-by=\([^] ]*\).*/\1/p" "$file"
  fi
}

work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
if [[ $(id -u) -eq 0 ]] || [[ -w /var/cache ]]; then
  uris=(); keyring=
  while IFS='|' read -r uri entry; do
    uris+=("$uri"); [[ -n $keyring ]] || keyring=$(signed_by "$entry")
  done < <(debian_mirrors)
  # A mirror signed by Debian's archive key when its entry does not say otherwise.
  [[ -n $keyring || ! -f /usr/share/keyrings/debian-archive-keyring.gpg ]] || keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  if ((${#uris[@]})); then
    mkdir -p "$work/parts" "$work/lists/partial" "$work/cache/archives/partial" "$work/dl"
    # The wanted version (2025.2.0) is the one of suite SUITE; only the suite is added to the mirrors.
    { echo "Types: deb-src"; echo "URIs: ${uris[*]}"; echo "Suites: $SUITE"; echo "Components: main"
      [[ -z $keyring ]] || echo "Signed-By: $keyring"; } > "$work/parts/yade-src.sources"
    opts=(-o Dir::Etc::SourceList=/dev/null -o "Dir::Etc::SourceParts=$work/parts" -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache")
    say "fetching Debian's yade source package with apt from ${uris[*]} (suite $SUITE, private source list)"
    # Failures are judged by the result: one unreachable mirror of several fails the update only.
    apt-get update -q "${opts[@]}" >"$work/apt.log" 2>&1 || true
    # Some mirrors answer 404 for the .dsc/.debian.tar.xz; the orig tarball is what we need.
    (cd "$work/dl" && apt-get source --download-only -q "${opts[@]}" yade >>"$work/apt.log" 2>&1 || true)
    if [[ -f "$work/dl/$TARBALL" ]] && verify "$work/dl/$TARBALL"; then
      unpack_tarball "$work/dl/$TARBALL" "Debian source package $TARBALL via apt from ${uris[*]} (sha256 verified)"; exit 0
    fi
    say "apt did not deliver a verified $TARBALL; its output:"; sed 's/^/    /' "$work/apt.log"
  else
    say "apt is configured with no Debian mirror"
  fi
fi
for cand in "$ROOT/../shared/cache/$TARBALL"; do
  if [[ -f "$cand" ]] && verify "$cand"; then
    unpack_tarball "$cand" "offline fallback $cand (sha256 verified)"; exit 0
  fi
done
say "error: no YADE headers. Set YADE_SOURCE to a YADE source tarball or tree."; exit 1
