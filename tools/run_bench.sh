#!/usr/bin/env bash
# Builds the release variant and runs the evaluator benchmarks once, then prints the cost of each
# layered material relative to a single Torrance-Sparrow lobe, all from the same run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh release >/dev/null
out=$(mktemp)
trap 'rm -f "$out"' EXIT
build/release/tests/bench/lamina_bench --benchmark_format=json --benchmark_min_time=0.5 >"$out"
node -e '
const report = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
// Nanoseconds per evaluation (a batch benchmark processes many per iteration).
const ns = {};
for (const b of report.benchmarks) ns[b.name] = 1e9 / b.items_per_second;
const rows = [["eval", "BM_eval_"], ["eval batch", "BM_eval_batch_"], ["sample", "BM_sample_"]];
console.log("ratio to a single Torrance-Sparrow lobe (same run):");
for (const [label, prefix] of rows) {
  const base = ns[prefix + "single_lobe"];
  for (const name of ["car_paint_2_layers", "house_paint_3_layers"]) {
    const t = ns[prefix + name];
    console.log(`  ${label.padEnd(11)} ${name.padEnd(22)} ${(t / base).toFixed(2)}x   (${t.toFixed(1)} ns vs ${base.toFixed(1)} ns per evaluation, ${(1e3 / t).toFixed(2)} M/s on one core)`);
  }
}' "$out"
