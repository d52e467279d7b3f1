#!/usr/bin/env bash
# The main job: installs dependencies if missing, builds if needed, runs the default example deck on
# 2 MPI ranks in ./results, and plots it. Usage: tools/run-example.sh [DECK.xml] [NUM_RANKS]
set -euo pipefail
# The deck as the caller names it (relative to the caller's directory), before moving to the repository.
DECK=$(realpath -e "${1:-$(dirname "$0")/../xml/beam_blast_225.xml}") || {
  echo "run-example.sh: no deck '${1:-}'" >&2
  exit 2
}
cd "$(dirname "$0")/.."
ROOT=$(pwd)
NP=${2:-2}
bash tools/install-deps.sh
bash tools/build.sh
source tools/mpi-env.sh
mkdir -p results
cd results
NAME=$(basename "$DECK" .xml)
mpiexec --oversubscribe -np "$NP" "$ROOT/build/apps/shellfrac/shellfrac" "$DECK"
/usr/bin/python3 "$ROOT/tools/plot_results.py" "$NAME.exo" -o "$NAME.png"
echo "results in $(pwd): $NAME.exo$([ "$NP" -gt 1 ] && echo ".$NP.*"), ${NAME}_history.csv, ${NAME}_summary.json, $NAME.png"
