#!/usr/bin/env bash
# The test suite, from a fresh Debian 12 machine: install what is missing, build, run every default test
# (ctest -LE slow; the [slow] cases run with: ctest --test-dir build -L slow).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
ctest --test-dir build -LE slow --output-on-failure -j"$(nproc)"
