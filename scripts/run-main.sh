#!/usr/bin/env bash
# README command 1: installs the dependencies, builds VoxelBRep against ParaView 5.11 (Release,
# build directory `build`) and runs Examples/voxelbrep_run.py. Without arguments the example
# extracts the EVM boundary of a built-in 128^3 phantom and writes out/voxelbrep.vtp and
# out/voxelbrep.png; arguments are passed on to it (see README.md, "Running on your own file").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh
cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
  -DBUILD_TESTING=ON
cmake --build build -j"${VOXELBREP_JOBS:-2}"

export PYTHONPATH="$PWD/build/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
# Rendering needs an X server: xvfb-run provides one (neither ParaView's VTK nor Debian's has
# an offscreen-only window).
exec xvfb-run -a /usr/bin/python3 Examples/voxelbrep_run.py "$@"
