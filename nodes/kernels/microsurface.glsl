// lamina kernels: the Smith microsurface of a rough dielectric boundary, for light that scatters
// on it any number of times (Heitz, Hanika, d'Eon and Dachsbacher 2016, "Multiple-Scattering
// Microfacet BSDFs with the Smith Model"). The reference solver walks light over it
// (graph/cpu/microsurface.cpp): a boundary that loses nothing, as a real smooth-or-rough glass
// surface does, where the single-scattering boundary of boundary.glsl loses what its facets would
// scatter again.
//
// Frame and conventions: z is the macro normal; the walk works on the upper side, and light on the
// lower side is handled by turning every direction around (w -> -w) and the relative index over
// (eta -> 1 / eta). Heights are uniform on [-1, 1] (the walk's result does not depend on the
// height distribution, sec. 3). eta is the index below over the index above.

// The microsurface's area projected toward w (w.z on either side): (1 + Lambda(w)) w.z.
LAMINA_FN float lamina_projected_area(int distribution, vec3 w, float m) {
  return max((1.0f + lamina_smith_lambda(distribution, w, m)) * w.z, 0.0f);
}

// The height distribution's CDF on [-1, 1] and its inverse. The inverse keeps 1e-6 from either end:
// light that meets the surface at its very top and refracts continues at the very bottom of the
// other side's heights, where C1(h) = 0 would mask every direction up completely, however little
// Lambda says it is masked (at h = -1 + 1e-6 and Lambda = 1e-4 it escapes with probability
// 0.9986, as it does at any height a real draw reaches). At exactly -1 such walks were trapped
// until the event limit lost them.
LAMINA_FN float lamina_height_cdf(float h) { return clamp(0.5f * (h + 1.0f), 0.0f, 1.0f); }
LAMINA_FN float lamina_height_inverse_cdf(float u) { return clamp(2.0f * u - 1.0f, -1.0f + 1.0e-6f, 1.0f - 1.0e-6f); }

// The probability that light leaving height h along w (travelling, w.z > 0) escapes the
// microsurface: C1(h)^Lambda(w) (Heitz et al. 2016, eq. 6 with Smith's height-correlated masking).
LAMINA_FN float lamina_escape_probability(int distribution, vec3 w, float h, float m) {
  if (w.z >= 0.99999f) return 1.0f;
  if (w.z <= 0.0f) return 0.0f;
  return pow(lamina_height_cdf(h), lamina_smith_lambda(distribution, w, m));
}

// The next height at which light travelling along w from height h meets the microsurface, drawn
// with u (Heitz et al. 2016, sec. 4.1: the CDF 1 - G1(w, h') between h and h'). Returns 2 (above
// every height) when the light escapes.
LAMINA_FN float lamina_next_height(int distribution, vec3 w, float h, float m, float u) {
  if (w.z >= 0.99999f) return 2.0f;
  if (w.z <= -0.99999f) return lamina_height_inverse_cdf(u * lamina_height_cdf(h));
  if (abs(w.z) < 1.0e-5f) return h;
  if (u > 1.0f - lamina_escape_probability(distribution, w, h, m)) return 2.0f;
  float lambda = lamina_smith_lambda(distribution, w, m);
  // Where Lambda is so small that the power underflows, the floor keeps the quotient finite (at
  // C1(h) = 0 it was 0 / 0, and a reference walk of fabric returned NaN).
  return lamina_height_inverse_cdf(lamina_height_cdf(h) / max(pow(1.0f - u, 1.0f / lambda), 1.0e-30f));
}

// The density of visible normals seen from w (either side; Heitz et al. 2016, eq. 2):
// D_w(n) = max(0, w.n) D(n) / projected area.
LAMINA_FN float lamina_visible_normal_density(int distribution, vec3 w, vec3 n, float m) {
  float area = lamina_projected_area(distribution, w, m);
  if (area <= 0.0f || n.z <= 0.0f) return 0.0f;
  return max(dot(w, n), 0.0f) * d_microfacet_h(distribution, n, m) / area;
}

