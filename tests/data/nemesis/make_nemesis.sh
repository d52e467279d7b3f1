#!/usr/bin/env bash
# Regenerates the pre-decomposed test meshes of this folder: two_blocks_tri6.exo (the Tri6TwoBlocksEverySet mesh
# of packages/meshio/test/test_exodus_piece_reader.cpp, written by that test) split for 1 to 4 ranks by SEACAS
# nem_slice (inertial bisection, elemental decomposition) and nem_spread, into two_blocks_tri6.par.P.r; and
# two_blocks_tri3.exo (the Tri3TwoBlocksEverySet mesh) for 2 ranks, into two_blocks_tri3.par.2.r.
#   tests/data/nemesis/make_nemesis.sh SEACAS_BIN   (the bin/ of tools/build-trilinos.sh's prefix)
set -euo pipefail
bin=$1
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
split() {  # split MESH P
  cp "$here/$1.exo" mesh.exo
  "$bin/nem_slice" -e -m "mesh=$2" -l inertial -o mesh.nem mesh.exo > /dev/null
  mkdir -p 1
  cat > nem_spread.inp <<INP
Input FEM file          = mesh.exo
LB file                 = mesh.nem
Restart Time list       = off
Parallel Disk Info      = number=1
Parallel file location  = root=$work/, subdir=.
INP
  "$bin/nem_spread" nem_spread.inp > /dev/null
  for f in 1/mesh.par.$2.*; do cp "$f" "$here/$1.par.$2.${f##*.}"; done
  rm -rf 1 mesh.nem mesh.exo
}
for P in 1 2 3 4; do split two_blocks_tri6 "$P"; done
split two_blocks_tri3 2
