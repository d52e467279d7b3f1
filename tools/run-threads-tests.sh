#!/usr/bin/env bash
# The threads path (README "for threads"): builds (or reuses) the Trilinos 13.2 with Kokkos OpenMP and SEACAS of
# tools/build-trilinos.sh, builds shellfrac against it in ${SHELLFRAC_BUILD_DIR:-build-threads} and runs the
# ctest label `threads` (ranks x threads bitwise equal to 1 x 1). Extra arguments go to ctest.
#   SHELLFRAC_THREADS_TARGETS  what to build (default: all; CI builds only what the threads tests run)
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
prefix=$(bash tools/build-trilinos.sh | tail -n 1)
export SHELLFRAC_TRILINOS_PREFIX=$prefix SHELLFRAC_BUILD_DIR=${SHELLFRAC_BUILD_DIR:-build-threads}
if [ -n "${SHELLFRAC_THREADS_TARGETS:-}" ]; then
  [ -f "$SHELLFRAC_BUILD_DIR/CMakeCache.txt" ] ||
    cmake -S . -B "$SHELLFRAC_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DTrilinos_DIR="$prefix/lib/cmake/Trilinos"
  # shellcheck disable=SC2086
  cmake --build "$SHELLFRAC_BUILD_DIR" -j "$(nproc)" --target $SHELLFRAC_THREADS_TARGETS
else
  bash tools/build.sh
fi
source tools/mpi-env.sh
ctest --test-dir "$SHELLFRAC_BUILD_DIR" --output-on-failure -L threads "$@"
