// lamina kernels: the energy a rough dielectric boundary reflects, from a table, and what the
// energy-conserving composition (stack.glsl) builds from it.
//
// E(mu) is the directional albedo of a boundary's reflection lobe, the integral over the upper
// hemisphere of lamina_boundary_reflection times cos_l, for a view of cosine mu; 1 - E(mu) is then
// the energy the boundary passes on to the layer below (or loses to the facets' multiple
// scattering, which in a dielectric mostly transmits). It depends on the distribution, the Fresnel
// term, the slope m and the relative index eta, and has no closed form, so it is tabulated:
// The table holds round(65535 E) on a grid of (eta, m, mu) for each combination of distribution and
// Fresnel term (LAMINA_ALBEDO_COMBOS, lamina_albedo_combo), as an image of
// LAMINA_ALBEDO_TABLE_WIDTH columns (albedo_grid.glsl). The numbers are computed from these kernels
// by graph/cpu/energy_table.cpp (a test regenerates them with LAMINA_UPDATE_TABLES=1 and checks them
// otherwise) and stored in nodes/kernels/dielectric_albedo.inc. Each back end defines, before
// including this file, LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW (the row where each combination starts,
// -1 if absent) and lamina_albedo_texel(x, y), the integer at column x of row y: C++ reads its
// array of every combination (kernels.h), GLSL a texture of the combinations a module's materials
// use, holding the same integers.

// A boundary's reflection in the energy-conserving composition: Torrance-Sparrow, F D G / (4 cos_l
// cos_v) with F at the symmetric V.H, and Smith's masking-shadowing G1(l) G1(v) for every
// distribution (Walter et al. 2007, eq. 23, with lamina_smith_g1), the masking of the microsurface
// the reference solver walks. (The Weidlich-Wilkie model's Beckmann and Blinn boundaries take the
// V-cavity term, which near grazing shadows less and reflects up to half again as much.)
LAMINA_FN float lamina_boundary_reflection(vec3 l, vec3 v, float eta, int distribution, int fresnel, float m) {
  if (l.z <= 0.0f || v.z <= 0.0f) return 0.0f;
  vec3 h = normalize(l + v);
  float v_dot_h = lamina_symmetric_dot(l, v, h);
  if (v_dot_h <= 0.0f) return 0.0f;
  float g = lamina_smith_g1(distribution, l.z, m) * lamina_smith_g1(distribution, v.z, m);
  float f = lamina_fresnel_dielectric(fresnel, v_dot_h, eta);
  return torrance_sparrow(vec3(f), d_microfacet_h(distribution, h, m), g, l.z, v.z).x;
}

// The entry at eta node i, slope node j, cosine node k of the combination starting at row `first`.
LAMINA_FN float lamina_albedo_entry(int first, int i, int j, int k) {
  return lamina_albedo_texel(j * LAMINA_ALBEDO_COSINES + k, first + i) * (1.0f / 65535.0f);
}

// E(mu) of a dielectric boundary: the table interpolated trilinearly in the grid's (x, m, z), every argument
// clamped to the grid. 1 for a combination the module has no table for (it cannot happen: the back
// ends emit every combination their materials use), which the conserving composition reads as a
// boundary that lets nothing through.
LAMINA_FN float lamina_dielectric_albedo(int distribution, int fresnel, float mu, float m, float eta) {
  int first = LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[lamina_albedo_combo(distribution, fresnel)];
  if (first < 0) return 1.0f;
  float s = 0.5f * log2(clamp(eta, 0.25f, 4.0f));
  float x = clamp((sign(s) * sqrt(abs(s)) + 1.0f) * 0.5f * float(LAMINA_ALBEDO_ETAS - 1), 0.0f,
                  float(LAMINA_ALBEDO_ETAS - 1));
  float y = clamp(m * float(LAMINA_ALBEDO_SLOPES - 1), 0.0f, float(LAMINA_ALBEDO_SLOPES - 1));
  float z = lamina_albedo_axis_cosine(mu, clamp(eta, 0.25f, 4.0f)) * float(LAMINA_ALBEDO_COSINES - 1);
  int i = min(int(x), LAMINA_ALBEDO_ETAS - 2);
  int j = min(int(y), LAMINA_ALBEDO_SLOPES - 2);
  int k = min(int(z), LAMINA_ALBEDO_COSINES - 2);
  float fx = x - float(i);
  float fy = y - float(j);
  float fz = z - float(k);
  float e00 = mix(lamina_albedo_entry(first, i, j, k), lamina_albedo_entry(first, i, j, k + 1), fz);
  float e01 = mix(lamina_albedo_entry(first, i, j + 1, k), lamina_albedo_entry(first, i, j + 1, k + 1), fz);
  float e10 = mix(lamina_albedo_entry(first, i + 1, j, k), lamina_albedo_entry(first, i + 1, j, k + 1), fz);
  float e11 = mix(lamina_albedo_entry(first, i + 1, j + 1, k), lamina_albedo_entry(first, i + 1, j + 1, k + 1), fz);
  return clamp(mix(mix(e00, e01, fy), mix(e10, e11, fy), fx), 0.0f, 1.0f);
}
