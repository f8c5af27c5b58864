#!/usr/bin/env bash
# The main job: install what is missing, build, then check, classify, measure, plot and compile to
# GLSL every bundled example, export the showcase scene to glTF with its fallback fit report, path
# trace the showcase and the fluorescence scene, and preview every example.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh release
lamina=build/release/lamina
echo
echo "== lamina validate examples"
$lamina validate examples
echo
echo "== lamina classify examples/materials"
$lamina classify examples/materials
echo
echo "== lamina albedo: directional albedo (R G B) of every example at theta 0, 60 and 85 degrees"
printf '%-24s %-26s %-26s %s\n' material "0 deg" "60 deg" "85 deg"
for file in examples/materials/*.json; do
  row=$(printf '%-24s' "$(basename "$file" .json)")
  for theta in 0 60 85; do
    values=$($lamina albedo "$file" --theta "$theta" | sed 's/^albedo = //')
    row+=$(printf ' %-26s' "$(printf '%.3f ' $values)")
  done
  echo "$row"
done
echo
echo "== lamina reference: the slab's true directional albedo at 30 deg (Monte Carlo, 65536 walks) beside the model's"
printf '%-24s %-26s %s\n' material "model" "reference (+- standard error)"
for file in examples/materials/*.json; do
  model=$($lamina albedo "$file" --theta 30 | sed 's/^albedo = //')
  # The solver walks flat layers: a material whose textures tilt a layer at uv (0, 0) is refused,
  # and the table says why instead of stopping.
  if out=$($lamina reference "$file" --albedo --theta 30 2>&1); then
    reference=$(echo "$out" | sed 's/^albedo = //; s/ (standard error.*//')
  else
    reference="not run: ${out#*.json: }"
  fi
  printf '%-24s %-26s %s\n' "$(basename "$file" .json)" "$(printf '%.3f ' $model)" "$reference"
done
echo
echo "== lamina eval: f (R G B, 1/sr, no cosine) and pdf of every example, light 30 deg off the normal, view 45 deg on the other side"
for file in examples/materials/*.json; do
  printf '%-24s %s\n' "$(basename "$file" .json)" "$($lamina eval "$file" --wi 0.5,0,0.8660254 --wo -0.7071068,0,0.7071068)"
done
echo
plots=build/plots
mkdir -p "$plots"
echo "== lamina plot: BRDF slices and a lit sphere of every example, in $plots/"
for file in examples/materials/*.json; do
  $lamina plot "$file" -o "$plots/$(basename "$file" .json).png"
done
ls "$plots"
echo
glsl=build/glsl
mkdir -p "$glsl"
echo "== lamina glsl: every example as GLSL 330, 450 and ES 3.00 sphere shaders in $glsl/, checked by glslangValidator"
for file in examples/materials/*.json; do
  name=$(basename "$file" .json)
  row=$(printf '%-24s' "$name")
  for target in 330 450 es300; do
    $lamina glsl "$file" --target "$target" --shader sphere -o "$glsl/$name.$target.frag"
    glslangValidator -S frag "$glsl/$name.$target.frag" >/dev/null
    row+=" $target ok"
  done
  echo "$row  ($(wc -l <"$glsl/$name.330.frag") lines)"
done
echo
gltf=build/gltf
mkdir -p "$gltf"
echo "== lamina gltf: examples/showcase.json to $gltf/showcase.glb, with the fitted fallback of every material"
$lamina gltf examples/showcase.json -o "$gltf/showcase.glb" --report
node tests/gltf/validate_gltf.mjs "$gltf/showcase.glb"
echo
echo "== lamina import: $gltf/showcase.glb back to lamina materials in $gltf/showcase_import/"
$lamina import "$gltf/showcase.glb" -o "$gltf/showcase_import/materials.json" --force
echo
render=build/render
mkdir -p "$render"
echo "== lamina render: examples/showcase.json path traced to $render/showcase.png (480 x 320, 16 samples per pixel)"
$lamina render examples/showcase.json -o "$render/showcase.png" --width 480 --spp 16 --stats

echo "== lamina render: examples/fluorescent_green_light.json, the fluorescent card beside its plain twin under green light, to $render/fluorescent_green_light.png"
$lamina render examples/fluorescent_green_light.json -o "$render/fluorescent_green_light.png" --width 480 --spp 16
echo
echo "== lamina preview: every example on a sphere in the studio, side by side, in $render/examples.png"
$lamina preview examples/materials --compare -o "$render/examples.png" --size 128 --spp 24
