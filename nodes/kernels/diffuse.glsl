// lamina kernels: diffuse substrates (Lambert, Oren-Nayar) and cosine-weighted sampling.

// Lambert's law: a constant BRDF albedo / pi.
LAMINA_FN vec3 lambert(vec3 albedo) { return albedo * LAMINA_INV_PI; }

// A fluorescent Lambertian base's albedo as a matrix (Weidlich and Wilkie course, sec. 5.2.2, after
// Wilkie et al. 2006): column j is what light absorbed in channel j leaves as, in every channel,
// spread as Lambert's law spreads it. The diagonal is the plain albedo; the rest is fluorescence,
// which re-radiates at longer wavelengths only (Stokes' shift), so in linear RGB green light may
// leave as red, and blue as red or green: shifts = (green to red, blue to red, blue to green). No
// channel returns more than it receives, so each column sums to at most 1: the checker refuses
// constants beyond that, and where a texture's values go beyond it the shifts of that column are
// scaled back (the albedo keeps its value).
LAMINA_FN mat3 lamina_fluorescent_albedo(vec3 albedo, vec3 shifts) {
  vec3 a = clamp(albedo, vec3(0.0f), vec3(1.0f));
  vec3 s = max(shifts, vec3(0.0f));
  float green_out = s.x;
  float blue_out = s.y + s.z;
  float green_scale = green_out > 1.0f - a.y ? (1.0f - a.y) / green_out : 1.0f;
  float blue_scale = blue_out > 1.0f - a.z ? (1.0f - a.z) / blue_out : 1.0f;
  return mat3(vec3(a.x, 0.0f, 0.0f), vec3(s.x * green_scale, a.y, 0.0f),
              vec3(s.y * blue_scale, s.z * blue_scale, a.z));
}

// The part of the course's Oren-Nayar BRDF that depends on neither direction, over albedo / pi:
// C1 = 1 - 0.5 s2 / (s2 + 0.33), s2 = sigma^2 (Weidlich and Wilkie course, sec. 3.3.1).
LAMINA_FN float oren_nayar_uniform(float sigma) {
  float s2 = sigma * sigma;
  return 1.0f - 0.5f * s2 / (s2 + 0.33f);
}

// The mean of the course's Oren-Nayar BRDF (oren_nayar below) over both hemispheres, each direction
// weighted by its cosine: (1 / pi^2) int int f cos_i cos_o dw_i dw_o, the value of the Lambert BRDF of
// equal mean albedo. Each term of the shader is a function of sigma times a fixed integral over the
// directions: C1 is constant; C2's cos_phi sin(alpha) and the inter-reflection term's cos_phi
// (2 beta / pi)^2 average to 0 over the azimuth; what remains are
//   C2: 0.45 s2 / (s2 + 0.09) I2, I2 = 4 int int mu_i mu_o (2 beta / pi)^3 tan(beta) / pi = 0.0435022781,
//   C3: 0.125 s2 / (s2 + 0.09) I3,
//       I3 = (1 - 2 / pi) 4 int int mu_i mu_o (4 alpha beta / pi^2)^2 tan((alpha + beta) / 2) = 0.0655060878
//   (both over dmu_i dmu_o),
// both integrals by Gauss-Legendre on the triangle mu_i < mu_o (converged to 9 digits; the test
// checks the whole mean against a quadrature of oren_nayar itself). The clamp to 0 at large sigma
// is left out: it changes the mean by less than the test's tolerance. For a white base the mean
// albedo pi x mean peaks at 1.0003 (sigma 0.08): the course's model itself reflects that little
// more than it receives, on average over its directions.
LAMINA_FN vec3 oren_nayar_mean(vec3 albedo, float sigma) {
  float s2 = sigma * sigma;
  float k = s2 / (s2 + 0.09f);
  float direct = oren_nayar_uniform(sigma) + k * (0.45f * 0.0435022781f + 0.125f * 0.0655060878f);
  return (albedo * direct + albedo * albedo * (0.17f * s2 / (s2 + 0.13f))) * LAMINA_INV_PI;
}

