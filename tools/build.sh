#!/usr/bin/env bash
# Configures (once) and builds shellfrac in ./build (Release). Extra arguments go to cmake at configure time.
#   SHELLFRAC_BUILD_DIR        the build folder (default: build)
#   SHELLFRAC_TRILINOS_PREFIX  a Trilinos installed by tools/build-trilinos.sh (Kokkos OpenMP threads, SEACAS
#                              Exodus) instead of Debian's
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${SHELLFRAC_BUILD_DIR:-build}
TRILINOS=()
if [ -n "${SHELLFRAC_TRILINOS_PREFIX:-}" ]; then
  if [ ! -f "$SHELLFRAC_TRILINOS_PREFIX/lib/cmake/Trilinos/TrilinosConfig.cmake" ]; then
    echo "build.sh: SHELLFRAC_TRILINOS_PREFIX=$SHELLFRAC_TRILINOS_PREFIX has no lib/cmake/Trilinos/TrilinosConfig.cmake" \
         "(build it with tools/build-trilinos.sh)" >&2
    exit 1
  fi
  TRILINOS=(-DTrilinos_DIR="$SHELLFRAC_TRILINOS_PREFIX/lib/cmake/Trilinos")
fi
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "${TRILINOS[@]}" "$@"
fi
cmake --build "$BUILD_DIR" -j "$(nproc)"
