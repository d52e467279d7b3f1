#!/usr/bin/env bash
# Fetches the Airbus A319 skin of the paper's §6.5 example: the OpenCASCADE BRep
# benchmarks/brep/A319.brep.gz of the Gmsh 4.8.4 source tree (millimetres, 83 surfaces), taken from Debian 12's
# gmsh source package the way a user would, with `apt-get source --download-only gmsh`.
#
#   tools/a319/fetch.sh [OUTDIR]        (default: ./a319)
#
# Writes OUTDIR/A319.brep.gz (kept, checked against its sha256) and OUTDIR/A319.brep. Idempotent: does nothing
# when both are there and the .gz has the right hash. Needs no standard input and works as root (CI).
#
# When apt has no deb-src entry (or the system's fails), the source package is fetched with a private apt
# configuration in a temporary directory (its own sources list, lists and cache; /etc/apt is never changed):
#   deb-src http://deb.debian.org/debian bookworm main
# SHELLFRAC_A319_PRIVATE_APT=1 forces that route.
set -euo pipefail

readonly SHA256_GZ=0ed03582ebb4459721338c5fc80c9cb767918f97a68be4d5c04b7204afc780c9
readonly ORIG_TARBALL=gmsh_4.8.4+ds2.orig.tar.xz
readonly MEMBER='*/benchmarks/brep/A319.brep.gz'
readonly DEBIAN_MIRROR=${SHELLFRAC_DEBIAN_MIRROR:-http://deb.debian.org/debian}
readonly DEBIAN_SUITE=${SHELLFRAC_DEBIAN_SUITE:-bookworm}

die() { echo "fetch.sh: error: $*" >&2; exit 1; }
note() { echo "fetch.sh: $*" >&2; }

[[ $# -le 1 ]] || die "usage: $0 [OUTDIR]"
outdir=${1:-a319}
gz=$outdir/A319.brep.gz
brep=$outdir/A319.brep

for tool in apt-get tar xz gunzip sha256sum mktemp; do
  command -v "$tool" >/dev/null 2>&1 || die "'$tool' not found (this script expects Debian 12 or a derivative)"
done

hash_of() { sha256sum "$1" | cut -d' ' -f1; }

# Temporaries removed on any exit (the downloads, and partial outputs of an interrupted run).
cleanup=()
trap 'rm -rf "${cleanup[@]}"' EXIT

# Unpacks $1 (a checked A319.brep.gz) into $brep through a temporary in the output directory.
unpack() {
  local tmp
  tmp=$(mktemp "$outdir/.A319.brep.XXXXXX") || die "cannot write into $outdir"
  cleanup+=("$tmp")
  gunzip -c "$1" >"$tmp" || { rm -f "$tmp"; die "gunzip of $1 failed"; }
  chmod 0644 "$tmp"
  mv -f "$tmp" "$brep"
}

# The .gz is already there with the right hash: nothing to fetch.
if [[ -f $gz && $(hash_of "$gz") == "$SHA256_GZ" ]]; then
  if [[ -f $brep && $(gunzip -c "$gz" | sha256sum | cut -d' ' -f1) == "$(hash_of "$brep")" ]]; then
    note "$brep is up to date (sha256 of $gz checked); nothing to do"
    exit 0
  fi
  note "$gz checked (sha256); unpacking it into $brep"
  unpack "$gz"
  note "wrote $brep ($(du -h "$brep" | cut -f1))"
  exit 0
fi

mkdir -p "$outdir" || die "cannot create $outdir"
work=$(mktemp -d "${TMPDIR:-/tmp}/shellfrac-a319.XXXXXX") || die "cannot create a temporary directory"
cleanup+=("$work")
# apt downloads as the unprivileged user _apt when run as root: let it write into the download directory.
chmod 0755 "$work"
mkdir -p "$work/src"
chmod 0777 "$work/src"

# Whether the system's apt sources (/etc/apt, or where APT_CONFIG points) have a deb-src entry.
have_system_deb_src() {
  local SL=/etc/apt/sources.list SP=/etc/apt/sources.list.d/ f
  eval "$(apt-config shell SL Dir::Etc::SourceList/f SP Dir::Etc::SourceParts/d 2>/dev/null)" || true
  for f in "$SL" "$SP"*.list; do
    [[ -f $f ]] && grep -Eq '^[[:space:]]*deb-src[[:space:]]' "$f" && return 0
  done
  for f in "$SP"*.sources; do
    [[ -f $f ]] && grep -Eiq '^[[:space:]]*Types:.*\bdeb-src\b' "$f" && return 0
  done
  return 1
}

# The system's apt, with the source indexes it already has.
fetch_system() {
  (cd "$work/src" && apt-get -q source --download-only gmsh) </dev/null >"$work/apt-source.log" 2>&1
}

# A private apt configuration: its own sources list, lists and cache under $work.
fetch_private() {
  local etc=$work/apt/etc lists=$work/apt/lists cache=$work/apt/cache keyring=""
  mkdir -p "$etc" "$lists/partial" "$cache/archives/partial"
  chmod -R 0755 "$work/apt"
  [[ -r /usr/share/keyrings/debian-archive-keyring.gpg ]] &&
    keyring="[signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] "
  echo "deb-src ${keyring}${DEBIAN_MIRROR} ${DEBIAN_SUITE} main" >"$etc/sources.list"
  local -a opts=(
    -o "Dir::Etc::SourceList=$etc/sources.list"
    -o "Dir::Etc::SourceParts=/dev/null"
    -o "Dir::State::Lists=$lists"
    -o "Dir::Cache=$cache"
  )
  note "apt-get update with a private sources list ($DEBIAN_MIRROR $DEBIAN_SUITE, deb-src)"
  apt-get -q "${opts[@]}" update </dev/null >"$work/apt-update.log" 2>&1 || {
    tail -n 20 "$work/apt-update.log" >&2
    die "apt-get update (private sources list) failed"
  }
  # apt-get update exits 0 when it could not reach the mirror: look for the Sources index itself.
  if ! compgen -G "$lists/*_source_Sources*" >/dev/null; then
    grep -E '^(Err|W|E):' "$work/apt-update.log" >&2 || tail -n 20 "$work/apt-update.log" >&2
    die "apt-get update got no source index from $DEBIAN_MIRROR $DEBIAN_SUITE (no network, or no mirror there?)"
  fi
  (cd "$work/src" && apt-get -q "${opts[@]}" source --download-only gmsh) </dev/null >"$work/apt-source.log" 2>&1
}

tarball=$work/src/$ORIG_TARBALL
fetched=""
if [[ ${SHELLFRAC_A319_PRIVATE_APT:-0} != 1 ]] && have_system_deb_src; then
  note "apt-get source --download-only gmsh (system deb-src entries)"
  if fetch_system && [[ -f $tarball ]]; then
    fetched=system
  else
    note "the system's deb-src entries did not give $ORIG_TARBALL; trying a private apt configuration"
    rm -f "$work/src"/gmsh_*
  fi
elif [[ ${SHELLFRAC_A319_PRIVATE_APT:-0} == 1 ]]; then
  note "SHELLFRAC_A319_PRIVATE_APT=1: private apt configuration"
else
  note "no deb-src entry in /etc/apt: private apt configuration"
fi
if [[ -z $fetched ]]; then
  if fetch_private && [[ -f $tarball ]]; then
    fetched=private
  else
    tail -n 20 "$work/apt-source.log" >&2 || true
    ls -l "$work/src" >&2 || true
    die "apt-get source --download-only gmsh did not give $ORIG_TARBALL"
  fi
fi
note "downloaded $(basename "$tarball") ($(du -h "$tarball" | cut -f1), $fetched apt)"

note "extracting $MEMBER"
tar -xJf "$tarball" -C "$work" --wildcards --no-anchored "$MEMBER" ||
  die "$MEMBER not found in $ORIG_TARBALL"
mapfile -t found < <(find "$work" -path "$work/src" -prune -o -path '*/benchmarks/brep/A319.brep.gz' -print)
[[ ${#found[@]} -eq 1 ]] || die "expected one A319.brep.gz in $ORIG_TARBALL, found ${#found[@]}"
got=$(hash_of "${found[0]}")
[[ $got == "$SHA256_GZ" ]] || die "sha256 of A319.brep.gz is $got, expected $SHA256_GZ"

# Write into temporaries in the output directory, then rename: never a half-written file.
unpack "${found[0]}"
tmp_gz=$(mktemp "$outdir/.A319.brep.gz.XXXXXX") || die "cannot write into $outdir"
cleanup+=("$tmp_gz")
cp "${found[0]}" "$tmp_gz"
chmod 0644 "$tmp_gz"
mv -f "$tmp_gz" "$gz"
note "wrote $gz (sha256 $SHA256_GZ) and $brep ($(du -h "$brep" | cut -f1))"
