#!/usr/bin/env bash
# Builds lamina twice, optimised and with ASan+UBSan, and runs the whole test suite on each.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for variant in release asan; do
  echo "== $variant build"
  bash tools/build.sh "$variant"
  echo "== $variant tests"
  (cd "build/$variant" && ctest --output-on-failure -j "$(nproc)")
done
