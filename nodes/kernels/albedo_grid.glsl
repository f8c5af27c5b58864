// lamina kernels: the grid of the dielectric albedo table (energy.glsl). Its own file because C++
// defines the table (kernels.h) between these constants and the functions that read it.

// The grid: eta = 4^(x |x|) with x uniform in [-1, 1], nodes closer together near eta = 1 (a node,
// index-matched, where E = 0), where E at grazing views climbs fastest with eta;
// m uniform in [0, 1]; and a cosine z uniform in [0, 1] (the node z = 0 holds the value at 0.001).
// z is the view's cosine mu where eta >= 1; where eta < 1 light can enter only inside the cone
// sin(theta) < eta, and z is the cosine of the refracted direction, so that the grid spans the cone
// and the total reflection beyond it does not bend the interpolation. (The composition reads E only
// inside the cone there.)
const int LAMINA_ALBEDO_ETAS = 21;
const int LAMINA_ALBEDO_SLOPES = 13;
const int LAMINA_ALBEDO_COSINES = 25;
const int LAMINA_ALBEDO_COMBO_SIZE = LAMINA_ALBEDO_ETAS * LAMINA_ALBEDO_SLOPES * LAMINA_ALBEDO_COSINES;
const int LAMINA_ALBEDO_COMBOS = 6;  // distributions (beckmann, blinn, ggx) x Fresnel (exact, approximations)
// The table is stored as an image, one row per (combination, eta) and LAMINA_ALBEDO_SLOPES runs of
// LAMINA_ALBEDO_COSINES texels across (the GLSL back end binds it as an R16UI texture).
const int LAMINA_ALBEDO_TABLE_WIDTH = LAMINA_ALBEDO_SLOPES * LAMINA_ALBEDO_COSINES;

// A table's combination: the distribution's code, times 2, plus 1 for the Schlick and Lazanyi
// terms, which are the same polynomial for a dielectric (lamina_fresnel_dielectric).
LAMINA_FN int lamina_albedo_combo(int distribution, int fresnel) {
  return clamp(distribution, 0, 2) * 2 + ((fresnel == 1 || fresnel == 2) ? 1 : 0);
}

// The grid coordinate z of a view's cosine mu (0 beyond the cone where eta < 1).
LAMINA_FN float lamina_albedo_axis_cosine(float mu, float eta) {
  if (eta >= 1.0f) return clamp(mu, 0.0f, 1.0f);
  return lamina_safe_sqrt(1.0f - (1.0f - lamina_sqr(clamp(mu, 0.0f, 1.0f))) / (eta * eta));
}

// The grid's nodes, for the table's generator: eta, m, and the view's cosine at node k.
LAMINA_FN float lamina_albedo_node_eta(int i) {
  float x = 2.0f * float(i) / float(LAMINA_ALBEDO_ETAS - 1) - 1.0f;
  return exp2(2.0f * x * abs(x));
}
LAMINA_FN float lamina_albedo_node_slope(int j) { return float(j) / float(LAMINA_ALBEDO_SLOPES - 1); }
LAMINA_FN float lamina_albedo_node_cosine(int k, float eta) {
  float z = max(float(k) / float(LAMINA_ALBEDO_COSINES - 1), 0.001f);
  if (eta >= 1.0f) return z;
  return sqrt(1.0f - eta * eta * (1.0f - z * z));
}
