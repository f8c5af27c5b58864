// lamina kernels: the energy a rough dielectric boundary reflects, from a table, and what the
// energy-conserving composition (stack.glsl) builds from it.
//
// E(mu) is the directional albedo of a boundary's reflection lobe, the integral over the upper
// hemisphere of lamina_boundary_reflection times cos_l, for a view of cosine mu: what its facets
// reflect once. The boundary itself, the Smith microsurface the reference solver walks, reflects
// more: light its facets send toward other facets scatters again, and near grazing incidence much
// of it leaves above (Heitz, Hanika, d'Eon and Dachsbacher 2016). M(mu) is that surplus: the
// microsurface's whole reflection, E_hc(mu) + E_ms(mu), minus E(mu), where E_hc is its single
// scattering (lamina_boundary_reflection with height-correlated masking, by quadrature) and E_ms
// what leaves after two events or more (by random walks; graph/cpu/energy_table.h). The
// energy-conserving composition (stack.glsl) passes 1 - E(mu) - M(mu) on to the layer below and
// reflects M by raising the boundary's own lobe: f(l, v) (1 + b(l) b(v)), b(mu) >= 0 tabulated
// (block B) so that the raised lobe reflects E(mu) + M(mu) at every node of the grid: b(mu) int f(l,
// v) b(v) cos_v dv = M(mu), solved for every run of the cosine axis at once by a symmetric scaling
// iteration with b interpolated as the composition reads it (graph/cpu/energy_table.h). This is the
// scaling form of multiple-scattering compensation (as in Turquin 2019, which raises a lobe by its
// missing energy over its albedo, M / E), made symmetric by a product, so that it is reciprocal; for
// a narrow lobe b is near sqrt(M / E). A min of the two directions' M / E, used first, is bounded
// pointwise but gives a grazing view's lobe, which also reaches less grazing exits of smaller gain,
// only half its M (an 8-degree GGX boundary of index 1.45 reflected 0.296 at 89 degrees where the
// microsurface's walks give 0.316); the geometric mean of the two keeps more but reflected up to
// 1.0014 over a white base where a rough lobe reaches exits of larger gain. Between the nodes the
// raised lobe reflects at most 0.001 more than E + M as interpolated where eta >= 1.1, 0.05 where eta
// < 1, across the moving edge of the cone (energy_table_test.cpp).
// Multiply-scattered light leaves a rough dielectric near its single-scattering lobe, forward, not
// back toward the light: the separable lobe M(l) M(v) / N of Kulla and Conty 2017, tried first, put
// light on the side of the light where the reference has none (RMS errors of 140% to 3000% in
// lamina compare's slices at 80 degrees, where this form has 2% to 5%). E, M and b depend on the
// distribution, the Fresnel term, the slope m and the relative index eta, and have no closed form,
// so they are tabulated: the table holds round(65535 E), rounded up and raised so that its
// interpolation bounds E between the nodes too (graph/cpu/energy_table.h), round(65535 M), and b
// (block B) on a grid of (eta, m, mu) for each combination of distribution and Fresnel term
// (LAMINA_ALBEDO_COMBOS, lamina_albedo_combo), as an image of
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

// Where a boundary's (mu, m, eta) falls on the table's grid: the first row of its combination (-1
// if the back end has none), and on each axis the node below it and the fraction beyond.
struct LaminaAlbedoPoint {
  int first;
  int i;
  int j;
  int k;
  float fx;
  float fy;
  float fz;
};

// The grid coordinates (x, y) of a boundary's relative index eta and slope m, clamped to the grid.
// A shading point fixes them for each of its boundaries, so the composition computes them once per
// entry (LaminaParams.grid) and only the cosine's at each lookup.
LAMINA_FN vec2 lamina_albedo_grid_xy(float m, float eta) {
  float s = 0.5f * log2(clamp(eta, 0.25f, 4.0f));
  float x = clamp((sign(s) * sqrt(abs(s)) + 1.0f) * 0.5f * float(LAMINA_ALBEDO_ETAS - 1), 0.0f,
                  float(LAMINA_ALBEDO_ETAS - 1));
  float y = pow(clamp(m, 0.0f, 1.0f), 1.0f / 3.0f) * float(LAMINA_ALBEDO_SLOPES - 1);
  return vec2(x, y);
}

