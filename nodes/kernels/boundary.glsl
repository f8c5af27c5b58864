// lamina kernels: one rough boundary between two dielectrics that reflects and transmits light in
// both directions (Walter, Marschner, Li and Torrance 2007, "Microfacet Models for Refraction
// through Rough Surfaces"), for the light that scatters once on its facets. The reference solver
// (graph/cpu/reference.cpp) weighs its ways of reaching the light by this boundary's sampling
// density; its own walks over the microsurface (microsurface.glsl) scatter any number of times.
//
// The boundary is the plane z = 0 of the frame; eta = n_below / n_above. Directions point away
// from the boundary and may lie on either side (z > 0 above, z < 0 below). f(l, e) is the BSDF for
// radiance arriving from l and leaving along e, without the cosine; l and e on the same side is
// reflection, on opposite sides transmission.
//
// Masking is Smith's separable G1(l) G1(e) (Walter eq. 23, lamina_smith_g1) for every
// distribution, so that one microsurface reflects and transmits. The layered model's Beckmann and
// Blinn lobes use the V-cavity term instead (g_microfacet); GGX's are the same.

// The index of the side a direction lies on, relative to the medium above.
LAMINA_FN float lamina_side_index(vec3 w, float eta) { return w.z > 0.0f ? 1.0f : eta; }

// The microfacet normal (z > 0) that turns l into e: the half vector of a reflection (Walter
// eq. 13), the generalised one -(n_l l + n_e e) of a transmission (eq. 16). vec3(0) when there is
// none (a straight path through an index-matched boundary) or a direction lies in the plane.
LAMINA_FN vec3 lamina_boundary_normal(vec3 l, vec3 e, float eta) {
  if (l.z == 0.0f || e.z == 0.0f) return vec3(0.0f);
  bool reflection = (l.z > 0.0f) == (e.z > 0.0f);
  vec3 h = reflection ? l + e : -(lamina_side_index(l, eta) * l + lamina_side_index(e, eta) * e);
  float len = length(h);
  if (len <= 1.0e-7f) return vec3(0.0f);
  h = h / len;
  return h.z < 0.0f ? -h : h;
}

// Whether both directions see the microfacet h from their own side (Walter's chi+ terms, eq. 33).
LAMINA_FN bool lamina_boundary_faces(vec3 l, vec3 e, vec3 h) {
  return h.z > 0.0f && dot(l, h) * l.z > 0.0f && dot(e, h) * e.z > 0.0f;
}

// f(l, e) of the boundary: Walter eq. 20 for reflection, eq. 21 for transmission (i = l, o = e),
// with the Fresnel term `fresnel_mode` selects at l.h. Transmitted radiance carries n_e^2 / n_l^2,
// so f(l, e) / n_e^2 = f(e, l) / n_l^2.
LAMINA_FN float lamina_boundary_eval(vec3 l, vec3 e, float eta, int distribution, int fresnel_mode, float m) {
  vec3 h = lamina_boundary_normal(l, e, eta);
  if (!lamina_boundary_faces(l, e, h)) return 0.0f;
  float n_l = lamina_side_index(l, eta);
  float n_e = lamina_side_index(e, eta);
  float l_h = dot(l, h);
  float e_h = dot(e, h);
  float fresnel = lamina_fresnel_dielectric(fresnel_mode, abs(l_h), l.z > 0.0f ? eta : 1.0f / eta);
  float d = d_microfacet_h(distribution, h, m);
  float g = lamina_smith_g1(distribution, abs(l.z), m) * lamina_smith_g1(distribution, abs(e.z), m);
  float cosines = abs(l.z) * abs(e.z);
  if ((l.z > 0.0f) == (e.z > 0.0f)) return fresnel * d * g / max(4.0f * cosines, LAMINA_MIN_DENOM);
  float denom = lamina_sqr(n_l * l_h + n_e * e_h);
  return abs(l_h) * abs(e_h) * n_e * n_e * (1.0f - fresnel) * d * g / max(cosines * denom, LAMINA_MIN_DENOM);
}

