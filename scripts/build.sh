#!/usr/bin/env bash
# Configures and builds radwalk (Release) into build/ (or $RADWALK_BUILD_DIR). Extra arguments go to CMake.
# With ccache installed it compiles through it, with CCACHE_BASEDIR at the source root, so that another copy of the
# source (the pip-install test's) reuses the compiled objects.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${RADWALK_BUILD_DIR:-build}
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR=$PWD  # the source root, whatever the environment says (setup.py does the same)
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
cmake --build "$build_dir" -j"$(nproc)"
