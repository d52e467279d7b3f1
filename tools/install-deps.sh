#!/usr/bin/env bash
# Installs shellfrac's build and run dependencies from Debian 12 packages. Idempotent: does nothing when
# everything is present. Works as root without a terminal (CI); otherwise uses sudo.
#   tools/install-deps.sh            the build, test and plotting dependencies
#   tools/install-deps.sh --render   also headless ParaView for tools/render.py (paraview, python3-paraview,
#                                    xvfb, python3-pil: about 600 MB)
set -euo pipefail

RENDER=0
for arg in "$@"; do
  case "$arg" in
    --render) RENDER=1 ;;
    *) echo "install-deps: unknown option '$arg' (use --render or nothing)" >&2; exit 2 ;;
  esac
done

PACKAGES=(
  # toolchain
  g++ make cmake pkg-config
  # Trilinos 13.2 (Tpetra, Kokkos, Teuchos, Zoltan2). Zoltan2's CMake config includes nearly every
  # package's config, so the umbrella -dev package is needed; plus Scotch for Zoltan2's scotch algorithm.
  trilinos-all-dev libptscotch-dev libscotchparmetis-dev
  # MPI, HDF5 (checkpoints), Exodus II + netCDF (meshes and results), METIS 5.1 (partitioning)
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libnetcdf-dev libexodusii-dev libmetis-dev
  # Gmsh (mesh generation in tests and examples), GoogleTest
  gmsh libgtest-dev
  # plotting of results (reads Exodus through netCDF4)
  python3 python3-numpy python3-matplotlib python3-netcdf4
)
if [ "$RENDER" -eq 1 ]; then
  PACKAGES+=(paraview python3-paraview xvfb python3-pil)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} Debian packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "install-deps: installing ${#missing[@]} package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" </dev/null >/tmp/shellfrac-apt.log 2>&1 || {
  echo "install-deps: apt-get failed; last lines of /tmp/shellfrac-apt.log:" >&2
  tail -20 /tmp/shellfrac-apt.log >&2
  exit 1
}
echo "install-deps: done"
