#!/usr/bin/env bash
# Exports, with the lamina CLI, for the validator test: the showcase scene (.gltf), which holds every
# example material; a sheet under a name whose buffer URI must be percent-encoded; the sheet of an
# image-textured example as .glb (the images in the BIN chunk); and the sheet of a tilted coat.
# Every example's own sheet would repeat the showcase's materials and fits (46 s of a CI run).
# Usage: export_examples.sh LAMINA SOURCE_DIR OUT_DIR [GLTF OPTIONS...]
# The sanitised build passes a small --bake-size and --fit-states 1: it looks for memory errors,
# which a 512-texel bake with all its fits only repeats, at 5 times the optimised build's cost.
set -euo pipefail
lamina=$1 source=$2 out=$3
shift 3
rm -rf "$out"
mkdir -p "$out"
"$lamina" gltf "$source/examples/showcase.json" -o "$out/showcase.gltf" "$@" >/dev/null
"$lamina" gltf "$source/examples/materials/car_paint.json" -o "$out/my scene#1%+.gltf" "$@" >/dev/null
"$lamina" gltf "$source/examples/materials/patina_map_copper.json" -o "$out/patina_map_copper.glb" "$@" >/dev/null
# A coat tilted by a texture: the one fallback with a clearcoat normal texture.
"$lamina" gltf "$source/tests/data/gltf/tilted_coat.json" -o "$out/tilted_coat.glb" "$@" >/dev/null
