#!/usr/bin/env bash
# Prints the README's table of one layered model against the reference solver (`lamina compare`
# with its defaults, at uv 0,0) for every example and test material, one Markdown row each:
#   bash tools/compare_table.sh energy_conserving   # every material
#   bash tools/compare_table.sh weidlich_wilkie     # all but those written for the other model
# About four minutes on two cores. Columns: the largest relative albedo error over 0..89 degrees
# and where, the albedo at 0 degrees (model / reference) and the slices' RMS errors at 0, 30, 60
# and 80 degrees.
set -euo pipefail
cd "$(dirname "$0")/.."
model=${1:-}
case "$model" in
  energy_conserving | weidlich_wilkie) ;;
  *) echo "usage: tools/compare_table.sh energy_conserving|weidlich_wilkie" >&2; exit 2 ;;
esac
bash tools/build.sh release >/dev/null
lamina=build/release/lamina
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for file in examples/materials/*.json tests/data/physics/*.json; do
  name=$(basename "$file" .json)
  # Test materials written for the energy-conserving model stay out of the other model's table.
  [[ $model == weidlich_wilkie && $name == conserving_* ]] && continue
  kind=example
  [[ $file == tests/* ]] && kind=test
  "$lamina" compare "$file" --model "$model" --json >"$work/$name.compare.json"
  # The class as `lamina classify` reads the structure: its second column, up to the reason.
  "$lamina" classify "$file" | sed -nE '1{s/^[^ ]+ +//; s/  +.*//; p}' >"$work/$name.class"
  printf '%s %s\n' "$name" "$kind" >>"$work/list"
done
node - "$work" "$model" <<'JS'
const fs = require('fs');
const [work, model] = process.argv.slice(2);
const percent = (x) => (model === 'energy_conserving' ? `${(100 * x).toFixed(1)}%` : `${Math.round(100 * x)}%`);
const rgb = (v) => v.map((x) => x.toFixed(2)).join(' ');
for (const line of fs.readFileSync(`${work}/list`, 'utf8').trim().split('\n')) {
  const [name, kind] = line.split(' ');
  const c = JSON.parse(fs.readFileSync(`${work}/${name}.compare.json`, 'utf8'));
  const source = JSON.parse(fs.readFileSync(`${kind === 'test' ? 'tests/data/physics' : 'examples/materials'}/${name}.json`, 'utf8'));
  const textured = source.materials[0].nodes.some((n) => n.type.startsWith('texture/'));
  const label = name + (kind === 'test' ? ' (test)' : textured ? ' (uv 0,0)' : '');
  const cls = fs.readFileSync(`${work}/${name}.class`, 'utf8').trim();
  const normal = c.albedo.find((a) => a.theta_deg === 0);
  const slices = c.slices.map((s) => percent(s.rms_relative_error)).join(' / ');
  console.log(`| ${label} | ${cls} | ${percent(c.max_albedo_error)} (${c.max_albedo_error_theta_deg}) | ` +
    `${rgb(normal.model)} / ${rgb(normal.reference)} | ${slices} |`);
}
JS
