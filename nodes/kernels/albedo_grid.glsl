// lamina kernels: the grid of the dielectric albedo table (energy.glsl). Its own file because C++
// defines the table (kernels.h) between these constants and the functions that read it.

// The grid: eta = 4^(x |x|) with x uniform in [-1, 1], nodes closer together near eta = 1 (a node,
// index-matched, where E = 0), where E at grazing views climbs fastest with eta;
// m = y^3 and a cosine z = w^2 with y and w uniform in [0, 1] (the node z = 0 holds the value at
// 0.001): nodes closer together toward smooth boundaries and grazing views, where a boundary's
// masking and multiple scattering change fastest (masking depends on m / mu: at 89 degrees a slope
// of 0.002 already masks part of what a smooth boundary reflects). z is the view's cosine mu where
// eta >= 1; where eta < 1 light can enter only inside the cone sin(theta) < eta, and z is the
// cosine of the refracted direction, so that the grid spans the cone and the total reflection
// beyond it does not bend the interpolation. (The composition reads E only inside the cone there.)
// Tables are linear in (x, y, w) between nodes.
const int LAMINA_ALBEDO_ETAS = 21;
const int LAMINA_ALBEDO_SLOPES = 13;
const int LAMINA_ALBEDO_COSINES = 25;
const int LAMINA_ALBEDO_COMBOS = 6;  // distributions (beckmann, blinn, ggx) x Fresnel (exact, approximations)
// The table is stored as an image, one row per (combination, eta) (the GLSL back end binds it as an
// R16UI texture). A row holds six blocks: E, the single-scattering albedo, as LAMINA_ALBEDO_SLOPES
// runs of LAMINA_ALBEDO_COSINES texels; from column LAMINA_ALBEDO_MULTIPLE_COLUMN, M, what the
// boundary's microsurface reflects beyond E (energy.glsl), on the same grid; and from column
// LAMINA_ALBEDO_CONE_COLUMN, C, the share of a conductor lobe of the combination's distribution
// that leaves inside the exit cone of a boundary of index eta above it (energy.glsl), on the same
// eta and slope axes where eta >= 1 (the rows under 1 hold the whole hemisphere's, as at eta = 1)
// and a cosine axis of its own, aligned with the cone (lamina_cone_axis); and from columns
// LAMINA_ALBEDO_PATH_COLUMN and LAMINA_ALBEDO_DEPTH_COLUMN, P and Q, how long the path is that the
// light the boundary lets through takes in the medium below (energy.glsl, lamina_rough_transmittance),
// as ratios r of cosines stored as round(65535 r / LAMINA_ALBEDO_PATH_RANGE) (under an index below 1,
// rough facets can bend the light nearer the normal than a smooth boundary does: r above 1); and
// from column LAMINA_ALBEDO_BOOST_COLUMN, B, the boost b of the boundary's lobe (energy.glsl), on E's
// grid, stored as floor(65535 b / LAMINA_ALBEDO_BOOST_RANGE) (b reaches that range only at 7 nodes,
// all of Blinn boundaries of slope 0.58 and over, where the walks' M is noisy).
const int LAMINA_ALBEDO_BLOCK = LAMINA_ALBEDO_SLOPES * LAMINA_ALBEDO_COSINES;
const int LAMINA_ALBEDO_MULTIPLE_COLUMN = LAMINA_ALBEDO_BLOCK;
const int LAMINA_ALBEDO_CONE_COLUMN = 2 * LAMINA_ALBEDO_BLOCK;
const int LAMINA_ALBEDO_PATH_COLUMN = 3 * LAMINA_ALBEDO_BLOCK;
const int LAMINA_ALBEDO_DEPTH_COLUMN = 4 * LAMINA_ALBEDO_BLOCK;
const int LAMINA_ALBEDO_BOOST_COLUMN = 5 * LAMINA_ALBEDO_BLOCK;
const int LAMINA_ALBEDO_TABLE_WIDTH = 6 * LAMINA_ALBEDO_BLOCK;
const float LAMINA_ALBEDO_PATH_RANGE = 2.0f;
const float LAMINA_ALBEDO_PATH_DEPTH = 0.5f;  // the optical depth of block Q
const float LAMINA_ALBEDO_BOOST_RANGE = 16.0f;
const int LAMINA_ALBEDO_COMBO_SIZE = LAMINA_ALBEDO_ETAS * LAMINA_ALBEDO_TABLE_WIDTH;

