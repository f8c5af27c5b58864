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

// The height distribution's CDF on [-1, 1] and its inverse.
LAMINA_FN float lamina_height_cdf(float h) { return clamp(0.5f * (h + 1.0f), 0.0f, 1.0f); }
LAMINA_FN float lamina_height_inverse_cdf(float u) { return clamp(2.0f * u - 1.0f, -1.0f, 1.0f); }

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
  return lamina_height_inverse_cdf(lamina_height_cdf(h) / pow(1.0f - u, 1.0f / lambda));
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

// Draws one scattering event on the upper side for light arriving from wi: a microfacet normal with
// the visible normal density D_wi(n) (GGX: lamina_sample_ggx_visible_normal, weight 1), or by plain
// NDF sampling (D(n) cos_n) weighted toward it by weight = max(0, wi.n) / (projected area cos_n)
// (Beckmann and Blinn, whose tails are light enough for the weight's variance to stay finite); then
// reflection with probability F(wi.n), else
// refraction (then `refracted` is true: the light continues in the lower medium, whichever way the
// facet sent it). u.x, u.y draw n, u.z chooses. Returns the direction (vec3(0) and weight 0 if none).
LAMINA_FN vec3 lamina_phase_sample(vec3 wi, float eta, int distribution, int fresnel_mode, float m, vec3 u,
                                   LAMINA_OUT(float) weight, LAMINA_OUT(bool) refracted) {
  weight = 0.0f;
  refracted = false;
  bool visible = distribution == 2 && wi.z > -0.99999f;
  vec3 n = visible ? lamina_sample_ggx_visible_normal(wi, max(m, LAMINA_MIN_SLOPE), vec2(u.x, u.y))
                   : sample_microfacet_normal(distribution, m, vec2(u.x, u.y));
  float wi_n = dot(wi, n);
  float area = lamina_projected_area(distribution, wi, m);
  if (wi_n <= 0.0f || n.z <= 0.0f || area <= 0.0f) return vec3(0.0f);
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
  weight = visible ? 1.0f : wi_n / (area * n.z);
  return normalize(wo);
}
