#!/usr/bin/env bash
# Installs the built lamina into a temporary prefix, builds examples/api against it with
# find_package(lamina) and runs it on an example. Usage: check_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -x "$work/prefix/bin/lamina"
test -f "$work/prefix/include/lamina/graph/load.h"
test -f "$work/prefix/share/lamina/schema/material.schema.json"
# The image module is installed beside liblamina and loads (--version asks it for OpenImageIO's).
"$work/prefix/bin/lamina" --version | tee "$work/version.txt"
grep -q "OpenImageIO [0-9]" "$work/version.txt"
cmake -S "$source/examples/api" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
output=$("$work/consumer/lamina_api_example" "$source/examples/materials/car_paint.json")
echo "$output"
grep -q "^  f   = " <<<"$output"
grep -q "albedo at 45 deg" <<<"$output"
# An invalid file is a user mistake: exit 2 with the pointer.
set +e
"$work/consumer/lamina_api_example" "$source/tests/data/bad/ior_below_one.json" 2>"$work/err.txt"
code=$?
set -e
[ "$code" = 2 ]
grep -q "ior_below_one.json:/materials/0/nodes/1/ior:" "$work/err.txt"
