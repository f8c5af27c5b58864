#!/usr/bin/env bash
# Runs every libFuzzer program of tests/fuzz for a bounded time, one per core at a time, each from its seed corpus
# (tests/fuzz/seeds.txt) and its regression corpus, and prints executions and executions per
# second per target. Each program finds its dictionary itself (tests/fuzz/fuzz_main.cpp). Exits 1 on the first finding, after saying where the failing input is kept and
# how to add it to the regression corpus that the ordinary test suite replays.
#
# Usage: tools/run_fuzz.sh [SECONDS_PER_TARGET] [BUILD_DIR] [TARGET...]   (defaults: 30, build/asan, all)
# LAMINA_FUZZ_SEED fixes libFuzzer's random seed (default 1, so that a CI run of the same code walks
# the same inputs and a finding reproduces with the same command); 0 draws a new seed each run,
# for long hunts.
# The programs come from the asan build (tools/build.sh asan: clang, ASan, UBSan, libFuzzer).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
seed=${LAMINA_FUZZ_SEED:-1}
build=${2:-build/asan}
work=$(mktemp -d "${TMPDIR:-/tmp}/lamina-fuzz.XXXXXXXX")
trap 'rm -rf "$work"' EXIT

targets=$(ls "$build"/tests/fuzz/fuzz_* 2>/dev/null | sed 's|.*/fuzz_||' | sort)
shift $(($# < 2 ? $# : 2))
[ $# -gt 0 ] && targets="$*"
[ -n "$targets" ] || { echo "run_fuzz: no fuzz programs in $build/tests/fuzz (build with tools/build.sh asan)" >&2; exit 2; }

# Leak checks on; a slow or bloated input is a finding too (the limits of graph/limits.h keep every
# valid input far below these).
# intercept_tls_get_addr=0: LeakSanitizer (clang 14) crashed at exit scanning a block of dynamic TLS
# that a library of the image module (loaded at run time, graph/image_codec.h) had left behind.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# One target per core at a time; each writes its own log, and the reports follow in the targets' order.
fuzz_target() {
  local target=$1
  local seeds="$work/$target/seeds" corpus="$work/$target/corpus" artifacts="$work/$target/artifacts"
  mkdir -p "$seeds" "$corpus" "$artifacts"
  # Seeds: the files seeds.txt lists for this target, and every input that once failed.
  while read -r name folder extension; do
    [ "$name" = "$target" ] || continue
    for f in "$folder"/*"$extension"; do [ -f "$f" ] && cp "$f" "$seeds/"; done
  done < <(grep -v '^#' tests/fuzz/seeds.txt)
  [ -d "tests/fuzz/regressions/$target" ] && cp tests/fuzz/regressions/"$target"/* "$seeds/" 2>/dev/null || true
  if "$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" "$corpus" "$seeds" >"$work/$target.log" 2>&1; then
    echo 0 >"$work/$target.status"
  else
    echo 1 >"$work/$target.status"
  fi
}
cores=$(nproc)
for target in $targets; do
  while [ "$(jobs -rp | wc -l)" -ge "$cores" ]; do wait -n || true; done
  fuzz_target "$target" &
done
wait

status=0
for target in $targets; do
  corpus="$work/$target/corpus"
  artifacts="$work/$target/artifacts"
  log="$work/$target.log"
  if [ "$(cat "$work/$target.status" 2>/dev/null)" = 0 ]; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    printf 'fuzz %-12s %9s executions in %ss, %6s per second, %6s edges covered, %5s corpus files\n' \
      "$target" "$runs" "$seconds" "$rate" "${cov:-?}" "$(ls "$corpus" | wc -l)"
  else
    status=1
    echo "fuzz $target: FINDING" >&2
    grep -E 'ERROR|SUMMARY|what\(\)|terminate|Finding|deadly|timeout|out-of-memory' "$log" | head -20 >&2
    for a in "$artifacts"/*; do
      [ -f "$a" ] || continue
      keep="tests/fuzz/regressions/$target/$(sha1sum "$a" | cut -c1-16)"
      mkdir -p "tests/fuzz/regressions/$target"
      cp "$a" "$keep"
      echo "  the input is now $keep: fix the cause, then commit it (the test suite replays it)" >&2
    done
    tail -40 "$log" >&2
  fi
done
exit $status
