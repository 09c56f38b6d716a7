#!/usr/bin/env bash
# The main job, from a fresh Debian 12 machine: install what is missing, build, solve the bundled Cornell box
# (patched to edges of at most 50 mm) and write results/cornell_box.vtp (open it in ParaView), a ParaView state
# results/cornell_box.py (File > Load State: true colours from the Cornell camera), .csv and .json.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
mkdir -p results
./build/apps/radwalk solve meshes/cornell_box.obj --max-edge 50 \
  -o results/cornell_box.vtp --paraview-state results/cornell_box.py --csv results/cornell_box.csv \
  --json results/cornell_box.json
