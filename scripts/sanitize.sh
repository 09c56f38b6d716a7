#!/usr/bin/env bash
# The sanitizer build of the whole suite (docs/reliability.md, "Sanitizer build"): configures and builds radwalk,
# its tests and the replay programs with AddressSanitizer and UndefinedBehaviorSanitizer (RADWALK_SANITIZE,
# default address,undefined) into build-asan/ (or $RADWALK_ASAN_BUILD_DIR), then runs the default suite there except
# the fuzz, paraview and python labels (the fuzz campaigns have their own instrumented tree; pvpython and the
# system python3 are not instrumented, so neither can load instrumented code).
#   scripts/sanitize.sh                      # build and run
#   scripts/sanitize.sh --build-only
#   scripts/sanitize.sh --no-build -R atomic # more arguments go to ctest
# Extra CMake arguments: RADWALK_ASAN_CMAKE_ARGS (e.g. "-DCMAKE_CXX_COMPILER=clang++ -DRADWALK_SANITIZE=address").
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${RADWALK_ASAN_BUILD_DIR:-build-asan}
build=1
run=1
case "${1:-}" in
  --build-only) run=0; shift ;;
  --no-build) build=0; shift ;;
esac
if [ "$build" = 1 ]; then
  launcher=()
  if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
  # shellcheck disable=SC2086
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRADWALK_SANITIZE=address,undefined \
        -DRADWALK_BUILD_BENCH=OFF "${launcher[@]}" ${RADWALK_ASAN_CMAKE_ARGS:-} >/dev/null
  cmake --build "$build_dir" -j"$(nproc)"
fi
if [ "$run" = 1 ]; then
  # halt_on_error: a report fails its test; detect_leaks stays on (tests/lsan.supp lists the known library leaks).
  export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=0}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  ctest --test-dir "$build_dir" -LE 'slow|fuzz|paraview|python' --output-on-failure -j"$(nproc)" "$@"
fi
