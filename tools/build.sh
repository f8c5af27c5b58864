#!/usr/bin/env bash
# Configures and builds one variant of lamina: `release` (optimised) or `asan` (AddressSanitizer
# and UndefinedBehaviorSanitizer). Usage: tools/build.sh [release|asan]
set -euo pipefail
cd "$(dirname "$0")/.."
variant=${1:-release}
case "$variant" in
  release) flags=(-DCMAKE_BUILD_TYPE=Release) ;;
  # clang, so that the same build also makes the libFuzzer programs of tests/fuzz.
  asan) flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DLAMINA_SANITIZE=ON -DLAMINA_FUZZ=ON
    -DCMAKE_CXX_COMPILER=clang++) ;;
  *) echo "usage: tools/build.sh [release|asan]" >&2; exit 2 ;;
esac
cmake -S . -B "build/$variant" -G Ninja "${flags[@]}" >/dev/null
cmake --build "build/$variant" -j "$(nproc)"
