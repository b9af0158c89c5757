#!/usr/bin/env bash
# Installs the Debian 12 (bookworm) packages VoxelBRep needs to build against ParaView 5.11,
# run its tests and build its sanitizer variant. Idempotent: packages that are already
# installed are skipped, and apt-get update runs only when something must be installed, so
# the script also succeeds without network access once everything is there.
#
# It never installs libvtk9-dev: Debian's stock VTK 9.1 conflicts with python3-paraview
# (scripts/run-tests.sh swaps them temporarily for its VTK 9.1 stage). If a previous run left
# libvtk9-dev or python3-vtk9 installed, they are removed so that python3-paraview can be
# (re)installed.
set -euo pipefail

PACKAGES=(
  # ParaView 5.11 and the VTK 9.2 SDK it ships (the packages its CMake config looks for)
  paraview paraview-dev python3-paraview python3-dev
  qttools5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools
  libopenmpi-dev python3-mpi4py openmpi-bin
  libdouble-conversion-dev libexpat1-dev libeigen3-dev libfreetype-dev libgdal-dev
  libgl2ps-dev libglew-dev libhdf5-dev libhdf5-openmpi-dev libjpeg-dev liblz4-dev
  liblzma-dev libxml2-dev libnetcdf-dev libgl-dev libpng-dev libtheora-dev libtiff-dev
  libx11-dev libxt-dev zlib1g-dev libutfcpp-dev libavcodec-dev libavformat-dev
  libswscale-dev libavutil-dev libjsoncpp-dev libpugixml-dev libfmt-dev
  # the algorithm core
  libcgal-dev libgmp-dev libqhull-dev
  # toolchain, tests, benchmarks, examples
  cmake g++ clang-format libgtest-dev libbenchmark-dev
  xvfb xauth python3-numpy python3-scipy python3-opencv
  # real label maps used by data-driven tests (NIfTI atlases)
  mricron-data
)
# Packages that must not be installed at the same time as python3-paraview.
CONFLICTING=(libvtk9-dev python3-vtk9)

is_installed() {
  [ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$1" 2>/dev/null)" = "ii " ]
}

missing=()
for p in "${PACKAGES[@]}"; do
  is_installed "$p" || missing+=("$p")
done
remove=()
for p in "${CONFLICTING[@]}"; do
  if is_installed "$p"; then remove+=("$p-"); fi
done

if [ ${#missing[@]} -eq 0 ] && [ ${#remove[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages are installed"
  exit 0
fi

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo" >&2; exit 1; }
  SUDO=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive

echo "install-deps: installing ${missing[*]:-nothing} ${remove[*]:+(removing ${remove[*]%-})}"
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}" "${remove[@]}"

still=()
for p in "${PACKAGES[@]}"; do
  is_installed "$p" || still+=("$p")
done
if [ ${#still[@]} -ne 0 ]; then
  echo "install-deps: still missing: ${still[*]}" >&2
  exit 1
fi
echo "install-deps: done"