// A table's combination: the distribution's code, times 2, plus 1 for the Schlick and Lazanyi
// terms, which are the same polynomial for a dielectric (lamina_fresnel_dielectric).
LAMINA_FN int lamina_albedo_combo(int distribution, int fresnel) {
  return clamp(distribution, 0, 2) * 2 + ((fresnel == 1 || fresnel == 2) ? 1 : 0);
}

// The cosine z on the grid's cosine axis of a view's cosine mu (0 beyond the cone where eta < 1);
// the grid coordinate is sqrt(z).
LAMINA_FN float lamina_albedo_axis_cosine(float mu, float eta) {
  if (eta >= 1.0f) return clamp(mu, 0.0f, 1.0f);
  return lamina_safe_sqrt(1.0f - (1.0f - lamina_sqr(clamp(mu, 0.0f, 1.0f))) / (eta * eta));
}

// The grid's coordinates as values, for the table's generator: eta, m and the view's cosine at
// grid coordinates x, y and w (node i of an axis at coordinate i).
LAMINA_FN float lamina_albedo_grid_eta(float x) {
  float t = 2.0f * x / float(LAMINA_ALBEDO_ETAS - 1) - 1.0f;
  return exp2(2.0f * t * abs(t));
}
LAMINA_FN float lamina_albedo_grid_slope(float y) {
  float t = y / float(LAMINA_ALBEDO_SLOPES - 1);
  return t * t * t;
}
LAMINA_FN float lamina_albedo_grid_cosine(float w, float eta) {
  float z = max(lamina_sqr(w / float(LAMINA_ALBEDO_COSINES - 1)), 0.001f);
  if (eta >= 1.0f) return z;
  return sqrt(1.0f - eta * eta * (1.0f - z * z));
}
// Block C's cosine axis at a node of index eta_n >= 1, aligned with its exit cone: node
// LAMINA_CONE_EDGE_NODE lies on the cone's edge; the nodes above it at the square root of the
// cosine outside the boundary, evenly, so that they crowd toward the edge, where a narrow lobe's
// share steps from 0 to 1 (on the plain cosine axis the step fell inside a cell, whose ramp read a
// smooth metal's mirror direction well inside the cone as partly outside); the nodes below it
// evenly in u from the edge (1) to grazing (eta_n). The argument is u = eta sin(theta), the sine
// outside the boundary: the composition reads both eta nodes around a boundary at its own u.
const int LAMINA_CONE_EDGE_NODE = 8;
LAMINA_FN float lamina_cone_axis(float u, float eta_n) {
  float above = float(LAMINA_ALBEDO_COSINES - 1 - LAMINA_CONE_EDGE_NODE);
  float inside = float(LAMINA_CONE_EDGE_NODE) + sqrt(lamina_safe_sqrt(1.0f - min(u * u, 1.0f))) * above;
  float beyond = float(LAMINA_CONE_EDGE_NODE) * clamp((eta_n - u) / max(eta_n - 1.0f, 1.0e-6f), 0.0f, 1.0f);
  return u <= 1.0f ? inside : beyond;
}
// Its inverse, for the table's generator: the cosine under a boundary of index eta_n >= 1 at node
// coordinate w (at least 0.001, as on the other axis).
LAMINA_FN float lamina_cone_axis_cosine(float w, float eta_n) {
  float edge = float(LAMINA_CONE_EDGE_NODE);
  float s = max(w - edge, 0.0f) / float(LAMINA_ALBEDO_COSINES - 1 - LAMINA_CONE_EDGE_NODE);
  float u_inside = lamina_safe_sqrt(1.0f - lamina_sqr(s * s));
  float u_beyond = eta_n - (w / edge) * (eta_n - 1.0f);
  float sine = min((w >= edge ? u_inside : u_beyond) / eta_n, 1.0f);
  return max(lamina_safe_sqrt(1.0f - sine * sine), 0.001f);
}
LAMINA_FN float lamina_albedo_node_eta(int i) { return lamina_albedo_grid_eta(float(i)); }
LAMINA_FN float lamina_albedo_node_slope(int j) { return lamina_albedo_grid_slope(float(j)); }
LAMINA_FN float lamina_albedo_node_cosine(int k, float eta) { return lamina_albedo_grid_cosine(float(k), eta); }
