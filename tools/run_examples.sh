#!/usr/bin/env bash
# The main job: install what is missing, build, then check and classify every bundled example.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh release
lamina=build/release/lamina
echo
echo "== lamina validate examples/materials"
$lamina validate examples/materials
echo
echo "== lamina classify examples/materials"
$lamina classify examples/materials
