#!/usr/bin/env bash
# Builds the release variant and runs the benchmarks once: the CPU evaluator (lamina_bench) and
# the generated GLSL on Mesa llvmpipe (lamina_glsl_bench). Prints the cost of each layered
# material relative to a single Torrance-Sparrow lobe, every ratio from one run of its program.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh release >/dev/null
cpu=$(mktemp)
gpu=$(mktemp)
trap 'rm -f "$cpu" "$gpu"' EXIT
build/release/tests/bench/lamina_bench --benchmark_format=json --benchmark_min_time=0.5 >"$cpu"
build/release/tests/glsl/lamina_glsl_bench --benchmark_format=json >"$gpu" 2>/dev/null
node -e '
const fs = require("fs");
const cpu = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
// Nanoseconds per evaluation (a batch benchmark processes many per iteration).
const ns = {};
for (const b of cpu.benchmarks) ns[b.name] = 1e9 / b.items_per_second;
const rows = [["eval", "BM_eval_"], ["eval batch", "BM_eval_batch_"], ["eval_pdf b.", "BM_eval_pdf_batch_"], ["sample", "BM_sample_"]];
console.log("CPU evaluator, ratio to a single Torrance-Sparrow lobe (same run):");
for (const [label, prefix] of rows) {
  const base = ns[prefix + "single_lobe"];
  for (const name of ["car_paint_2_layers", "house_paint_3_layers"]) {
    const t = ns[prefix + name];
    console.log(`  ${label.padEnd(11)} ${name.padEnd(22)} ${(t / base).toFixed(2)}x   (${t.toFixed(1)} ns vs ${base.toFixed(1)} ns per evaluation, ${(1e3 / t).toFixed(2)} M/s on one core)`);
  }
}
console.log("The energy-conserving model, ratio to the same material under the Weidlich-Wilkie model and to a single lobe (same run):");
for (const [label, prefix] of rows) {
  const base = ns[prefix + "single_lobe"];
  for (const name of ["car_paint_2_layers", "house_paint_3_layers"]) {
    const t = ns[prefix + name + "_conserving"], faithful = ns[prefix + name];
    console.log(`  ${label.padEnd(11)} ${name.padEnd(22)} ${(t / faithful).toFixed(2)}x, ${(t / base).toFixed(2)}x   (${t.toFixed(1)} ns vs ${faithful.toFixed(1)} ns and ${base.toFixed(1)} ns per evaluation)`);
  }
}
console.log("Textured evaluation, ratio to the same stack untextured and to it under a checker, which resolves the stack at every point with the cheapest texture (same run, a new uv per evaluation):");
const flat = ns["BM_eval_textured_untextured_stack"], checker = ns["BM_eval_textured_checker"];
for (const name of ["checker", "noise_4_octaves", "voronoi", "glitter_select_of_4"]) {
  const t = ns["BM_eval_textured_" + name];
  if (!(t > 0)) throw new Error(`CPU benchmark BM_eval_textured_${name} did not run`);
  console.log(`  eval        ${name.padEnd(22)} ${(t / flat).toFixed(2)}x, ${(t / checker).toFixed(2)}x   (${t.toFixed(1)} ns vs ${flat.toFixed(1)} ns and ${checker.toFixed(1)} ns per evaluation)`);
}
const gpu = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
const ms = {};
for (const b of gpu.benchmarks) ms[b.name.split("/")[1]] = b.real_time;
console.log(`GLSL on llvmpipe (${gpu.context.host_name}), 1024 x 1024 sphere, ratio to a single lobe (same run), each example in the default model and in the Weidlich-Wilkie model:`);
for (const [label, prefix] of [["light only", "light_"], ["sphere", "sphere_"]]) {
  const base = ms[prefix + "single_lobe"];
  for (const name of ["car_paint", "house_paint", "car_paint_weidlich_wilkie", "house_paint_weidlich_wilkie"]) {
    const t = ms[prefix + name];
    if (!(t > 0)) throw new Error(`GLSL benchmark ${prefix + name} did not run`);
    console.log(`  ${label.padEnd(11)} ${name.padEnd(28)} ${(t / base).toFixed(2)}x   (${t.toFixed(1)} ms vs ${base.toFixed(1)} ms per frame)`);
  }
}' "$cpu" "$gpu"