// Draws the direction y, on either side, into which the boundary scatters x: a microfacet normal
// with density D(h) cos_h (sample_microfacet_normal), facing x's side; reflection about it with
// probability F(x.h), else refraction through it (Walter eqs. 39 and 40). u.x, u.y draw h, u.z
// chooses. vec3(0) when h faces away from x or the result leaves on the wrong side (the sample is
// lost: its density is still counted by lamina_boundary_pdf).
LAMINA_FN vec3 lamina_boundary_sample(vec3 x, float eta, int distribution, int fresnel_mode, float m, vec3 u) {
  if (x.z == 0.0f) return vec3(0.0f);
  float side = x.z > 0.0f ? 1.0f : -1.0f;
  vec3 h = sample_microfacet_normal(distribution, m, vec2(u.x, u.y)) * side;
  float x_h = dot(x, h);
  if (x_h <= 0.0f) return vec3(0.0f);
  float eta_x = x.z > 0.0f ? eta : 1.0f / eta;  // the index past the boundary over x's
  float fresnel = lamina_fresnel_dielectric(fresnel_mode, x_h, eta_x);
  vec3 y = vec3(0.0f);
  if (u.z < fresnel) {
    y = 2.0f * x_h * h - x;
    if (y.z * side <= 0.0f) return vec3(0.0f);
  } else {
    // Snell's law at the microfacet: sin_t = sin_x / eta_x.
    float ratio = 1.0f / eta_x;
    float sin2_t = ratio * ratio * (1.0f - x_h * x_h);
    if (sin2_t >= 1.0f) return vec3(0.0f);
    y = (ratio * x_h - sqrt(1.0f - sin2_t)) * h - ratio * x;
    if (y.z * side >= 0.0f) return vec3(0.0f);
  }
  return normalize(y);
}

// The density of lamina_boundary_sample drawing y from x, per solid angle of y: the microfacet
// density D(h) cos_h, times F or 1 - F, times the Jacobian d omega_h / d omega_y: 1 / (4 |x.h|) for
// reflection (Walter eq. 14), n_y^2 |y.h| / (n_x x.h + n_y y.h)^2 for transmission (eq. 17).
LAMINA_FN float lamina_boundary_pdf(vec3 y, vec3 x, float eta, int distribution, int fresnel_mode, float m) {
  vec3 h = lamina_boundary_normal(x, y, eta);
  if (!lamina_boundary_faces(x, y, h)) return 0.0f;
  float x_h = dot(x, h);
  float y_h = dot(y, h);
  float fresnel = lamina_fresnel_dielectric(fresnel_mode, abs(x_h), x.z > 0.0f ? eta : 1.0f / eta);
  float density = d_microfacet_h(distribution, h, m) * h.z;
  if ((x.z > 0.0f) == (y.z > 0.0f)) return fresnel * density / max(4.0f * abs(x_h), LAMINA_MIN_DENOM);
  float n_x = lamina_side_index(x, eta);
  float n_y = lamina_side_index(y, eta);
  float denom = lamina_sqr(n_x * x_h + n_y * y_h);
  return (1.0f - fresnel) * density * n_y * n_y * abs(y_h) / max(denom, LAMINA_MIN_DENOM);
}

// Beer-Lambert transmittance per channel along one crossing of a layer (Weidlich and Wilkie
// course, eq. 3.2): exp(-sigma d / |cos|). absorption() is the two crossings of the model in one
// exponential.
LAMINA_FN vec3 lamina_crossing_transmittance(vec3 sigma, float thickness, float cos_w) {
  if (thickness == 0.0f) return vec3(1.0f);
  float c = abs(cos_w);
  if (c <= 0.0f) return vec3(0.0f);
  return exp(-max(sigma * (thickness / max(c, LAMINA_MIN_DENOM)), vec3(0.0f)));
}