// The phase function of one scattering event on the upper side (light arriving from wi, leaving
// along wo, both pointing away from the event), per solid angle of wo: a visible normal, then
// Fresnel reflection or refraction through it (Heitz et al. 2016, sec. 5.2, the dielectric phase
// function). wo.z < 0 is refraction into the lower medium (relative index eta).
LAMINA_FN float lamina_phase_eval(vec3 wi, vec3 wo, float eta, int distribution, int fresnel_mode, float m) {
  if (wo.z >= 0.0f) {
    vec3 sum = wi + wo;
    float len = length(sum);
    if (len <= 1.0e-7f) return 0.0f;
    vec3 n = sum / len;
    float wi_n = dot(wi, n);
    if (n.z <= 0.0f || wi_n <= 0.0f) return 0.0f;
    return lamina_fresnel_dielectric(fresnel_mode, wi_n, eta) * lamina_visible_normal_density(distribution, wi, n, m) /
           (4.0f * wi_n);
  }
  // Refraction: n = -(wi + eta wo) / |..| (Walter eq. 16 with n_i = 1, n_o = eta).
  vec3 sum = wi + eta * wo;
  float len = length(sum);
  if (len <= 1.0e-7f) return 0.0f;
  vec3 n = -sum / len;
  if (n.z < 0.0f) n = -n;
  float wi_n = dot(wi, n);
  float wo_n = dot(wo, n);
  if (wi_n <= 0.0f || wo_n >= 0.0f) return 0.0f;
  float denom = lamina_sqr(wi_n + eta * wo_n);
  return (1.0f - lamina_fresnel_dielectric(fresnel_mode, wi_n, eta)) *
         lamina_visible_normal_density(distribution, wi, n, m) * eta * eta * (-wo_n) / max(denom, LAMINA_MIN_DENOM);
}

// Draws a GGX normal n with the density of visible normals D_v(n) seen from v, slope alpha (Heitz
// 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)): stretch v to the
// configuration of slope 1, where the visible normals are uniform over the hemisphere's projection;
// draw a point on the disk, warped linearly to that projection; lift it to the hemisphere; unstretch.
// The projection is the half disk and half the equator's ellipse (minor axis v.z): their union
// when v is above the macro surface, their difference when it is below, so the same warp serves
// both (v.z > -1).
LAMINA_FN vec3 lamina_sample_ggx_visible_normal(vec3 v, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 2.0f * LAMINA_PI * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(1.0f - p1 * p1, 0.0f)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(1.0f - p1 * p1 - p2 * p2, 0.0f)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0f)));
}

// Draws the slopes (x, y) of a visible normal of the Beckmann distribution of slope 1 seen from a
// direction at angle theta in the xz plane (Heitz and d'Eon 2014, "Importance Sampling
// Microfacet-Based BSDFs using the Distribution of Visible Normals", sec. 4 and its Beckmann
// appendix). Slopes have the density exp(-x^2 - y^2) / pi, and a facet of slope x shows the
// direction sin(theta) (c - x) of its area per unit macro area, c = cot(theta), none where x > c;
// so y keeps its own density and x has the CDF
//   C(x) = (c (1 + erf x) + exp(-x^2) / sqrt(pi)) / (c (1 + erf c) + exp(-c^2) / sqrt(pi)).
// C is inverted in b = erf x, bounded to [-1, erf c], where dC/db = (c - x) / N: Newton steps that a
// bracket keeps from leaving it (a step out of it is a bisection), a fixed 10 of them with selects
// rather than branches (residual of C below 1e-8 in double from a first guess linear in b). Below
// c = -1.5 (LAMINA_BECKMANN_LOWEST_COT) 1 + erf c and the two terms of the denominator, which
// nearly cancel, lose their digits in float, and past c = -4 every visible slope is beyond what
// float's erf can tell from -1: the walk does not ask for those. The normal is the one of slopes
// (x, y).
const float LAMINA_BECKMANN_LOWEST_COT = 1.5f;
LAMINA_FN vec2 lamina_beckmann_visible_slopes(float cos_theta, float sin_theta, vec2 u) {
  float inv_root_pi = 0.564189583547756f;
  float c = cos_theta / max(sin_theta, 1.0e-7f);
  float lo = -1.0f;
  float hi = lamina_erf(c);
  float norm = c * (1.0f + hi) + exp(-c * c) * inv_root_pi;
  float b = lo + (hi - lo) * u.x;
  for (int i = 0; i < 10; ++i) {
    // Also false for a NaN: a step that divided by a vanishing slope becomes a bisection.
    b = (b >= lo && b <= hi) ? b : 0.5f * (lo + hi);
    float x = lamina_erfinv(b);
    float value = (c * (1.0f + b) + exp(-x * x) * inv_root_pi) / norm - u.x;
    hi = value > 0.0f ? b : hi;
    lo = value > 0.0f ? lo : b;
    b = b - value * norm / (c - x);
  }
  b = (b >= lo && b <= hi) ? b : 0.5f * (lo + hi);
  return vec2(lamina_erfinv(b), lamina_erfinv(2.0f * u.y - 1.0f));
}

