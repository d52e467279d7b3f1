#!/usr/bin/env bash
# Builds and installs Trilinos 13.2 for shellfrac from Debian 12's own source package (trilinos 13.2.0-4).
#
# Why: Debian's binary Trilinos 13.2 (trilinos-all-dev) has Kokkos built for Serial only and no SEACAS.
# This build gives hybrid MPI + Kokkos OpenMP threads and Exodus output through SEACAS:
#   Kokkos (OpenMP + Serial), KokkosKernels (ETI trimmed to double / int ordinal / size_t offset,
#   LayoutLeft, OpenMP and Serial on HostSpace), Teuchos, Tpetra (Scalar double, GlobalOrdinal long long,
#   nodes OpenMP (default) and Serial), Zoltan2 (+ Zoltan, Xpetra) with PT-Scotch,
#   SEACAS Exodus and the applications exodiff, epu, nem_slice and nem_spread.
#   Open MPI (mpicc/mpicxx), netCDF from libnetcdf-dev, HDF5 of the openmpi flavour, Release, shared
#   libraries, C++17 without GNU extensions (Kokkos 3.4 refuses them), no tests, no examples, no Fortran.
#
# Prefix: ${XDG_CACHE_HOME:-$HOME/.cache}/shellfrac/trilinos-13.2-<key>, the key being the first 12 hex
# digits of the sha256 of this script's lines that are not comments: any change to the code installs into
# a new prefix, while editing comments keeps the installed one. Beside it: trilinos-src/ (the downloaded
# Debian source package), trilinos-src/trilinos-13.2.0-<hash> (unpacked tree) and trilinos-build-<hash>
# (build tree); both trees are deleted after a successful install unless SHELLFRAC_TRILINOS_KEEP_BUILD=1.
# An interrupted run resumes in the same build tree.
#
# Usage: tools/build-trilinos.sh [--print-prefix]
#   The last line printed is always the prefix; pass it to CMake as -DTrilinos_DIR=<prefix>/lib/cmake/Trilinos.
#   --print-prefix prints it without building. A complete prefix (stamp <prefix>/.complete, written last,
#   plus TrilinosConfig.cmake, bin/exodiff and bin/epu present) is left as it is.
#   SHELLFRAC_TRILINOS_JOBS: parallel compile jobs (default: nproc). Compiles run under nice -n 19.
#   As root, missing Debian build dependencies are installed with apt-get; otherwise the script names them.
#
# Source: `apt-get source --download-only trilinos`. Debian 12's images carry no deb-src entries, so unless
# the system's apt already has Sources indexes, a private apt configuration (own sources list, lists and
# cache under trilinos-src/apt) is used; /etc/apt is never changed. dpkg-source -x applies Debian's patches.
#
# Fixes applied to the unpacked source (idempotent):
#   - SEACAS ex_utils.c declares `const int NC_SZIP_NN = 32;`, which netCDF >= 4.9 (Debian 12: 4.9.0)
#     already defines as a macro in netcdf.h: the declaration is replaced by an #ifndef/#define guard.
#
# ParMETIS through Scotch (libptscotchparmetis from libscotchparmetis-dev) was tried and dropped: Scotch
# 7.0.3's parmetis.h is the ParMETIS 3 compatibility API (SCOTCH_Num/float, no PARMETIS_MAJOR_VERSION),
# so the TPL's check for ParMETIS >= 4.0.3 fails and Zoltan2 stops the configure with "Zoltan2 requires
# ParMETIS_version 4.0.3 or later" (Zoltan2's ParMETIS adapter also needs the 4.x idx_t/real_t API).
# Zoltan2's Scotch algorithm is available.
#
# Consumers: find_package(Trilinos 13.2 COMPONENTS ... SEACASExodus) with -DTrilinos_DIR=<prefix>/lib/cmake/Trilinos;
# the Exodus library is the imported target `exodus` (SEACASExodus_LIBRARIES), exodusII.h is in <prefix>/include.
# The plain imported targets (kokkoscore, tpetra, ...) carry no -fopenmp: link Kokkos::kokkos as well
# (it adds -fopenmp to compile and link lines) or add ${Trilinos_CXX_COMPILER_FLAGS}.
#
# Measured: a build from scratch (download, unpack, configure, build, install) on this project's 2-core
# machine with -j2 under nice -n 19, while another shellfrac build and test run competed for the same
# cores (load average 2-3.3), took 49 min 17 s: configure 7 s, SEACAS applications 4.5 min, the rest
# (KokkosKernels, Tpetra, Zoltan, Zoltan2, Xpetra) 44 min, install 5 s. Installed size: 99 MB.
set -euo pipefail

