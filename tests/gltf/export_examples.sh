#!/usr/bin/env bash
# Exports the showcase scene (.glb and .gltf), every example material's sample sheet (.glb) and one
# sheet under a name whose buffer URI must be percent-encoded, with the lamina CLI, for the
# validator test. Usage: export_examples.sh LAMINA SOURCE_DIR OUT_DIR
set -euo pipefail
lamina=$1 source=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
"$lamina" gltf "$source/examples/showcase.json" -o "$out/showcase.glb" >/dev/null
"$lamina" gltf "$source/examples/showcase.json" -o "$out/showcase.gltf" >/dev/null
"$lamina" gltf "$source/examples/materials/car_paint.json" -o "$out/my scene#1%+.gltf" >/dev/null
for material in "$source"/examples/materials/*.json; do
  "$lamina" gltf "$material" -o "$out/$(basename "$material" .json).glb" >/dev/null
done
