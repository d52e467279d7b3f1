#!/usr/bin/env bash
# Meshes the A319 skin (tools/a319/fetch.sh gets A319.brep, in millimetres) into linear triangles for
# shellfrac, written as Gmsh msh 4.1 (ASCII) in metres.
#
#   tools/a319/mesh.sh [-i BREP] [-o OUT.msh] [-s SIZE_MM] [-f FIRST_SIZE_MM] [-a ALGORITHM] [--direct]
#
#   -i   the BRep (default a319/A319.brep)
#   -o   the mesh to write (default a319/a319.msh); written through a temporary, then renamed
#   -s   target element size in mm (default 100)
#   -f   size of the first mesh, whose facets carry the geometry of the final one (default SIZE / 2)
#   -a   Gmsh 2-D algorithm for the final mesh: 6 Frontal-Delaunay (default), 1 MeshAdapt, 5 Delaunay
#   --direct  mesh the CAD faces directly (gmsh BREP -2 -clmax SIZE), for comparison: its short CAD
#        edges (7 to 30 mm) leave triangles 2 mm high that set the explicit time step
#
# The default route meshes the CAD faces at FIRST_SIZE, then remeshes that triangulation with remesh.geo
# (ClassifySurfaces + CreateGeometry): the surfaces stay the 83 CAD faces, but the curves between two faces are
# rebuilt from the shared mesh edges, so the short CAD edges vanish. Gmsh 4.8.4 (Debian 12) runs with one
# thread (-nt 1) and at nice 10 (SHELLFRAC_NICE to change). The mesh is summarised by mesh_quality.py.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { echo "mesh.sh: error: $*" >&2; exit 1; }
note() { echo "mesh.sh: $*" >&2; }

brep=a319/A319.brep out=a319/a319.msh size=100 first="" algorithm=6 direct=0
while [[ $# -gt 0 ]]; do
  case $1 in
    -i) brep=${2:?}; shift 2 ;;
    -o) out=${2:?}; shift 2 ;;
    -s) size=${2:?}; shift 2 ;;
    -f) first=${2:?}; shift 2 ;;
    -a) algorithm=${2:?}; shift 2 ;;
    --direct) direct=1; shift ;;
    -h|--help) sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
[[ -z $first ]] && first=$(awk -v s="$size" 'BEGIN { print s / 2 }')
for v in "$size" "$first"; do
  [[ $v =~ ^[0-9]+([.][0-9]+)?$ ]] && awk -v s="$v" 'BEGIN { exit !(s > 0) }' || die "bad size '$v' (mm)"
done
[[ $algorithm =~ ^(1|5|6)$ ]] || die "bad algorithm '$algorithm' (1, 5 or 6)"
command -v gmsh >/dev/null 2>&1 || die "gmsh not found (Debian 12: apt-get install gmsh)"
[[ -r $brep ]] || die "cannot read $brep (tools/a319/fetch.sh fetches it)"
version=$(gmsh --version 2>&1 | tail -n 1)
[[ $version == 4.8.4 ]] || note "warning: gmsh $version; these settings were measured with 4.8.4"

mkdir -p "$(dirname "$out")"
work=$(mktemp -d "${TMPDIR:-/tmp}/shellfrac-a319-mesh.XXXXXX")
tmp_out=$(mktemp "$(dirname "$out")/.$(basename "$out").XXXXXX")
trap 'rm -rf "$work" "$tmp_out"' EXIT

run_gmsh() {  # log file, then gmsh arguments; a failure keeps the log as OUT.log
  local log=$1; shift
  if ! nice -n "${SHELLFRAC_NICE:-10}" gmsh "$@" -nt 1 >"$log" 2>&1 || grep -q '^Error' "$log"; then
    grep -E '^(Error|Warning)' "$log" | head -n 20 >&2
    cp "$log" "$out.log" 2>/dev/null || true
    die "gmsh failed (its log: $out.log)"
  fi
}

start=$(date +%s)
if [[ $direct == 1 ]]; then
  note "meshing the CAD faces of $brep directly at $size mm"
  run_gmsh "$work/direct.log" "$brep" -2 -clmax "$size" -format msh41 -save_all \
    -string "Mesh.ScalingFactor = 0.001;" -o "$tmp_out"
else
  note "first mesh of the CAD faces of $brep at $first mm"
  run_gmsh "$work/first.log" "$brep" -2 -clmax "$first" -format msh41 -save_all -o "$work/first.msh"
  note "remeshing its reclassified surfaces at $size mm (algorithm $algorithm)"
  run_gmsh "$work/remesh.log" "$here/remesh.geo" -2 -format msh41 -save_all \
    -setstring base "$work/first.msh" -setnumber size "$size" -setnumber algorithm "$algorithm" \
    -setnumber scaling 0.001 -o "$work/remeshed.msh"
  # Gmsh writes the discrete surfaces' parametrizations (the whole first mesh, 87 MB at 50 mm) after the
  # elements; the section is optional in msh 4.1 and no reader of the mesh needs it.
  awk '/^\$Parametrizations$/ { skip = 1 } !skip { print } /^\$EndParametrizations$/ { skip = 0 }' \
    "$work/remeshed.msh" >"$tmp_out"
fi
[[ -s $tmp_out ]] && grep -q '^\$EndElements$' "$tmp_out" || die "gmsh wrote no complete mesh"
chmod 0644 "$tmp_out"
mv -f "$tmp_out" "$out"
note "wrote $out (metres) in $(( $(date +%s) - start )) s"

if /usr/bin/python3 -c 'import numpy' 2>/dev/null; then
  /usr/bin/python3 "$here/mesh_quality.py" "$out" --smallest 5 --parts
else
  note "no numpy for /usr/bin/python3: skipping mesh_quality.py"
fi