// The course's Oren-Nayar shader (Weidlich and Wilkie course, sec. 3.3.1, after L. Gritz; the
// model of Oren and Nayar 1994 with its inter-reflection term) turned into a BRDF: the shader's
// radiance (L1 + L2) divided by cos_i, times 1/pi. Symmetric in wi and wo; sigma = 0 gives
// exactly lambert(albedo). Where the course's formula turns negative (sigma above about 0.65, both
// directions near grazing on opposite sides of the normal) the result is clamped to 0.
LAMINA_FN vec3 oren_nayar(vec3 wi, vec3 wo, vec3 albedo, float sigma) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return vec3(0.0f);
  // alpha = max(theta_i, theta_o) has the smaller cosine, beta = min(theta_i, theta_o) the larger.
  float cos_alpha = min(min(wi.z, wo.z), 1.0f);
  float cos_beta = min(max(wi.z, wo.z), 1.0f);
  float alpha = lamina_acos(cos_alpha);
  float beta = lamina_acos(cos_beta);
  float sin_alpha = lamina_safe_sqrt(1.0f - cos_alpha * cos_alpha);
  float sin_beta = lamina_safe_sqrt(1.0f - cos_beta * cos_beta);
  // tan(beta) from the cosine, since acos rounds up to just above pi/2 near grazing and tan would
  // flip sign there.
  float tan_beta = sin_beta / max(cos_beta, LAMINA_MIN_DENOM);
  // tan((alpha + beta) / 2) = (sin alpha + sin beta) / (cos alpha + cos beta), for the same reason.
  float tan_half_sum = (sin_alpha + sin_beta) / max(cos_alpha + cos_beta, LAMINA_MIN_DENOM);
  // cos(phi_i - phi_o) from the projections onto the tangent plane; 0 when either is the normal.
  float proj = lamina_safe_sqrt(wi.x * wi.x + wi.y * wi.y) * lamina_safe_sqrt(wo.x * wo.x + wo.y * wo.y);
  float cos_phi = proj > 0.0f ? clamp((wi.x * wo.x + wi.y * wo.y) / proj, -1.0f, 1.0f) : 0.0f;
  // 1 - |cos_phi| as sin^2 / (1 + |cos_phi|): near cos_phi = +-1 the subtraction loses its digits,
  // which tan((alpha + beta) / 2) multiplies by up to 1e4 at grazing. 1 when either is the normal.
  float sin_phi = proj > 0.0f ? (wi.x * wo.y - wi.y * wo.x) / proj : 0.0f;
  float one_minus_abs_cos_phi = proj > 0.0f ? sin_phi * sin_phi / (1.0f + abs(cos_phi)) : 1.0f;

  float s2 = sigma * sigma;
  float two_beta_over_pi = 2.0f * beta * LAMINA_INV_PI;
  // Weidlich and Wilkie course, sec. 3.3.1 (Gritz's shader):
  // C1 = oren_nayar_uniform,
  // C2 = 0.45 s2 / (s2 + 0.09) sin(alpha)                        if cos_phi >= 0,
  //      0.45 s2 / (s2 + 0.09) (sin(alpha) - (2 beta / pi)^3)    otherwise,
  // C3 = 0.125 s2 / (s2 + 0.09) (4 alpha beta / pi^2)^2.
  // Near grazing (beta -> pi/2) sin(alpha) - (2 beta / pi)^3 is a difference of two numbers near 1,
  // which tan(beta) then multiplies by up to 1e4: the same difference, written with
  // x = 1 - 2 beta / pi and 1 - sin(alpha) = cos^2(alpha) / (1 + sin(alpha)), is
  // x (3 - 3x + x^2) - cos^2(alpha) / (1 + sin(alpha)), and keeps its digits. x = (2 / pi) asin(cos beta):
  // where cos beta < 1/4, by the Maclaurin series of asin (Abramowitz and Stegun 4.4.40) to c^9, whose
  // remainder is under 3e-8 of the value there; above, 1 - 2 beta / pi is at least 0.16 and loses at
  // most 3 bits. (atan(cos beta, sin beta) gives the same, at a third of Oren-Nayar's whole cost.)
  float c2_beta = cos_beta * cos_beta;
  float asin_cos_beta =
      cos_beta * (1.0f + c2_beta * (1.0f / 6.0f + c2_beta * (3.0f / 40.0f +
                                                             c2_beta * (5.0f / 112.0f + c2_beta * (35.0f / 1152.0f)))));
  float x = cos_beta < 0.25f ? 2.0f * LAMINA_INV_PI * asin_cos_beta : 1.0f - two_beta_over_pi;
  float opposite = x * (3.0f - 3.0f * x + x * x) - cos_alpha * cos_alpha / (1.0f + sin_alpha);
  float c1 = oren_nayar_uniform(sigma);
  float c2 = 0.45f * s2 / (s2 + 0.09f) * (cos_phi >= 0.0f ? sin_alpha : opposite);
  float c3 = 0.125f * s2 / (s2 + 0.09f) * lamina_sqr(4.0f * alpha * beta * LAMINA_INV_PI * LAMINA_INV_PI);
  // Same section: L1 / cos_i = albedo (C1 + cos_phi C2 tan(beta) + (1 - |cos_phi|) C3 tan((alpha + beta) / 2)),
  // L2 / cos_i = albedo^2 0.17 s2 / (s2 + 0.13) (1 - cos_phi (2 beta / pi)^2).
  vec3 direct = albedo * (c1 + cos_phi * c2 * tan_beta + one_minus_abs_cos_phi * c3 * tan_half_sum);
  vec3 interreflected =
      albedo * albedo * (0.17f * s2 / (s2 + 0.13f) * (1.0f - cos_phi * two_beta_over_pi * two_beta_over_pi));
  return max(direct + interreflected, vec3(0.0f)) * LAMINA_INV_PI;
}

// Cosine-weighted hemisphere sample, z up (Malley's method: a uniform disk sample lifted to the
// hemisphere; Pharr, Jakob and Humphreys, PBR 3rd ed., sec. 13.6.3): r = sqrt(u.x), phi = 2 pi u.y,
// z = sqrt(1 - u.x), with density cos / pi.
LAMINA_FN vec3 sample_cosine(vec2 u) {
  float r = lamina_safe_sqrt(u.x);
  float phi = 2.0f * LAMINA_PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), lamina_safe_sqrt(1.0f - u.x));
}

// Same source: p(w) = cos / pi above the horizon.
LAMINA_FN float pdf_cosine(float cos_theta) { return cos_theta > 0.0f ? cos_theta * LAMINA_INV_PI : 0.0f; }
