#!/usr/bin/env bash
# Configures (once) and builds shellfrac in ./build (Release). Extra arguments go to cmake at configure time.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${SHELLFRAC_BUILD_DIR:-build}
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@"
fi
cmake --build "$BUILD_DIR" -j "$(nproc)"