// The grid point of a view of cosine mu on a boundary of grid coordinates xy
// (lamina_albedo_grid_xy of its slope and of eta), every argument clamped to the grid.
LAMINA_FN LaminaAlbedoPoint lamina_albedo_point_at(int distribution, int fresnel, vec2 xy, float mu, float eta) {
  LaminaAlbedoPoint p;
  p.first = LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[lamina_albedo_combo(distribution, fresnel)];
  float x = xy.x;
  float y = xy.y;
  float z = sqrt(lamina_albedo_axis_cosine(mu, clamp(eta, 0.25f, 4.0f))) * float(LAMINA_ALBEDO_COSINES - 1);
  p.i = min(int(x), LAMINA_ALBEDO_ETAS - 2);
  p.j = min(int(y), LAMINA_ALBEDO_SLOPES - 2);
  p.k = min(int(z), LAMINA_ALBEDO_COSINES - 2);
  p.fx = x - float(p.i);
  p.fy = y - float(p.j);
  p.fz = z - float(p.k);
  return p;
}

LAMINA_FN LaminaAlbedoPoint lamina_albedo_point(int distribution, int fresnel, float mu, float m, float eta) {
  return lamina_albedo_point_at(distribution, fresnel, lamina_albedo_grid_xy(m, eta), mu, eta);
}

// The entry at eta node i, slope node j, cosine node k of the block starting at column `block` of
// the combination starting at row `first`.
LAMINA_FN float lamina_albedo_entry(int first, int block, int i, int j, int k) {
  return lamina_albedo_texel(block + j * LAMINA_ALBEDO_COSINES + k, first + i) * (1.0f / 65535.0f);
}

// A block (E or M) at a grid point, interpolated trilinearly in the grid's (x, y, w).
LAMINA_FN float lamina_albedo_interpolate(LAMINA_IN(LaminaAlbedoPoint) p, int block) {
  float e00 = mix(lamina_albedo_entry(p.first, block, p.i, p.j, p.k),
                  lamina_albedo_entry(p.first, block, p.i, p.j, p.k + 1), p.fz);
  float e01 = mix(lamina_albedo_entry(p.first, block, p.i, p.j + 1, p.k),
                  lamina_albedo_entry(p.first, block, p.i, p.j + 1, p.k + 1), p.fz);
  float e10 = mix(lamina_albedo_entry(p.first, block, p.i + 1, p.j, p.k),
                  lamina_albedo_entry(p.first, block, p.i + 1, p.j, p.k + 1), p.fz);
  float e11 = mix(lamina_albedo_entry(p.first, block, p.i + 1, p.j + 1, p.k),
                  lamina_albedo_entry(p.first, block, p.i + 1, p.j + 1, p.k + 1), p.fz);
  return clamp(mix(mix(e00, e01, p.fy), mix(e10, e11, p.fy), p.fx), 0.0f, 1.0f);
}

// E(mu) of a dielectric boundary. 1 for a combination the module has no table for (it cannot
// happen: the back ends emit every combination their materials use), which the conserving
// composition reads as a boundary that lets nothing through.
LAMINA_FN float lamina_dielectric_albedo(int distribution, int fresnel, float mu, float m, float eta) {
  LaminaAlbedoPoint p = lamina_albedo_point(distribution, fresnel, mu, m, eta);
  if (p.first < 0) return 1.0f;
  return lamina_albedo_interpolate(p, 0);
}

// All the energy a boundary of grid coordinates xy (lamina_albedo_grid_xy of its slope and eta)
// reflects at mu, E(mu) + M(mu); multiple receives M(mu) alone. (The table keeps E + M <= 1 at every
// node, so interpolated they stay within 1.)
LAMINA_FN float lamina_boundary_energy_at(LAMINA_IN(LaminaAlbedoPoint) p, LAMINA_OUT(float) multiple) {
  multiple = 0.0f;
  if (p.first < 0) return 1.0f;
  multiple = lamina_albedo_interpolate(p, LAMINA_ALBEDO_MULTIPLE_COLUMN);
  return min(lamina_albedo_interpolate(p, 0) + multiple, 1.0f);
}
LAMINA_FN float lamina_boundary_energy(int distribution, int fresnel, vec2 xy, float mu, float eta,
                                       LAMINA_OUT(float) multiple) {
  return lamina_boundary_energy_at(lamina_albedo_point_at(distribution, fresnel, xy, mu, eta), multiple);
}

