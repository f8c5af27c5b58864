#!/usr/bin/env bash
# Every kernel in nodes/kernels/*.glsl compiles as GLSL 330 core, 450 core and ES 3.00.
# For each target: the prelude the GLSL back end writes, the files in include order, and a
# fragment main() that calls every kernel once, validated by glslangValidator.
# Usage: glsl_kernels_check.sh <project source dir>
set -euo pipefail

src=${1:?usage: glsl_kernels_check.sh <project source dir>}
kernels="$src/nodes/kernels"
validator=$(command -v glslangValidator || true)
if [[ -z $validator ]]; then
  echo "glslangValidator not found (Debian: apt-get install glslang-tools)" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

main_body() {
  cat <<'GLSL'

in vec2 v_uv;
out vec4 frag_color;

void main() {
  float c = clamp(v_uv.x, 0.0f, 1.0f);
  float m = max(v_uv.y, LAMINA_MIN_SLOPE);
  vec3 w = normalize(vec3(v_uv, 1.0f));
  vec3 v = normalize(vec3(-v_uv.y, v_uv.x, 0.5f));
  vec3 s = vec3(0.0f);
  float f = 0.0f;
  // common
  f += lamina_sqr(c) + lamina_luminance(w) + lamina_safe_sqrt(c) + LAMINA_PI + LAMINA_INV_PI;
  // fresnel
  f += fresnel_dielectric(c, 1.5f) + fresnel_schlick(c, 0.04f) + lamina_rarer_side_cosine(c, 0.7f);
  f += lamina_fresnel_dielectric(1, c, 0.7f);
  s += fresnel_schlick_rgb(c, vec3(0.04f)) + conductor_f0(vec3(0.1f, 0.42f, 1.56f), vec3(3.8f, 2.5f, 1.9f));
  s += lamina_fresnel_conductor(2, c, vec3(0.1f, 0.42f, 1.56f), vec3(3.8f, 2.5f, 1.9f));
  s += fresnel_conductor(c, vec3(0.1f, 0.42f, 1.56f), vec3(3.8f, 2.5f, 1.9f));
  s += fresnel_lazanyi(c, vec3(0.1f, 0.42f, 1.56f), vec3(3.8f, 2.5f, 1.9f));
  // microfacet
  f += d_beckmann(c, m) + blinn_exponent(m) + d_blinn(c, m) + d_ggx(c, m) + d_microfacet(2, c, m);
  f += g_vcavity(c, w.z, v.z, 0.7f) + g1_smith_ggx(c, m) + g_smith_ggx(c, w.z, m);
  f += g_microfacet(0, c, w.z, v.z, 0.7f, m);
  s += torrance_sparrow(vec3(f), 1.0f, 0.5f, c, w.z);
  s += sample_microfacet_normal(1, m, v_uv);
  f += pdf_microfacet_normal(2, m, c);
  // diffuse
  s += lambert(vec3(0.5f)) + oren_nayar(w, v, vec3(0.3f, 0.4f, 0.1f), 0.34f) + sample_cosine(v_uv);
  f += pdf_cosine(c);
  // layer
  s += refract_down(w, 1.5f) + refract_up(v, 1.5f) + mirror_across_horizon(w);
  f += refraction_jacobian(c, w.z, 1.5f);
  s += tir_compensation(vec3(0.96f), 0.8f);
  s += absorption(vec3(0.6f, 1.0f, 1.0f), 0.5f, c, w.z);
  // texture
  f += checker_value(v_uv, vec2(8.0f)) + remap_value(c, 0.0f, 1.0f, -1.0f, 1.0f, true);
  s += srgb_to_linear(w) + srgb_from_linear(w);
  // procedural
  ivec3 cell = ivec3(0);
  vec4 cell_random = vec4(0.0f);
  f += lamina_hash_unit(lamina_hash3(uvec3(7u)).x) + lamina_perlin(w * 3.0f, 1u) + lamina_fbm(w, 4, 2.0f, 0.5f, 2u, true, c);
  f += lamina_marble(c, f, 0.5f, vec2(0.1f)) + lamina_sinc(c) + lamina_voronoi(w * 5.0f, c > 0.5f, 1.0f, 3u, cell).y + float(cell.x);
  s += lamina_tilted_normal(lamina_cell_randoms(cell, 3u, cell_random), m, 2) + cell_random.xyz;
  LaminaVoronoi cells = lamina_voronoi_cell(w * 4.0f, true, 0.9f, 5u, 3.0f, 0, c);
  s += cells.colour + cells.normal + vec3(cells.distances, cells.value) + lamina_space_point(v_uv, w, 1, 2.0f);
  f += lamina_noise_value(w, 2, 2.0f, 0.5f, 1u, false, 0.0f) + lamina_patina_weight(c, 0.5f, 0.1f);
  f += lamina_marble_value(w, 4.0f, v, 3.0f, 1.0f, 3, 2.0f, 0.5f, 9u, 0.01f) + lamina_space_footprint(c, 0);
  s += lamina_fade(w) + lamina_lattice_point(v) + vec3(lamina_gradient_dot(lamina_hash_cell(cell, 1u).y, w));
  // preview
  vec2 q = lamina_preview_disk(lamina_preview_subsample(v_uv, 3), vec2(640.0f, 480.0f));
  vec3 pn = lamina_preview_normal(q);
  if (lamina_preview_on_sphere(q)) s += lamina_preview_background();
  s.xy += lamina_preview_uv(pn) + vec2(lamina_preview_context(q, vec2(640.0f, 480.0f)).footprint);
  s += lamina_preview_local(LAMINA_PREVIEW_LIGHT, pn) + lamina_preview_local(LAMINA_PREVIEW_VIEW, pn);
  s += lamina_preview_light(w, v) + lamina_preview_sky_point(LAMINA_PREVIEW_SKY_POINTS - 1);
  s += lamina_preview_sky(lamina_preview_sky_weight(w, v, c), vec3(LAMINA_PREVIEW_AMBIENT));
  s += lamina_preview_mean(lamina_preview_display(w)) * LAMINA_PREVIEW_IRRADIANCE;
  f += float(LAMINA_PREVIEW_SUBSAMPLES);
  // stack
  vec3 lb = vec3(0.0f);
  vec3 vb = vec3(0.0f);
  vec3 carry = vec3(0.0f);
  bool inside = false;
  ivec4 texels = ivec4(0);
  f += lamina_slope(c, true) + lamina_effective_slope(m, 0.1f, true) + lamina_symmetric_dot(w, v, w);
  s += lamina_interface_eval(w, v, 1.5f, 0, 1, m, lb, vb, carry) + lb + vb + carry;
  s += lamina_conductor_eval(w, v, vec3(0.2f), vec3(3.0f), vec3(1.5f), 300.0f, 2, 2, m) + lamina_lambert_eval(w, v, vec3(0.5f));
  // flakes
  LaminaFlakes flakes = lamina_flakes(0.5f, vec3(0.9f), 0.1f, 0, m);
  LaminaFlakes coated = flakes;
  vec3 flake_x;
  coated.film = 3;
  coated.film_eta = vec3(1.6f);
  coated.film_depth = 240.0f;
  s += lamina_flake_glitter(w, v, flakes, 0.2f) + lamina_flake_glitter_and_depth(w, v, coated, 0.1f, flake_x);
  vec3 flake_q = lamina_flake_q_flakes(coated, 0.2f) + lamina_flake_q_boundary(flakes, 0.2f, 1.5f);
  s += lamina_flake_shade(w, v, flakes, 0.2f, vec3(0.5f), flake_q) + flake_q;
  f += lamina_flake_orientation(1, c, m) + lamina_flake_depth_share(c) + lamina_flake_lobe(w, v, 2, m);
  s += lamina_flake_depth(w, flakes, 0.2f) + lamina_flake_depth_factor(s);
  vec3 flake_r;
  vec3 flake_t;
  lamina_flake_optics(coated, c, flake_r, flake_t);
  s += lamina_flake_depth_through(w, coated, flake_t, 0.0f) + flake_r;
  vec3 flake_x0;
  vec3 flake_diffuse;
  vec3 flake_albedo;
  lamina_flake_paint_resolve(coated, vec3(0.5f), flake_x0, flake_diffuse, flake_albedo);
  s += lamina_flake_paint_eval(w, v, coated, flake_diffuse, flake_x0) + flake_albedo;
  s += lamina_flake_shade_through(flake_x0, vec3(0.5f), flake_q) + flake_x;
  f += lamina_flake_glitter_share(vec3(0.5f), flake_diffuse);
  s += lamina_fresnel_film(LAMINA_FRESNEL_FILM_RGB, c, vec3(1.4f), vec3(0.2f), vec3(3.0f), 300.0f);
  s += lamina_fresnel_base(LAMINA_FRESNEL_FILM_SPECTRAL, c, vec3(1.5f), vec3(0.0f), vec3(2.4f, 2.5f, 2.6f), 250.0f);
  s += lamina_selection_step(v, 1.5f, 0, vec3(0.1f), 0.5f, f);
  f += lamina_reflection_density(0, m, v, w) + lamina_folded_reflection_density(1, m, v, w);
  s += lamina_with_cosine(w, c);
  f += lamina_cos_critical(1.5f) + lamina_microfacet_lobe_pdf(0, m, v, w, 1.0f, w, 1.5f);
  f += lamina_diffuse_lobe_pdf(w, 1.0f, 1.5f);
  s += lamina_sample_microfacet_lobe(2, m, v, v_uv, 1.5f, inside) + lamina_sample_diffuse_lobe(v_uv, 1.5f);
  s += lamina_leave_or_spread(w, 1.5f, inside) + lamina_spread_source(w, 1.5f) + lamina_entry_normal(w);
  s.xy += lamina_image_uv(v_uv, 30.0f, vec2(2.0f), vec2(0.1f));
  f += float(lamina_positive_mod(-3, 4) + lamina_wrap_index(-2, 8, 2));
  s.xy += lamina_bilinear_texels(v_uv, 16, 8, 0, texels) + vec2(texels.xy);
  if (inside) f += 1.0f;
  // the composition: a layer over a mix of a conductor and a Lambert base
  LaminaContext ctx = lamina_context(v_uv);
  s.xy += ctx.uv;
  LaminaEntry entries[LAMINA_STACK];
  LaminaInputs inputs[LAMINA_STACK];
  for (int i = 0; i < LAMINA_STACK; ++i) {
    entries[i].kind = i == 0 ? LAMINA_LAYER : i == 1 ? LAMINA_MIX : LAMINA_SUBSTRATE;
    entries[i].model = i == 2 ? LAMINA_SUBSTRATE_CONDUCTOR : LAMINA_SUBSTRATE_LAMBERT;
    entries[i].medium = LAMINA_MEDIUM_ABSORBING;
    entries[i].distribution = 0;
    entries[i].fresnel = 0;
    entries[i].degrees = 1;
    entries[i].parent = i == 0 ? -1 : i == 1 ? 0 : 1;
    entries[i].side = i == 3 ? 1 : 0;
    entries[i].first = i == 0 ? 1 : i == 1 ? 2 : -1;
    entries[i].second = i == 1 ? 3 : -1;
    inputs[i].colour0 = vec3(0.5f);
    inputs[i].colour1 = vec3(3.0f);
    inputs[i].colour2 = vec3(0.1f);
    inputs[i].scalars = vec4(1.5f, 10.0f, 0.5f, 0.0f);
    inputs[i].normal = i == 2 ? w : vec3(0.0f, 0.0f, 1.0f);
  }
  LaminaParams params[LAMINA_STACK];
  lamina_stack_resolve(LAMINA_STACK, entries, inputs, 1.0f, true, int(c > 0.5f), params);
  float weight[LAMINA_STACK];
  vec3 sv[LAMINA_STACK];
  bool valid[LAMINA_STACK];
  lamina_stack_select(LAMINA_STACK, entries, params, v, weight, sv, valid);
  int chosen = lamina_stack_choose(LAMINA_STACK, weight, c);
  s += lamina_stack_eval(LAMINA_STACK, entries, params, w, v) + lamina_stack_sample(LAMINA_STACK, entries, params, sv, chosen, v_uv);
  s += lamina_substrate_eval(entries[2], params[2], w, v);
  f += lamina_flake_share(entries[2], params[2]);
  s += lamina_entry_flakes(entries[2], params[2]).colour;
  if (lamina_is_flake_paint(entries[2])) f += 1.0f;
  vec3 tx = vec3(0.0f);
  vec3 ty = vec3(0.0f);
  lamina_entry_tangents(params[2].normal, tx, ty);
  s += tx + ty + lamina_from_entry(params[2], lamina_to_entry(params[2], w));
  int above[LAMINA_STACK];
  for (int i = 0; i < LAMINA_STACK; ++i) above[i] = lamina_frame_above(entries, above, i);
  s += lamina_to_frame(params, above[2], w) + lamina_from_frame(params, -1, w);
  s.xy += lamina_tilt_weight(w, v, vec2(0.5f));
  if (lamina_traps_light(entries, params, 0)) f += 1.0f;
  f += lamina_stack_pdf(LAMINA_STACK, entries, params, weight, sv, valid, w, v);
  // energy
  f += lamina_dielectric_albedo(0, 0, c, m, 1.5f) + lamina_albedo_node_eta(1) + lamina_albedo_node_slope(1);
  f += lamina_boundary_reflection(w, v, 1.5f, 1, 0, m);
  f += lamina_albedo_node_cosine(1, 0.7f) + lamina_albedo_axis_cosine(c, 0.7f) + oren_nayar_uniform(0.3f);
  f += lamina_albedo_grid_eta(0.5f) + lamina_albedo_grid_slope(0.5f) + lamina_albedo_grid_cosine(0.5f, 0.7f);
  float multiple = 0.0f;
  f += lamina_boundary_energy(2, 1, lamina_albedo_grid_xy(m, 1.5f), c, 1.5f, multiple) + multiple;
  f += lamina_albedo_interpolate(lamina_albedo_point(0, 0, c, m, 0.7f), LAMINA_ALBEDO_MULTIPLE_COLUMN);
  s += one_way_absorption(vec3(0.1f), 0.5f, c) + lamina_diffuse_profile(entries, params, 0, c);
  float reflected = 0.0f;
  s += lamina_layer_passage(entries[0], params[0], c, 0.5f, multiple, reflected) + reflected;
  vec3 echo = vec3(0.0f);
  float share_in = 0.0f;
  float keep = 0.0f;
  s += lamina_trapped_light(entries, params, 0, c, c, 0.5f, echo, share_in, keep) + echo + keep;
  s += lamina_trap_gain(entries, params, 0, 0.5f) + lamina_trap_ramp(entries, params, 0);
  s += lamina_trap_series(entries, params, 0, 0.9f) + vec3(lamina_trap_angles(entries, params, 0), 0.0f);
  vec3 a_all = vec3(0.0f);
  s += lamina_arrival_reflected(entries, params, 0, c, a_all, share_in) + a_all;
  f += lamina_ramp_mean(1, 0.2f, 0.1f, m);
  f += lamina_arrival_y(entries, params, 0);
  f += lamina_arrival_cosine(c, 0.5f, 1.5f, m) + lamina_edge_ramp(0, 0, vec2(1.0f), vec2(2.0f), 0.7f).y;
  s += lamina_guide_entry_keep(entries, params, 0, 1, 1.3f);
  f += lamina_exit_reflected(entries, params, 0, c).y + lamina_exit_cut(entries, params, 0).y;
  f += lamina_spread_kept(entries, params, 0, c, share_in) + lamina_spread_own(entries, params, 0);
  s += lamina_forward_coefficient(entries, params, 0) + lamina_forward_part(s, s, s, w, v);
  LaminaGuide guide = lamina_guide(entries, params, 1, 1.3f);
  f += lamina_beyond_edge_angle(0.5f, c, m);
  s += lamina_guide_keep(entries, 1, guide, c) + lamina_gap_series_kept(s, s, c);
  float whole = 0.0f;
  f += lamina_conductor_cone_share(1, lamina_albedo_grid_xy(m, 1.5f), lamina_cone_etas(lamina_albedo_grid_xy(m, 1.5f)), c,
                                   whole) + whole;
  f += lamina_albedo_point_at(0, 0, vec2(1.0f), c, 0.7f).fx;
  s += lamina_stack_eval_conserving(LAMINA_STACK, entries, params, w, v);
  // a blend of two parts, each the stack above (LAMINA_PARTS 2, LAMINA_BLEND 3)
  LaminaEntry blend[LAMINA_BLEND];
  LaminaInputs blend_inputs[LAMINA_BLEND];
  for (int i = 0; i < LAMINA_BLEND; ++i) {
    blend[i] = entries[i == 0 ? 1 : 0];
    blend[i].parent = i == 0 ? -1 : 0;
    blend[i].side = i == 2 ? 1 : 0;
    blend_inputs[i] = inputs[i];
  }
  float blend_share[LAMINA_BLEND];
  lamina_blend_shares(LAMINA_BLEND, blend, blend_inputs, blend_share);
  int part_counts[LAMINA_PARTS] = int[LAMINA_PARTS](LAMINA_STACK, LAMINA_STACK);
  float part_share[LAMINA_PARTS] = float[LAMINA_PARTS](blend_share[1], blend_share[2]);
  LaminaEntry part_entries[LAMINA_PARTS * LAMINA_STACK];
  LaminaInputs part_inputs[LAMINA_PARTS * LAMINA_STACK];
  for (int i = 0; i < LAMINA_PARTS * LAMINA_STACK; ++i) {
    part_entries[i] = entries[i % LAMINA_STACK];
    part_inputs[i] = inputs[i % LAMINA_STACK];
  }
  LaminaPoint point;
  lamina_blend_resolve(LAMINA_PARTS, part_counts, part_entries, part_inputs, part_share, true, 1, point);
  s += lamina_blend_eval(LAMINA_PARTS, part_counts, part_entries, point, 1, w, v);
  LaminaPartsSelection selection;
  lamina_blend_select(LAMINA_PARTS, part_counts, part_entries, point, v, selection);
  f += lamina_blend_pdf(LAMINA_PARTS, part_counts, part_entries, point, selection, w, v);
  int part_chosen = lamina_blend_choose(LAMINA_PARTS, part_counts, selection, c);
  s += lamina_blend_sample(part_counts, part_entries, point, selection, part_chosen, v_uv);
  if (lamina_is_lobe(entries[0]) && lamina_is_microfacet_lobe(entries[2])) f += 1.0f;
  frag_color = vec4(s, f);
}
GLSL
}

