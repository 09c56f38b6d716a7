#!/usr/bin/env bash
# The real-ParaView test (CTest label "paraview"): run_paraview_test.sh RADWALK SOURCE_DIR WORK_DIR
#
# 1. Fetches ParaView beside the system VTK with scripts/pvpython.sh (apt-get download + dpkg -x into a cache
#    outside the build; never apt-get install paraview) and installs xvfb with apt if it is missing.
#    Exit 77 (CTest: skipped) with a message when the packages cannot be fetched.
# 2. Makes every kind of radwalk output in WORK_DIR: solve .vtp (+ ParaView state), progressive .pvd, random-walk
#    .vtp with error bars (+ its convergence series), compare .vtp, path-tracer .vtp (+ series) and the path
#    tracer's PNG from the Cornell box's camera, form-factor diagnostics .vtp, an adaptively refined .vtp
#    (T-junctions), a patch .vtp without B, and solve .vtp files with states of a closed scene (the cube) and an
#    open one (the parallel squares) for the one camera rule.
# 3. Runs tests/paraview/check_outputs.py in pvpython under scripts/with_xvfb.sh (once more if it dies other than
#    by failing its checks: an X server start occasionally fails on a loaded machine). It leaves
#    WORK_DIR/screenshots/*.png.
set -euo pipefail
radwalk=$1
src=$2
work=$3
skip=77

status=0
"$src/scripts/pvpython.sh" --fetch || status=$?
if [ "$status" -ne 0 ]; then
  [ "$status" -eq "$skip" ] && echo "SKIP: ParaView packages cannot be fetched here (see above)" >&2
  exit "$status"
fi
if ! command -v Xvfb >/dev/null; then
  if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null; then
    echo "installing xvfb (xvfb-run) with apt" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y -qq --no-install-recommends xvfb xauth >/dev/null 2>&1 ||
      { apt-get update -qq >/dev/null 2>&1 && apt-get install -y -qq --no-install-recommends xvfb xauth >/dev/null 2>&1; } ||
      { echo "SKIP: xvfb cannot be installed here" >&2; exit "$skip"; }
  else
    echo "SKIP: Xvfb is missing and cannot be installed (not root)" >&2
    exit "$skip"
  fi
fi

rm -rf "$work"
mkdir -p "$work/tmp"
cd "$work"
# Temporary files of everything below (radwalk, pvpython, the X wrapper's folder) in the work folder, not in /tmp.
export TMPDIR=$work/tmp
cb=$src/meshes/cornell_box.obj
run() { echo "+ radwalk $*" >&2; "$radwalk" -q "$@" >/dev/null; }
run solve "$cb" --max-edge 50 --rays 2000 -o solve.vtp --paraview-state solve.py --json solve.json
run solve "$cb" --max-edge 100 --rays 500 --solver gauss-seidel --progressive progressive
run solve "$cb" --max-edge 100 --rays 500 --solver random-walk --walk gather --estimator expected-value \
  --walks-per-patch 200 --theory -o random_walk.vtp --progressive random_walk_series
run compare "$src/meshes/cube.obj" --rays 2000 --walks-per-patch 200 --runs 2 \
  --estimators gather-absorption,gather-expected-value,shoot-collision -o compare.vtp
run pathtrace "$cb" --max-edge 100 --spp 16 -o pathtrace.vtp --progressive pathtrace_series
run pathtrace "$cb" --image pathtrace_128.png --width 128 --height 128 --spp 256
run formfactors "$cb" --max-edge 100 --rays 500 --vtp formfactors.vtp
run solve "$cb" --refine 0.2 --refine-steps 3 --rays 4000 -o refined.vtp
run patch "$cb" --max-edge 100 -o patches.vtp
run solve "$src/meshes/cube.obj" --max-edge 0.25 --rays 500 -o cube.vtp --paraview-state cube.py
run solve "$src/meshes/parallel_squares.obj" --max-edge 0.25 --rays 500 -o squares.vtp --paraview-state squares.py

attempt() {
  "$src/scripts/with_xvfb.sh" "$src/scripts/pvpython.sh" "$src/tests/paraview/check_outputs.py" "$work" "$src"
}
# Exit 1 is the checks' verdict (or a Python error); anything else (an abort in the X or OpenGL start) is retried.
status=0
attempt || status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 1 ]; then
  echo "pvpython exited with $status (X server or OpenGL start failed?); once more" >&2
  status=0
  attempt || status=$?
fi
exit "$status"