// b(mu), the boost of a boundary's lobe at a grid point (block B): the lobe with its multiple
// scattering is f(l, v) (1 + b(l) b(v)). 0 where the table has no entry.
LAMINA_FN float lamina_boundary_boost_at(LAMINA_IN(LaminaAlbedoPoint) p) {
  if (p.first < 0) return 0.0f;
  return LAMINA_ALBEDO_BOOST_RANGE * lamina_albedo_interpolate(p, LAMINA_ALBEDO_BOOST_COLUMN);
}

// What a medium of optical depth tau = sigma d (per channel, along its normal) lets through of the
// light a rough boundary lets into it from a direction of cosine mu above: the mean of exp(-tau x)
// over the directions its microsurface lets the light through in (after one scattering event or
// more: the walks of microsurface.glsl, as the reference takes them), weighted by the energy each
// carries, x = 1 / |cos| being the path per unit thickness. A smooth
// boundary's is exp(-tau x_s), x_s = 1 / mu_below; a rough one's is less: the facets a grazing view
// sees tilt toward it and bend the light further from the normal (through a 14 degree boundary of
// index 1.45 at 80 degrees, the mean path is 1.5 times longer, and a tint under it absorbed 11% too
// little without this). Writing the mean as exp(-tau g(tau)) with g(tau) = x_s / r(tau), the table
// holds r at tau -> 0 (block P: x_s over the mean of x) and at tau_q = LAMINA_ALBEDO_PATH_DEPTH
// (block Q). g decreases with tau, from the mean path toward the shortest (the tilted mean of x),
// and is convex where the paths' spread is skewed toward long ones, as here; so the chord between the
// two for tau < tau_q, and g(tau_q) beyond, never let through more than the mean of exp(-tau x)
// (a test holds it within 10% of the walks' mean for tau up to 0.6 at views from 60 to 89 degrees;
// beyond tau_q, within 40%, where little passes). r = 1 at a smooth boundary's nodes, where this is
// exactly exp(-tau x_s), and where the table has no entry.
LAMINA_FN vec2 lamina_path_ratios_at(LAMINA_IN(LaminaAlbedoPoint) p) {
  if (p.first < 0) return vec2(1.0f);
  return max(LAMINA_ALBEDO_PATH_RANGE * vec2(lamina_albedo_interpolate(p, LAMINA_ALBEDO_PATH_COLUMN),
                                             lamina_albedo_interpolate(p, LAMINA_ALBEDO_DEPTH_COLUMN)),
             vec2(1.0e-3f));
}
LAMINA_FN vec2 lamina_boundary_path_ratios(int distribution, int fresnel, vec2 xy, float mu, float eta) {
  return lamina_path_ratios_at(lamina_albedo_point_at(distribution, fresnel, xy, mu, eta));
}

LAMINA_FN vec3 lamina_rough_transmittance(vec3 sigma, float thickness, float mu_below, vec2 ratios) {
  if (mu_below <= 0.0f) return vec3(0.0f);
  if (thickness == 0.0f) return vec3(1.0f);
  vec3 tau = max(sigma * thickness, vec3(0.0f));
  float x_s = 1.0f / max(mu_below, LAMINA_MIN_DENOM);
  vec3 share = min(tau / LAMINA_ALBEDO_PATH_DEPTH, vec3(1.0f));
  vec3 g = x_s * (vec3(1.0f / ratios.x) + (1.0f / ratios.y - 1.0f / ratios.x) * share);
  return exp(-tau * g);
}