status=0
for target in 330 450 es300; do
  shader="$work/kernels_$target.frag"
  {
    case $target in
      330) echo "#version 330 core" ;;
      450) echo "#version 450 core" ;;
      es300) printf '%s\n' "#version 300 es" "precision highp float;" "precision highp int;" ;;
    esac
    # The macros the back end defines: the lengths of the stack's arrays, the film's Fresnel terms and
    # whether a base may fluoresce (common.glsl defines the others).
    echo "#define LAMINA_STACK 4"
    echo "#define LAMINA_PARTS 2"
    echo "#define LAMINA_BLEND 3"
    echo "#define LAMINA_FILM_FRESNEL lamina_fresnel_film"
    echo "#define LAMINA_FLAKE_FILM lamina_fresnel_film"
    echo "#define LAMINA_FLUORESCENCE true"
    # and the dielectric albedo table's reader (energy.glsl): a texture of every combination.
    echo "uniform highp usampler2D lamina_dielectric_albedo_table;"
    etas=$(sed -n 's/^const int LAMINA_ALBEDO_ETAS = \([0-9]*\);.*/\1/p' "$kernels/albedo_grid.glsl")
    echo "const int LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[6] = int[6](0, $etas, $((2 * etas)), $((3 * etas)), $((4 * etas)), $((5 * etas)));"
    echo "float lamina_albedo_texel(int x, int y) {"
    echo "  return float(texelFetch(lamina_dielectric_albedo_table, ivec2(x, y), 0).r);"
    echo "}"
    # The files in the order kernels.h includes them, the one list of kernel files.
    for f in $(sed -n 's|^#include "nodes/kernels/\(.*\.glsl\)"$|\1|p' "$kernels/kernels.h"); do
      cat "$kernels/$f"
    done
    main_body
  } >"$shader"
  if "$validator" "$shader" >"$work/log" 2>&1; then
    echo "ok: GLSL $target"
  else
    echo "FAILED: GLSL $target" >&2
    cat "$work/log" >&2
    status=1
  fi
done
exit $status