// Draws a Beckmann normal n of RMS slope m with the density of visible normals D_v(n) seen from v
// (v.z >= -1.5 m |v.xy|, the cotangent lamina_beckmann_visible_slopes keeps its digits down to;
// Heitz and d'Eon 2014): stretch v to slope 1 (the distribution's shape does not change with m, and
// a facet of slope p = m q shows v what one of slope q shows the stretched direction), draw the
// slopes in v's azimuth, rotate them back and scale them by m.
LAMINA_FN vec3 lamina_sample_beckmann_visible_normal(vec3 v, float m, vec2 u) {
  vec3 vs = normalize(vec3(m * v.x, m * v.y, v.z));
  float sin_theta = sqrt(vs.x * vs.x + vs.y * vs.y);
  float cos_phi = sin_theta > 0.0f ? vs.x / sin_theta : 1.0f;
  float sin_phi = sin_theta > 0.0f ? vs.y / sin_theta : 0.0f;
  vec2 q = lamina_beckmann_visible_slopes(vs.z, sin_theta, u);
  vec2 p = m * vec2(cos_phi * q.x - sin_phi * q.y, sin_phi * q.x + cos_phi * q.y);
  return normalize(vec3(-p.x, -p.y, 1.0f));
}

// Draws one scattering event on the upper side for light arriving from wi: a microfacet normal with
// the visible normal density D_wi(n) (GGX: lamina_sample_ggx_visible_normal; Beckmann:
// lamina_sample_beckmann_visible_normal; weight 1), or weighted toward it by the ratio of D_wi to
// the density drawn with (Blinn: plain NDF sampling D(n) cos_n, weight max(0, wi.n) / (projected
// area cos_n); Beckmann seen from below the lowest cotangent its visible slopes keep their digits
// at: the normals visible from there in wi's azimuth, which include every one wi sees).
// The plain NDF draw is unbiased but noisy: a facet facing away loses the light, and for a Beckmann
// coat of 35 degrees over white the reference's albedo had 16 times GGX's standard error; then
// reflection with probability F(wi.n), else
// refraction (then `refracted` is true: the light continues in the lower medium, whichever way the
// facet sent it). u.x, u.y draw n, u.z chooses. Returns the direction (vec3(0) and weight 0 if none).
LAMINA_FN vec3 lamina_phase_sample(vec3 wi, float eta, int distribution, int fresnel_mode, float m, vec3 u,
                                   LAMINA_OUT(float) weight, LAMINA_OUT(bool) refracted) {
  weight = 0.0f;
  refracted = false;
  bool ggx = distribution == 2 && wi.z > -0.99999f;
  bool beckmann = distribution == 0;
  // Beckmann seen from further below than cot = -1.5 (in the stretched frame of slope 1) draws the
  // normals visible from the direction of its azimuth at cot = -1.5, which include all it sees.
  float mm = max(m, LAMINA_MIN_SLOPE);
  float planar = sqrt(wi.x * wi.x + wi.y * wi.y);
  bool raised = beckmann && wi.z < -LAMINA_BECKMANN_LOWEST_COT * mm * planar;
  vec2 azimuth = planar > 0.0f ? vec2(wi.x, wi.y) / planar : vec2(1.0f, 0.0f);
  vec3 seen = raised ? normalize(vec3(azimuth, -LAMINA_BECKMANN_LOWEST_COT * mm)) : wi;
  vec3 n = ggx        ? lamina_sample_ggx_visible_normal(wi, mm, vec2(u.x, u.y))
           : beckmann ? lamina_sample_beckmann_visible_normal(seen, mm, vec2(u.x, u.y))
                      : sample_microfacet_normal(distribution, m, vec2(u.x, u.y));
  float wi_n = dot(wi, n);
  float area = lamina_projected_area(distribution, wi, m);
  if (wi_n <= 0.0f || n.z <= 0.0f || area <= 0.0f) return vec3(0.0f);
  // D_wi(n) over the density n was drawn with: 1 for visible normals seen from wi itself.
  float seen_area = lamina_projected_area(distribution, seen, m);
  float drawn_weight = ggx        ? 1.0f
                     : raised   ? wi_n * seen_area / (max(dot(seen, n), 1.0e-30f) * area)
                     : beckmann ? 1.0f
                                : wi_n / (area * n.z);
  float fresnel = lamina_fresnel_dielectric(fresnel_mode, wi_n, eta);
  vec3 wo = vec3(0.0f);
  if (u.z < fresnel) {
    wo = 2.0f * wi_n * n - wi;
  } else {
    float ratio = 1.0f / eta;
    float sin2_t = ratio * ratio * (1.0f - wi_n * wi_n);
    if (sin2_t >= 1.0f) return vec3(0.0f);
    wo = (ratio * wi_n - sqrt(1.0f - sin2_t)) * n - ratio * wi;
    refracted = true;
  }
  weight = drawn_weight;
  return normalize(wo);
}
