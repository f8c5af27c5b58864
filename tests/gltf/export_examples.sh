#!/usr/bin/env bash
# Exports the showcase scene (.gltf), every example material's sample sheet (.glb), one sheet
# under a name whose buffer URI must be percent-encoded and the sheet of a tilted coat, with the
# lamina CLI, for the validator test. Usage: export_examples.sh LAMINA SOURCE_DIR OUT_DIR [--showcase-only] [GLTF OPTIONS...]
# The sanitised build passes --showcase-only, a small --bake-size and --fit-states 1: it looks for
# memory errors, which the sheets (the showcase's materials again) and a 512-texel bake with all its
# fits only repeat, at 5 times the optimised build's cost.
set -euo pipefail
lamina=$1 source=$2 out=$3
shift 3
sheets=1
if [ "${1:-}" = "--showcase-only" ]; then
  sheets=0
  shift
fi
rm -rf "$out"
mkdir -p "$out"
"$lamina" gltf "$source/examples/showcase.json" -o "$out/showcase.gltf" "$@" >/dev/null
"$lamina" gltf "$source/examples/materials/car_paint.json" -o "$out/my scene#1%+.gltf" "$@" >/dev/null
# A coat tilted by a texture: the one fallback with a clearcoat normal texture.
"$lamina" gltf "$source/tests/data/gltf/tilted_coat.json" -o "$out/tilted_coat.glb" "$@" >/dev/null
if [ "$sheets" = 1 ]; then
  for material in "$source"/examples/materials/*.json; do
    "$lamina" gltf "$material" -o "$out/$(basename "$material" .json).glb" "$@" >/dev/null
  done
fi
