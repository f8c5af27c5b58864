#!/usr/bin/env bash
# Counts, with callgrind, the instructions one query of the CPU evaluator takes (inclusive of
# everything it calls), for the benchmark's single lobe and two layered examples in both models,
# or for the material files given. Counts do not depend on the machine's load, unlike the times of
# tools/run_bench.sh: compare builds with them.
#   bash tools/count_instructions.sh [MATERIAL.json ...]
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "count_instructions: needs valgrind (apt install valgrind)" >&2; exit 2; }
bash tools/build.sh release >/dev/null
driver=build/release/tests/bench/lamina_query_driver
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
materials=("$@")
if ((${#materials[@]} == 0)); then
  # The benchmark's single Torrance-Sparrow lobe: the car paint's aluminium without its varnish.
  cat >"$work/single_lobe.json" <<'JSON'
{"format": 1, "materials": [{"name": "single_lobe", "surface": "@metal", "nodes": [
  {"id": "metal", "type": "substrate/conductor", "metal": "aluminium", "roughness_deg": 12.0}]}]}
JSON
  materials=("$work/single_lobe.json")
  # Each example in the default model, then in the seeds' (a copy with "model" set).
  for name in car_paint house_paint; do
    node -e '
      const fs = require("fs");
      const d = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
      d.materials[0].model = "weidlich_wilkie";
      fs.writeFileSync(process.argv[2], JSON.stringify(d));' \
      "examples/materials/$name.json" "$work/${name}_weidlich_wilkie.json"
    materials+=("examples/materials/$name.json" "$work/${name}_weidlich_wilkie.json")
  done
fi
queries=20000
printf '%-28s %10s %10s %10s\n' "instructions per query" eval eval_pdf sample
for m in "${materials[@]}"; do
  row=$(printf '%-28s' "$(basename "$m" .json)")
  for q in eval eval_pdf sample; do
    valgrind --tool=callgrind --toggle-collect="lamina::cpu::Evaluator::$q(*" \
      --callgrind-out-file="$work/out" "$driver" "$m" "$q" "$queries" >/dev/null 2>"$work/log" ||
      { cat "$work/log" >&2; exit 1; }
    row+=$(callgrind_annotate "$work/out" 2>/dev/null |
      awk -v n="$queries" '/PROGRAM TOTALS/ {gsub(",", "", $1); printf " %10.0f", $1 / n}')
  done
  echo "$row"
done
