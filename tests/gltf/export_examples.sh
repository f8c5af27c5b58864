#!/usr/bin/env bash
# Exports, with the lamina CLI, for the validator test: the showcase scene (.gltf), which holds every
# example material; a sheet under a name whose buffer URI must be percent-encoded; the sheet of an
# image-textured example as .glb (the images in the BIN chunk); and the sheet of a tilted coat.
# Every example's own sheet would repeat the showcase's materials and fits (46 s of a CI run).
# Usage: export_examples.sh LAMINA SOURCE_DIR OUT_DIR [--sheets-only] [GLTF OPTIONS...]
# The sanitised build passes --sheets-only, a small --bake-size and --fit-states 1: it looks for
# memory errors in the CLI's export, which the two sheets exercise; every material's export runs
# under it in the glTF unit tests, and the showcase's Khronos verdict is the optimised build's.
set -euo pipefail
lamina=$1 source=$2 out=$3
shift 3
whole=1
if [ "${1:-}" = "--sheets-only" ]; then
  whole=0
  shift
fi
rm -rf "$out"
mkdir -p "$out"
"$lamina" gltf "$source/examples/materials/car_paint.json" -o "$out/my scene#1%+.gltf" "$@" >/dev/null
if [ "$whole" = 1 ]; then
  "$lamina" gltf "$source/examples/showcase.json" -o "$out/showcase.gltf" "$@" >/dev/null
  "$lamina" gltf "$source/examples/materials/patina_map_copper.json" -o "$out/patina_map_copper.glb" "$@" >/dev/null
fi
# A coat tilted by a texture: the one fallback with a clearcoat normal texture.
"$lamina" gltf "$source/tests/data/gltf/tilted_coat.json" -o "$out/tilted_coat.glb" "$@" >/dev/null
