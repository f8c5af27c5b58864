// lamina kernels: Fresnel reflectance (unpolarised light).
// cos_i is the cosine between the incident direction and the (micro)surface normal; the API clamps
// it to [0, 1]. eta is the relative index n_t / n_i of the medium light enters.

// Exact reflectance of a dielectric boundary: the mean of the s- and p-polarised amplitude
// reflectances squared. Returns 1 under total internal reflection (possible only for eta < 1) and
// for eta <= 0, which cannot transmit; returns exactly 0 for eta == 1, an index-matched boundary.
LAMINA_FN float fresnel_dielectric(float cos_i, float eta) {
  if (eta == 1.0f) return 0.0f;
  if (eta <= 0.0f) return 1.0f;
  float c = clamp(cos_i, 0.0f, 1.0f);
  // Snell's law: sin_t = sin_i / eta.
  float sin2_t = (1.0f - c * c) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = sqrt(1.0f - sin2_t);
  // Born and Wolf, Principles of Optics, sec. 1.5.2 (Fresnel formulae), divided through by n_i:
  // r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t), r_p = (eta cos_i - cos_t) / (eta cos_i + cos_t).
  // Both denominators are > 0 here because cos_t > 0.
  float r_s = (c - eta * cos_t) / (c + eta * cos_t);
  float r_p = (eta * c - cos_t) / (eta * c + cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
}

// Exact reflectance of a boundary to a complex relative index eta + i k, per channel
// (the course's complexFresnelReflector; metals: Weidlich and Wilkie course sec. 2.1).
LAMINA_FN vec3 fresnel_conductor(float cos_i, vec3 eta, vec3 k) {
  float c = clamp(cos_i, 0.0f, 1.0f);
  float cos2 = c * c;
  float sin2 = 1.0f - cos2;
  // Born and Wolf, Principles of Optics, sec. 14.2, in the arrangement of Lagarde 2013 ("Memo on
  // Fresnel equations"): with a^2 + b^2 = sqrt((eta^2 - k^2 - sin^2)^2 + 4 eta^2 k^2) and
  // a = sqrt((a^2 + b^2 + eta^2 - k^2 - sin^2) / 2),
  //   R_s = (a^2 + b^2 + cos^2 - 2 a cos) / (a^2 + b^2 + cos^2 + 2 a cos),
  //   R_p = R_s (cos^2 (a^2 + b^2) + sin^4 - 2 a cos sin^2) / (cos^2 (a^2 + b^2) + sin^4 + 2 a cos sin^2).
  // For k = 0 this is fresnel_dielectric, total internal reflection included (a = 0 there).
  vec3 t0 = eta * eta - k * k - sin2;
  vec3 a2_plus_b2 = sqrt(t0 * t0 + 4.0f * eta * eta * k * k);
  vec3 a = sqrt(max(0.5f * (a2_plus_b2 + t0), vec3(0.0f)));
  vec3 t1 = a2_plus_b2 + cos2;
  vec3 t2 = 2.0f * c * a;
  vec3 r_s = (t1 - t2) / max(t1 + t2, vec3(LAMINA_MIN_DENOM));
  vec3 t3 = cos2 * a2_plus_b2 + sin2 * sin2;
  vec3 t4 = t2 * sin2;
  vec3 r_p = r_s * (t3 - t4) / max(t3 + t4, vec3(LAMINA_MIN_DENOM));
  return 0.5f * (r_s + r_p);
}

// Schlick 1994, eq. 24: F = F0 + (1 - F0) (1 - cos)^5, F0 the reflectance at normal incidence.
LAMINA_FN float fresnel_schlick(float cos_i, float f0) {
  float q = 1.0f - clamp(cos_i, 0.0f, 1.0f);
  float q2 = q * q;
  return f0 + (1.0f - f0) * q2 * q2 * q;
}

// The same per channel.
LAMINA_FN vec3 fresnel_schlick_rgb(float cos_i, vec3 f0) {
  float q = 1.0f - clamp(cos_i, 0.0f, 1.0f);
  float q2 = q * q;
  return f0 + (1.0f - f0) * (q2 * q2 * q);
}

// The exact reflectance at normal incidence of a boundary to the complex relative index eta + i k:
// fresnel_conductor at cos_i = 1, where r_s = r_p (Born and Wolf, Principles of Optics, sec. 14.2):
// F0 = ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2). For k = 0 it is the dielectric ((eta-1)/(eta+1))^2.
LAMINA_FN vec3 conductor_f0(vec3 eta, vec3 k) {
  vec3 k2 = k * k;
  return ((eta - 1.0f) * (eta - 1.0f) + k2) / max((eta + 1.0f) * (eta + 1.0f) + k2, vec3(LAMINA_MIN_DENOM));
}

// Lazanyi and Szirmay-Kalos 2005, as coded in Elek 2010, App. B (Elek sec. 3.1: within 5 % of the exact term):
// F = ((n - 1)^2 + 4 n (1 - cos)^5 + k^2) / ((n + 1)^2 + k^2).
LAMINA_FN vec3 fresnel_lazanyi(float cos_i, vec3 n, vec3 k) {
  float q = 1.0f - clamp(cos_i, 0.0f, 1.0f);
  float q2 = q * q;
  vec3 num = (n - 1.0f) * (n - 1.0f) + 4.0f * n * (q2 * q2 * q) + k * k;
  vec3 den = (n + 1.0f) * (n + 1.0f) + k * k;
  return num / max(den, vec3(LAMINA_MIN_DENOM));
}

// --- the Fresnel term a node selects (its `fresnel` parameter) ------------------------------------
// 0 exact (the default), 1 Schlick, 2 Lazanyi-Szirmay-Kalos; other values give the exact term.

// The cosine the Schlick-type approximations of a dielectric boundary take. Schlick's polynomial
// describes light arriving from the optically rarer side; light arriving from the denser side
// (eta < 1) uses the cosine of the refracted direction instead, which lies on the rarer side, and
// total internal reflection gives F = 1 (de Greve 2006, "Reflections and Refractions in Ray
// Tracing", Schlick approximation, for n1 > n2). So the approximations, like the exact term, give
// the same F on both sides of a boundary for the two directions Snell's law connects.
// Returns cos_i for eta >= 1, cos_t = sqrt(1 - (1 - cos_i^2) / eta^2) for eta < 1, and -1 under
// total internal reflection.
LAMINA_FN float lamina_rarer_side_cosine(float cos_i, float eta) {
  float c = clamp(cos_i, 0.0f, 1.0f);
  if (eta >= 1.0f) return c;
  float sin2_t = (1.0f - c * c) / (eta * eta);
  if (sin2_t >= 1.0f) return -1.0f;
  return sqrt(1.0f - sin2_t);
}

// A dielectric boundary of relative index eta. Approximations: Schlick with F0 = ((eta-1)/(eta+1))^2;
// Lazanyi and Szirmay-Kalos (fresnel_lazanyi) with k = 0, which is algebraically the same polynomial,
// since (eta + 1)^2 - (eta - 1)^2 = 4 eta. Both at lamina_rarer_side_cosine. As the exact term: 0 for
// an index-matched boundary (eta = 1; Schlick's polynomial would still give (1 - cos)^5 there), 1
// for eta <= 0.
LAMINA_FN float lamina_fresnel_dielectric(int mode, float cos_i, float eta) {
  if (mode != 1 && mode != 2) return fresnel_dielectric(cos_i, eta);
  if (eta == 1.0f) return 0.0f;
  if (eta <= 0.0f) return 1.0f;
  float c = lamina_rarer_side_cosine(cos_i, eta);
  if (c < 0.0f) return 1.0f;
  if (mode == 1) {
    float r = (eta - 1.0f) / (eta + 1.0f);
    return fresnel_schlick(c, r * r);
  }
  return fresnel_lazanyi(c, vec3(eta), vec3(0.0f)).x;
}

// A conductor of complex relative index eta + i k. Schlick interpolates from the exact reflectance
// at normal incidence (conductor_f0); Lazanyi and Szirmay-Kalos is Elek's App. B form. The two are
// algebraically equal, as (eta + 1)^2 + k^2 - (eta - 1)^2 - k^2 = 4 eta makes 1 - F0 the coefficient
// of (1 - cos)^5 in both, and differ only in float rounding (the error-compensation term Lazanyi and
// Szirmay-Kalos 2005 go on to add for metals is not in Elek's listing, so not here either).
LAMINA_FN vec3 lamina_fresnel_conductor(int mode, float cos_i, vec3 eta, vec3 k) {
  if (mode == 1) return fresnel_schlick_rgb(cos_i, conductor_f0(eta, k));
  if (mode == 2) return fresnel_lazanyi(cos_i, eta, k);
  return fresnel_conductor(cos_i, eta, k);
}