SCRIPT=$(readlink -f "${BASH_SOURCE[0]}")
# The key covers every line that is not a comment: editing only comments keeps the prefix.
HASH=$(grep -v '^[[:space:]]*#' "$SCRIPT" | sha256sum | cut -c1-12)
BASE="${XDG_CACHE_HOME:-$HOME/.cache}/shellfrac"
PREFIX="$BASE/trilinos-13.2-$HASH"
SRC_ROOT="$BASE/trilinos-src"
SRC="$SRC_ROOT/trilinos-13.2.0-$HASH"
BUILD="$BASE/trilinos-build-$HASH"
JOBS="${SHELLFRAC_TRILINOS_JOBS:-$(nproc)}"
UPSTREAM_VERSION=13.2.0

if [ "${1:-}" = "--print-prefix" ]; then
  echo "$PREFIX"
  exit 0
elif [ $# -gt 0 ]; then
  echo "usage: $0 [--print-prefix]" >&2
  exit 2
fi

T0=$(date +%s)
STEP="start"
log() { printf '[%s +%5ss] build-trilinos: %s\n' "$(date '+%F %T')" "$(( $(date +%s) - T0 ))" "$*"; }
phase() { STEP="$1"; log "== $1"; }
on_exit() {
  local rc=$?
  if [ $rc -ne 0 ]; then
    echo "build-trilinos: FAILED in step '$STEP' (exit $rc); prefix $PREFIX is not complete" >&2
  fi
}
trap on_exit EXIT

complete() {
  [ -f "$PREFIX/.complete" ] && [ -f "$PREFIX/lib/cmake/Trilinos/TrilinosConfig.cmake" ] &&
    [ -x "$PREFIX/bin/exodiff" ] && [ -x "$PREFIX/bin/epu" ]
}
if complete; then
  log "already installed (stamp $PREFIX/.complete)"
  echo "$PREFIX"
  exit 0
fi

mkdir -p "$BASE" "$SRC_ROOT"
# One build per prefix at a time.
exec 9>"$BASE/trilinos-13.2-$HASH.lock"
if ! flock -n 9; then
  log "another run is building $PREFIX; waiting for it"
  flock 9
  if complete; then echo "$PREFIX"; exit 0; fi
fi
log "prefix $PREFIX, build tree $BUILD, $JOBS job(s)"

# ---------------------------------------------------------------------------------------------------
phase "build dependencies"
DEPS=(dpkg-dev cmake ninja-build g++ libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libnetcdf-dev
      libptscotch-dev libblas-dev liblapack-dev zlib1g-dev)
missing=()
for p in "${DEPS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "build-trilinos: missing Debian packages (install them as root): ${missing[*]}" >&2
    exit 1
  fi
  log "installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq </dev/null
  apt-get install -y -qq --no-install-recommends "${missing[@]}" </dev/null
else
  log "all ${#DEPS[@]} Debian packages present"
fi
LIBDIR="/usr/lib/$(dpkg-architecture -qDEB_HOST_MULTIARCH)"

# ---------------------------------------------------------------------------------------------------
phase "download source package"
DL="$SRC_ROOT/download"
mkdir -p "$DL"
find_dsc() { ls "$DL"/trilinos_"$UPSTREAM_VERSION"-*.dsc 2>/dev/null | sort -V | tail -1; }
DSC=$(find_dsc || true)
if [ -n "$DSC" ]; then
  log "using $DSC"
else
  fetched=no
  # The system's own deb-src entries, when it has any.
  if apt-get indextargets --format '$(CREATED_BY)' 2>/dev/null | grep -qx Sources; then
    log "system apt has deb-src entries: apt-get source --download-only trilinos"
    if (cd "$DL" && apt-get source --download-only trilinos </dev/null); then fetched=yes; fi
  fi
  if [ "$fetched" = no ]; then
    # A private apt configuration with one deb-src entry for the system's Debian mirror and release.
    CODENAME=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
    [ -n "$CODENAME" ] || { echo "build-trilinos: no VERSION_CODENAME in /etc/os-release" >&2; exit 1; }
    MIRROR=$(
      { awk -v s="$CODENAME" 'BEGIN{RS=""; IGNORECASE=1}
          /(^|\n)Types:[^\n]*deb/ && $0 ~ "(^|\n)Suites:[^\n]*[ \t]" s "([ \t]|\n|$)" {
            if (match($0, /(^|\n)URIs:[ \t]*[^ \t\n]+/)) { u=substr($0, RSTART, RLENGTH); sub(/.*URIs:[ \t]*/, "", u); print u } }' \
          /etc/apt/sources.list.d/*.sources 2>/dev/null
        awk -v s="$CODENAME" '$1=="deb" { i=2; if ($2 ~ /^\[/) { while (i<=NF && $i !~ /\]$/) i++; i++ }
          if ($(i+1)==s) print $i }' /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null
      } | grep -v -i security | head -1 || true)
    MIRROR=${MIRROR:-http://deb.debian.org/debian}
    APTDIR="$SRC_ROOT/apt"
    mkdir -p "$APTDIR/sources.list.d" "$APTDIR/lists/partial" "$APTDIR/cache/archives/partial"
    : >"$APTDIR/sources.list"
    cat >"$APTDIR/sources.list.d/debian-src.sources" <<EOF
Types: deb-src
URIs: $MIRROR
Suites: $CODENAME
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    APT_PRIVATE=(-o "Dir::Etc::SourceList=$APTDIR/sources.list" -o "Dir::Etc::SourceParts=$APTDIR/sources.list.d"
                 -o "Dir::State::Lists=$APTDIR/lists" -o "Dir::Cache=$APTDIR/cache")
    # apt's download sandbox user (_apt) cannot write under root's home.
    [ "$(id -u)" -ne 0 ] || APT_PRIVATE+=(-o "APT::Sandbox::User=root")
    log "no deb-src in the system's apt: private configuration $APTDIR (deb-src $MIRROR $CODENAME main)"
    apt-get "${APT_PRIVATE[@]}" update </dev/null
    (cd "$DL" && apt-get "${APT_PRIVATE[@]}" source --download-only trilinos </dev/null)
  fi
  DSC=$(find_dsc || true)
  [ -n "$DSC" ] || {
    echo "build-trilinos: the source package downloaded is not Trilinos $UPSTREAM_VERSION: $(ls "$DL")" >&2
    exit 1
  }
  log "downloaded $DSC"
fi

# ---------------------------------------------------------------------------------------------------
phase "unpack source"
if [ -f "$SRC/.unpacked" ]; then
  log "already unpacked: $SRC"
else
  rm -rf "$SRC"
  dpkg-source -x "$DSC" "$SRC" | tail -n 3
  touch "$SRC/.unpacked"
fi

phase "patch source"
EXUTILS="$SRC/packages/seacas/libraries/exodus/src/ex_utils.c"
if grep -q 'const int NC_SZIP_NN = 32;' "$EXUTILS"; then
  sed -i 's|^\([[:space:]]*\)const int NC_SZIP_NN = 32;.*$|#ifndef NC_SZIP_NN\n#define NC_SZIP_NN 32 /* netcdf.h defines it from netCDF 4.9 on */\n#endif|' "$EXUTILS"
  log "ex_utils.c: NC_SZIP_NN guarded"
fi
grep -q '^#ifndef NC_SZIP_NN' "$EXUTILS" || { echo "build-trilinos: the NC_SZIP_NN fix did not apply" >&2; exit 1; }

# ---------------------------------------------------------------------------------------------------
phase "configure"
HDF5_DIR="$LIBDIR/hdf5/openmpi"
CONFIG=(
  -G Ninja
  -DCMAKE_BUILD_TYPE=Release
  -DCMAKE_INSTALL_PREFIX="$PREFIX"
  -DCMAKE_C_COMPILER="$(command -v mpicc)"
  -DCMAKE_CXX_COMPILER="$(command -v mpicxx)"
  -DCMAKE_CXX_STANDARD=17
  -DCMAKE_CXX_EXTENSIONS=OFF
  -DBUILD_SHARED_LIBS=ON
  -DTrilinos_ENABLE_Fortran=OFF
  -DTrilinos_ENABLE_OpenMP=ON
  -DTrilinos_ENABLE_ALL_PACKAGES=OFF
  -DTrilinos_ENABLE_ALL_OPTIONAL_PACKAGES=OFF
  -DTrilinos_ENABLE_TESTS=OFF
  -DTrilinos_ENABLE_EXAMPLES=OFF
  -DTrilinos_ENABLE_EXPLICIT_INSTANTIATION=ON
  -DTrilinos_ENABLE_DEVELOPMENT_MODE=OFF
  -DTrilinos_ASSERT_MISSING_PACKAGES=OFF
  -DTrilinos_ENABLE_FLOAT=OFF
  -DTrilinos_ENABLE_COMPLEX=OFF
  # packages
  -DTrilinos_ENABLE_Kokkos=ON
  -DTrilinos_ENABLE_KokkosKernels=ON
  -DTrilinos_ENABLE_Teuchos=ON
  -DTrilinos_ENABLE_Tpetra=ON
  -DTrilinos_ENABLE_Zoltan2=ON
  -DTrilinos_ENABLE_Epetra=OFF
  -DTrilinos_ENABLE_SEACASExodus=ON
  -DTrilinos_ENABLE_SEACASExodiff=ON
  -DTrilinos_ENABLE_SEACASEpu=ON
  -DTrilinos_ENABLE_SEACASNemslice=ON
  -DTrilinos_ENABLE_SEACASNemspread=ON
  -DTrilinos_ENABLE_SEACASExodus_for=OFF
  -DTrilinos_ENABLE_SEACASIoss=OFF
  # Kokkos 3.4
  -DKokkos_ENABLE_SERIAL=ON
  -DKokkos_ENABLE_OPENMP=ON
  -DKokkos_ENABLE_PTHREAD=OFF
  -DKokkos_ENABLE_CUDA=OFF
  # KokkosKernels: instantiate only what Tpetra<double, int, long long> uses (size_t row offsets)
  -DKokkosKernels_INST_DOUBLE=ON
  -DKokkosKernels_INST_FLOAT=OFF
  -DKokkosKernels_INST_COMPLEX_DOUBLE=OFF
  -DKokkosKernels_INST_COMPLEX_FLOAT=OFF
  -DKokkosKernels_INST_ORDINAL_INT=ON
  -DKokkosKernels_INST_ORDINAL_INT64_T=OFF
  -DKokkosKernels_INST_OFFSET_INT=OFF
  -DKokkosKernels_INST_OFFSET_SIZE_T=ON
  -DKokkosKernels_INST_LAYOUTLEFT=ON
  -DKokkosKernels_INST_LAYOUTRIGHT=OFF
  -DKokkosKernels_INST_EXECSPACE_OPENMP=ON
  -DKokkosKernels_INST_EXECSPACE_SERIAL=ON
  -DKokkosKernels_INST_EXECSPACE_THREADS=OFF
  -DKokkosKernels_INST_MEMSPACE_HOSTSPACE=ON
  -DKokkosKernels_INST_MEMSPACE_HBWSPACE=OFF
  # Tpetra
  -DTpetra_INST_DOUBLE=ON
  -DTpetra_INST_FLOAT=OFF
  -DTpetra_INST_LONG_DOUBLE=OFF
  -DTpetra_INST_COMPLEX_DOUBLE=OFF
  -DTpetra_INST_COMPLEX_FLOAT=OFF
  -DTpetra_INST_INT_INT=OFF
  -DTpetra_INST_INT_LONG=OFF
  -DTpetra_INST_INT_LONG_LONG=ON
  -DTpetra_INST_INT_UNSIGNED=OFF
  -DTpetra_INST_INT_UNSIGNED_LONG=OFF
  -DTpetra_INST_OPENMP=ON
  -DTpetra_INST_SERIAL=ON
  -DTpetra_INST_PTHREAD=OFF
  -DTpetra_INST_CUDA=OFF
  -DXpetra_ENABLE_Epetra=OFF
  # TPLs from Debian
  -DTPL_ENABLE_MPI=ON
  -DTPL_ENABLE_Scotch=ON
  -DTPL_Scotch_INCLUDE_DIRS=/usr/include/scotch
  -DTPL_Scotch_LIBRARIES="$LIBDIR/libptscotch.so;$LIBDIR/libptscotcherr.so;$LIBDIR/libscotch.so;$LIBDIR/libscotcherr.so"
  -DTPL_ENABLE_ParMETIS=OFF
  -DTPL_ENABLE_METIS=OFF
  -DTPL_ENABLE_Netcdf=ON
  -DTPL_Netcdf_INCLUDE_DIRS=/usr/include
  -DTPL_Netcdf_LIBRARIES="$LIBDIR/libnetcdf.so"
  -DTPL_ENABLE_HDF5=ON
  -DTPL_HDF5_INCLUDE_DIRS=/usr/include/hdf5/openmpi
  -DTPL_HDF5_LIBRARIES="$HDF5_DIR/libhdf5_hl.so;$HDF5_DIR/libhdf5.so;$LIBDIR/libz.so"
  -DTPL_ENABLE_Pnetcdf=OFF
  -DTPL_ENABLE_Matio=OFF
  -DTPL_ENABLE_X11=OFF
  -DTPL_ENABLE_CGNS=OFF
  -DTPL_ENABLE_Boost=OFF
  -DTPL_ENABLE_DLlib=OFF
)
mkdir -p "$BUILD"
nice -n 19 cmake -S "$SRC" -B "$BUILD" "${CONFIG[@]}" >"$BUILD/configure.log" 2>&1 || {
  tail -n 40 "$BUILD/configure.log" >&2
  echo "build-trilinos: configure failed; full log: $BUILD/configure.log" >&2
  exit 1
}
grep -E "^Final set of enabled (packages|SE packages|TPLs)" "$BUILD/configure.log" || true
log "configure log: $BUILD/configure.log"

# ---------------------------------------------------------------------------------------------------
phase "build"
# The SEACAS applications first: the part of this build that Debian's package never compiles.
nice -n 19 cmake --build "$BUILD" -j "$JOBS" --target exodiff epu nem_slice nem_spread >"$BUILD/build-seacas.log" 2>&1 || {
  grep -n -B2 -A12 -E "error:|FAILED:" "$BUILD/build-seacas.log" | head -n 60 >&2
  echo "build-trilinos: build of the SEACAS applications failed; full log: $BUILD/build-seacas.log" >&2
  exit 1
}
log "SEACAS applications built"
nice -n 19 cmake --build "$BUILD" -j "$JOBS" >"$BUILD/build.log" 2>&1 || {
  grep -n -B2 -A12 -E "error:|FAILED:" "$BUILD/build.log" | head -n 60 >&2
  echo "build-trilinos: build failed; full log: $BUILD/build.log" >&2
  exit 1
}
log "build log: $BUILD/build.log"

# ---------------------------------------------------------------------------------------------------
phase "install"
rm -f "$PREFIX/.complete"
nice -n 19 cmake --install "$BUILD" >"$BUILD/install.log" 2>&1 || {
  tail -n 20 "$BUILD/install.log" >&2
  echo "build-trilinos: install failed; full log: $BUILD/install.log" >&2
  exit 1
}

phase "check install"
for f in lib/cmake/Trilinos/TrilinosConfig.cmake include/KokkosCore_config.h include/exodusII.h bin/exodiff bin/epu; do
  [ -e "$PREFIX/$f" ] || { echo "build-trilinos: $PREFIX/$f missing after install" >&2; exit 1; }
done
grep -q '^#define KOKKOS_ENABLE_OPENMP' "$PREFIX/include/KokkosCore_config.h" ||
  { echo "build-trilinos: installed Kokkos lacks OpenMP" >&2; exit 1; }
if ldd "$PREFIX/bin/exodiff" "$PREFIX/lib/libtpetra.so" | grep -q 'not found'; then
  ldd "$PREFIX/bin/exodiff" "$PREFIX/lib/libtpetra.so" | grep 'not found' >&2
  echo "build-trilinos: installed binaries miss libraries" >&2
  exit 1
fi

ELAPSED=$(( $(date +%s) - T0 ))
printf 'key=%s\nbuilt=%s\nwall_seconds=%s\njobs=%s\n' \
  "$HASH" "$(date '+%F %T')" "$ELAPSED" "$JOBS" >"$PREFIX/.complete"
STEP="clean up"
if [ "${SHELLFRAC_TRILINOS_KEEP_BUILD:-0}" != 1 ]; then
  rm -rf "$BUILD" "$SRC"
fi
log "done in $((ELAPSED / 60)) min $((ELAPSED % 60)) s"
echo "$PREFIX"
