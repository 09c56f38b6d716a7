#!/usr/bin/env bash
# The fuzz harnesses of tests/fuzz (docs/reliability.md, section "Fuzzing").
#
#   scripts/fuzz.sh HARNESS|all SECONDS [LIBFUZZER_FLAG...]   build the fuzz tree, then fuzz HARNESS (or each
#                                                             harness in turn) for SECONDS
#   scripts/fuzz.sh --build-only                              configure and build the fuzz tree only
#   scripts/fuzz.sh --no-build HARNESS|all SECONDS [FLAG...]  fuzz without building (CTest: the build is a fixture)
#
# Harnesses: obj_mtl mtl ply stl gltf vtk matrix_market npz validate_patch. The fuzz tree is $RADWALK_FUZZ_BUILD_DIR (default
# build/fuzz): clang++ ($RADWALK_FUZZ_CXX, default clang++) with libFuzzer, ASan and UBSan, through
# $RADWALK_FUZZ_LAUNCHER (default ccache when installed). Where clang++ cannot link -fsanitize=fuzzer the script
# says why and exits 77 (CTest's SKIP_RETURN_CODE).
# A run starts from the committed seeds (tests/fuzz/corpus/HARNESS) and the inputs earlier runs kept
# (BUILD/corpus/HARNESS, where new ones go), with the dictionary tests/fuzz/dict/HARNESS.dict. A crash, sanitizer
# report, broken oracle, timeout or out-of-memory is saved in BUILD/crashes/HARNESS/ and the script exits 1 naming
# the file and the command that reproduces it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RADWALK_FUZZ_BUILD_DIR:-$root/build/fuzz}
cxx=${RADWALK_FUZZ_CXX:-clang++}
all_harnesses=(obj_mtl mtl ply stl gltf vtk matrix_market npz validate_patch)

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
}

# Exit 77 with a message unless clang++ links a libFuzzer program with ASan and UBSan.
require_libfuzzer() {
  if ! command -v "$cxx" >/dev/null 2>&1; then
    echo "fuzz: skipped: $cxx not found (install clang and libclang-rt-14-dev, as scripts/install-deps.sh does)"
    exit 77
  fi
  mkdir -p "$build/probe"
  printf '%s\n' '#include <cstddef>' '#include <cstdint>' \
    'extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }' >"$build/probe/probe.cpp"
  if ! "$cxx" -fsanitize=fuzzer,address,undefined "$build/probe/probe.cpp" -o "$build/probe/probe" \
      >"$build/probe/log" 2>&1; then
    echo "fuzz: skipped: $cxx cannot link -fsanitize=fuzzer,address,undefined (libFuzzer missing? on Debian:" \
         "apt-get install libclang-rt-14-dev):"
    sed 's/^/  /' "$build/probe/log" | head -5
    exit 77
  fi
}

build_tree() {
  require_libfuzzer
  local cc=${RADWALK_FUZZ_CC:-${cxx/clang++/clang}}
  local launcher=${RADWALK_FUZZ_LAUNCHER-}
  if [ -z "${RADWALK_FUZZ_LAUNCHER+set}" ] && command -v ccache >/dev/null 2>&1; then launcher=ccache; fi
  local start=$SECONDS
  echo "fuzz: configuring $build ($cxx${launcher:+ via $launcher})"
  cmake -S "$root" -B "$build" -DRADWALK_FUZZ=ON -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_C_COMPILER="$cc" ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log"; exit 1; }
  cmake --build "$build" --target radwalk_fuzzers -j"$(nproc)"
  echo "fuzz: fuzz tree built in $((SECONDS - start)) s"
}

# fuzz_one HARNESS SECONDS [FLAG...]
fuzz_one() {
  local h=$1 seconds=$2
  shift 2
  local exe="$build/tests/fuzz/fuzz_$h"
  if [ ! -x "$exe" ]; then
    echo "fuzz: $exe is missing: build the fuzz tree first (scripts/fuzz.sh --build-only)" >&2
    exit 1
  fi
  local corpus="$build/corpus/$h" crashes="$build/crashes/$h" seeds="$root/tests/fuzz/corpus/$h"
  mkdir -p "$corpus" "$crashes"
  # validate_patch reads OBJ + MTL and PLY: both dictionaries.
  local dict="$build/$h.dict"
  case $h in
    validate_patch) cat "$root/tests/fuzz/dict/obj_mtl.dict" "$root/tests/fuzz/dict/ply.dict" >"$dict" ;;
    *) cp "$root/tests/fuzz/dict/$h.dict" "$dict" ;;
  esac
  local symbolizer=/usr/lib/llvm-14/bin/llvm-symbolizer
  command -v llvm-symbolizer >/dev/null 2>&1 && symbolizer=$(command -v llvm-symbolizer)
  [ -x "$symbolizer" ] && export ASAN_SYMBOLIZER_PATH=$symbolizer
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  echo "fuzz: $h for $seconds s (corpus $corpus, seeds $seeds, findings in $crashes/)"
  local status=0
  # -error_exitcode=1: libFuzzer's default, 77, is CTest's skip code. One input must not run 25 s, allocate 512 MB
  # at once or grow the process beyond 2.5 GB.
  "$exe" "$corpus" "$seeds" -max_total_time="$seconds" -dict="$dict" -artifact_prefix="$crashes/" \
    -max_len=8192 -timeout=25 -rss_limit_mb=2560 -malloc_limit_mb=512 -error_exitcode=1 -timeout_exitcode=1 \
    -print_final_stats=1 "$@" >"$build/$h.log" 2>&1 || status=$?
  grep -E '^(#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|stat::peak_rss_mb|Done )' "$build/$h.log" || true
  if [ "$status" -ne 0 ]; then
    echo "fuzz: FINDING in $h (exit $status):"
    grep -m 5 -E 'fuzz oracle failed|runtime error|ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|^SUMMARY' \
      "$build/$h.log" | sed 's/^/  /' || true
    echo "fuzz: the end of $build/$h.log:"
    tail -n 40 "$build/$h.log"
    local found
    found=$(ls -t "$crashes" 2>/dev/null | head -n 1 || true)
    if [ -n "$found" ]; then
      echo "fuzz: reproducer $crashes/$found"
      echo "fuzz: reproduce with: $exe $crashes/$found"
      echo "fuzz: (or without clang: build/tests/fuzz/replay_$h $crashes/$found)"
    fi
    return 1
  fi
}

[ $# -ge 1 ] || usage
build_first=1
case $1 in
  --build-only) build_tree; exit 0 ;;
  --no-build) build_first=0; shift ;;
  -h|--help) usage ;;
esac
[ $# -ge 2 ] || usage
target=$1 seconds=$2
shift 2
if [ "$target" = all ]; then harnesses=("${all_harnesses[@]}"); else harnesses=("$target"); fi
for h in "${harnesses[@]}"; do
  [[ " ${all_harnesses[*]} " == *" $h "* ]] || { echo "fuzz: unknown harness '$h' (${all_harnesses[*]})" >&2; exit 2; }
done
if [ "$build_first" = 1 ]; then build_tree; else require_libfuzzer; fi
failed=0
for h in "${harnesses[@]}"; do fuzz_one "$h" "$seconds" "$@" || failed=1; done
exit "$failed"
