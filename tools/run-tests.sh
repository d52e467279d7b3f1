#!/usr/bin/env bash
# The whole test suite: installs dependencies if missing, builds, runs every ctest test (unit, MPI at
# several rank counts, end-to-end). Extra arguments go to ctest (e.g. -L mpi, -R mesh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
bash tools/build.sh
source tools/mpi-env.sh
ctest --test-dir "${SHELLFRAC_BUILD_DIR:-build}" --output-on-failure -j 2 "$@"
