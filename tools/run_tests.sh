#!/usr/bin/env bash
# Builds lamina twice, optimised (GCC) and with ASan+UBSan (clang), runs the whole test suite on
# each, then runs every fuzz target of the sanitised build for 10 seconds (tools/run_fuzz.sh; the CI budget
# of 30 minutes on 2 cores leaves that much: longer hunts run the script by hand).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
# intercept_tls_get_addr=0: LeakSanitizer (clang 14) crashed at exit scanning a block of dynamic TLS
# that a library of the image module (loaded at run time, graph/image_codec.h) had left behind.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for variant in release asan; do
  echo "== $variant build"
  bash tools/build.sh "$variant"
  echo "== $variant tests"
  (cd "build/$variant" && ctest --output-on-failure -j "$(nproc)")
done
echo "== fuzz"
bash tools/run_fuzz.sh 10 build/asan