// The share of a conductor lobe of the given distribution and slope m, with a Fresnel term of 1,
// that a direction of cosine mu reflects inside the exit cone of a boundary of relative index eta
// above it (cos > sqrt(1 - 1 / eta^2); the whole hemisphere where eta <= 1), xy being
// lamina_albedo_grid_xy(m, max(eta, 1)): the table's block C,
// round(65535 C) rounded down, interpolated like E; whole receives the share over the whole
// hemisphere (the row eta = 1, the middle node of the eta axis: one grid point serves both). A
// conductor reflects F(mu) times about as much (F at the mirror direction's V.H, mu itself). 0 for a
// distribution the module has no table for.
// Block C at eta node i, interpolated in the slope (node j, fraction fy) and at coordinate z of
// its cosine axis (lamina_cone_axis).
LAMINA_FN float lamina_cone_block_at(int first, int i, int j, float fy, float z) {
  int k = min(int(z), LAMINA_ALBEDO_COSINES - 2);
  float fz = z - float(k);
  int b = LAMINA_ALBEDO_CONE_COLUMN;
  float c0 = mix(lamina_albedo_entry(first, b, i, j, k), lamina_albedo_entry(first, b, i, j, k + 1), fz);
  float c1 = mix(lamina_albedo_entry(first, b, i, j + 1, k), lamina_albedo_entry(first, b, i, j + 1, k + 1), fz);
  return mix(c0, c1, fy);
}

// What block C's reads need of a boundary's grid coordinates xy that no direction changes: the
// boundary's index on the grid and the indices of the two eta nodes around it. A shading point
// fixes them (LaminaParams.cone_etas), so a lookup computes only its direction's coordinates.
LAMINA_FN vec3 lamina_cone_etas(vec2 xy) {
  int i = min(int(xy.x), LAMINA_ALBEDO_ETAS - 2);
  return vec3(lamina_albedo_grid_eta(xy.x), lamina_albedo_node_eta(i), lamina_albedo_node_eta(i + 1));
}

// Both eta nodes are read at the boundary's own u = eta sin(theta), the sine outside it, on their
// cone-aligned axes: the cone's edge, where a narrow lobe's share steps from 0 to 1, lies on a node
// of each. (Read at one cosine on a plain cosine axis, the step of each node was spread over a
// cell and blended with the other's at another cosine: a smooth metal's mirror direction well
// inside the cone read as partly outside it, which the composition returned as trapped light on
// top of the peak that carries it, and a smooth coat over a smooth metal reflected 1.15 at 70
// degrees.) etas is lamina_cone_etas(xy).
LAMINA_FN float lamina_conductor_cone_share(int distribution, vec2 xy, vec3 etas, float mu, LAMINA_OUT(float) whole) {
  int first = LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[lamina_albedo_combo(distribution, 0)];
  whole = 0.0f;
  if (first < 0) return 0.0f;
  int i = min(int(xy.x), LAMINA_ALBEDO_ETAS - 2);
  int j = min(int(xy.y), LAMINA_ALBEDO_SLOPES - 2);
  float fx = xy.x - float(i);
  float fy = xy.y - float(j);
  float sine = lamina_safe_sqrt(1.0f - lamina_sqr(clamp(mu, 0.0f, 1.0f)));
  float u = etas.x * sine;
  float below = lamina_cone_block_at(first, i, j, fy, lamina_cone_axis(u, etas.y));
  float above = lamina_cone_block_at(first, i + 1, j, fy, lamina_cone_axis(u, etas.z));
  whole = clamp(lamina_cone_block_at(first, (LAMINA_ALBEDO_ETAS - 1) / 2, j, fy, lamina_cone_axis(sine, 1.0f)), 0.0f,
                1.0f);
  return clamp(mix(below, above, fx), 0.0f, 1.0f);
}

// The share of the lobe lamina_conductor_cone_share reads that lies beyond the cone's edge: 1 -
// inside / whole, 0 where the table holds no lobe there (whole 0).
LAMINA_FN float lamina_cone_share_beyond(int distribution, vec2 xy, vec3 etas, float mu) {
  float whole = 0.0f;
  float inside = lamina_conductor_cone_share(distribution, xy, etas, mu, whole);
  return whole > 0.0f ? clamp(1.0f - inside / whole, 0.0f, 1.0f) : 0.0f;
}
