// lamina kernels: microfacet distributions, geometry terms, the Torrance-Sparrow lobe and normal
// sampling. m is the Beckmann RMS slope (tan of the course's roughness angle); distribution
// 0 = Beckmann, 1 = normalised Blinn, 2 = GGX (alpha = m). Every D is normalised so that
// integral D(h) cos_h d omega_h = 1 over the hemisphere (Walter et al. 2007, eq. 4).

// Smooth limit: callers clamp m to at least this; the kernels clamp again so that no argument
// divides by zero.
const float LAMINA_MIN_SLOPE = 1.0e-4f;

LAMINA_FN float d_beckmann(float cos_h, float m) {
  if (cos_h <= 0.0f) return 0.0f;
  float c2 = min(cos_h * cos_h, 1.0f);
  float sin2 = 1.0f - c2;
  float m2 = lamina_sqr(max(m, LAMINA_MIN_SLOPE));
  // Past tan^2/m^2 = 80 the lobe is below 1e-30 (exp(-80) = 2e-35) for any sensible m, and
  // stopping there keeps tan^2 = sin^2/cos^2 and 1/cos^4 finite as cos_h -> 0.
  if (sin2 >= 80.0f * m2 * c2) return 0.0f;
  float tan2 = sin2 / c2;
  // Walter et al. 2007, eq. 25 (Elek 2010, App. B, without its 1/pi):
  // D = exp(-tan^2 / m^2) / (pi m^2 cos^4).
  return exp(-tan2 / m2) * LAMINA_INV_PI / (m2 * c2 * c2);
}

// Walter et al. 2007 (Phong distribution: the exponent whose lobe matches a Beckmann slope m):
// e = 2 / m^2 - 2.
LAMINA_FN float blinn_exponent(float m) { return max(2.0f / lamina_sqr(max(m, LAMINA_MIN_SLOPE)) - 2.0f, 0.0f); }

LAMINA_FN float d_blinn(float cos_h, float m) {
  if (cos_h <= 0.0f) return 0.0f;
  float e = blinn_exponent(m);
  // Weidlich and Wilkie course, eq. 3.7 (its blinnD; Walter et al. 2007, eq. 30):
  // D = (e + 2) / (2 pi) cos^e.
  return (e + 2.0f) * (0.5f * LAMINA_INV_PI) * pow(min(cos_h, 1.0f), e);
}

LAMINA_FN float d_ggx(float cos_h, float alpha) {
  if (cos_h <= 0.0f) return 0.0f;
  float c2 = min(cos_h * cos_h, 1.0f);
  float a2 = lamina_sqr(max(alpha, LAMINA_MIN_SLOPE));
  // Walter et al. 2007, eq. 33: D = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2), multiplied out as
  // alpha^2 / (pi (alpha^2 cos^2 + sin^2)^2), which needs no division by cos.
  float den = a2 * c2 + (1.0f - c2);
  return a2 * LAMINA_INV_PI / max(den * den, LAMINA_MIN_DENOM);
}

// Unknown distributions give 0.
LAMINA_FN float d_microfacet(int distribution, float cos_h, float m) {
  if (distribution == 0) return d_beckmann(cos_h, m);
  if (distribution == 1) return d_blinn(cos_h, m);
  if (distribution == 2) return d_ggx(cos_h, m);
  return 0.0f;
}

// D at a unit half vector h, computed from its components: sin^2 = h.x^2 + h.y^2 instead of
// 1 - cos^2, which cancels near the normal. There a narrow lobe (m = tan 1 deg) turns one rounding
// of cos_h into a relative error of about 4e-4 in D; from the components D keeps float accuracy,
// so CPU and GPU agree at the peak of sharp lobes too. Same formulas as d_beckmann, d_blinn and
// d_ggx (Walter et al. 2007, eqs. 25, 30, 33).
LAMINA_FN float d_microfacet_h(int distribution, vec3 h, float m) {
  if (h.z <= 0.0f) return 0.0f;
  float c2 = h.z * h.z;
  float sin2 = h.x * h.x + h.y * h.y;
  if (distribution == 0) {
    float m2 = lamina_sqr(max(m, LAMINA_MIN_SLOPE));
    if (sin2 >= 80.0f * m2 * c2) return 0.0f;
    return exp(-(sin2 / c2) / m2) * LAMINA_INV_PI / (m2 * c2 * c2);
  }
  if (distribution == 1) {
    float e = blinn_exponent(m);
    // cos^e = exp(e/2 ln(1 - s)) with s = sin^2 / |h|^2; ln(1 - s) by its series for small s, and
    // 1 - s as cos^2 / |h|^2 elsewhere, which keeps its digits near the horizon too.
    float s = sin2 / (sin2 + c2);
    float log_c2 = s < 0.01f ? -s * (1.0f + s * (0.5f + s * (1.0f / 3.0f + 0.25f * s))) : log(c2 / (sin2 + c2));
    return (e + 2.0f) * (0.5f * LAMINA_INV_PI) * exp(0.5f * e * log_c2);
  }
  if (distribution == 2) {
    float a2 = lamina_sqr(max(m, LAMINA_MIN_SLOPE));
    float den = a2 * c2 + sin2;
    return a2 * LAMINA_INV_PI / max(den * den, LAMINA_MIN_DENOM);
  }
  return 0.0f;
}

LAMINA_FN float g_vcavity(float cos_l, float cos_v, float cos_h, float v_dot_h) {
  if (cos_l <= 0.0f || cos_v <= 0.0f || cos_h <= 0.0f || v_dot_h <= 0.0f) return 0.0f;
  // Weidlich and Wilkie course, sec. 3.3.1 (geom; Elek 2010, App. B; Cook and Torrance 1982):
  // G = min(1, 2 cos_h cos_v / v.h, 2 cos_h cos_l / v.h), compared before dividing so that a tiny
  // v.h cannot overflow.
  float num = 2.0f * cos_h * min(cos_l, cos_v);
  return num >= v_dot_h ? 1.0f : num / v_dot_h;
}

LAMINA_FN float g1_smith_ggx(float cos_w, float alpha) {
  if (cos_w <= 0.0f) return 0.0f;
  float c = min(cos_w, 1.0f);
  // Walter et al. 2007, eq. 34: G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2)), multiplied through by cos:
  // 2 cos / (cos + sqrt(cos^2 + alpha^2 sin^2)); the denominator is > 0 for cos > 0.
  return 2.0f * c / (c + sqrt(c * c + alpha * alpha * (1.0f - c * c)));
}

// Walter et al. 2007, eq. 23: the separable Smith approximation G = G1(l) G1(v).
LAMINA_FN float g_smith_ggx(float cos_l, float cos_v, float alpha) {
  return g1_smith_ggx(cos_l, alpha) * g1_smith_ggx(cos_v, alpha);
}

// The mean of max(0, w.n) / cos_n over normals n drawn with density D(n) cos_n, Blinn's
// distribution of exponent e, for a direction w of cosine c (> 0) and sine s, over the normals
// with t = cos_n^(e + 1) in [lo, hi]: 8-point Gauss-Legendre in t (Abramowitz and Stegun 25.4.30),
// where the density is uniform. Over the azimuth, max(0, w.n) averages to b when b >= a, else to
// (b acos(-b / a) + sqrt(a^2 - b^2)) / pi, with a = s sin_n and b = c cos_n.
LAMINA_FN float lamina_blinn_visible_at(float c, float s, float e, float t) {
  float cos_n = pow(t, 1.0f / (e + 1.0f));
  float a = s * lamina_safe_sqrt(1.0f - cos_n * cos_n);
  float b = c * cos_n;
  if (b >= a) return b;
  return (b * lamina_acos(-b / a) + lamina_safe_sqrt(a * a - b * b)) * LAMINA_INV_PI;
}

LAMINA_FN float lamina_blinn_visible_piece(float c, float s, float e, float lo, float hi) {
  float h = 0.5f * (hi - lo);
  float mid = 0.5f * (hi + lo);
  float sum = 0.3626837834f * (lamina_blinn_visible_at(c, s, e, mid - h * 0.1834346425f) +
                               lamina_blinn_visible_at(c, s, e, mid + h * 0.1834346425f));
  sum += 0.3137066459f * (lamina_blinn_visible_at(c, s, e, mid - h * 0.5255324099f) +
                          lamina_blinn_visible_at(c, s, e, mid + h * 0.5255324099f));
  sum += 0.2223810345f * (lamina_blinn_visible_at(c, s, e, mid - h * 0.7966664774f) +
                          lamina_blinn_visible_at(c, s, e, mid + h * 0.7966664774f));
  sum += 0.1012285363f * (lamina_blinn_visible_at(c, s, e, mid - h * 0.9602898565f) +
                          lamina_blinn_visible_at(c, s, e, mid + h * 0.9602898565f));
  return h * sum;
}

// Smith's Lambda of Blinn's distribution for a direction of cosine c in (0, 1): I / c - 1, with I
// the integral of max(0, w.n) D(n) over the normals, the microsurface's area projected toward w
// (Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", sec. 5),
// which has no closed form for Blinn: I = (e + 2) / (e + 1) times the integral over
// t = cos_n^(e + 1) in [0, 1] of lamina_blinn_visible_at. Above its kink (b = a, where
// cos_n = sin theta) the integrand is c t^(1 / (e + 1)), integrated exactly; below, by quadrature.
// Then I / c - 1 = (e + 2) / (e + 1) (lower piece) / c - sin^(e + 2) theta, without the
// cancellation of forming I first.
LAMINA_FN float lamina_blinn_lambda(float c, float e) {
  float s = lamina_safe_sqrt(1.0f - c * c);
  float kink = pow(s, e + 1.0f);
  float lower = lamina_blinn_visible_piece(c, s, e, 0.0f, kink);
  float lambda = (e + 2.0f) / (e + 1.0f) * lower / max(c, LAMINA_MIN_DENOM) - kink * s;
  return max(lambda, 0.0f);
}

// Smith's Lambda of direction w for the distribution of slope m, for w on either side:
// Lambda(-w) = -1 - Lambda(w) (Heitz et al. 2016, sec. 2). Beckmann: Lambda = (erf(a) - 1) / 2 +
// exp(-a^2) / (2 a sqrt(pi)) with a = 1 / (m tan theta) (Walter et al. 2007, the integral behind
// eq. 27), here exp(-a^2) (1 / (2 a sqrt(pi)) - poly(a) / 2) and its asymptotic series past a = 3;
// GGX (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2 (Walter eq. 34's G1 = 1 / (1 + Lambda)); Blinn by
// quadrature (lamina_blinn_lambda; Walter's sec. 5.2 borrows Beckmann's, which at slope 1 lets a
// lossless boundary scatter several times the light it receives).
LAMINA_FN float lamina_smith_lambda(int distribution, vec3 w, float m) {
  float c = abs(w.z);
  float lambda_up = 0.0f;
  if (c < 0.99999f) {
    float s = sqrt(1.0f - c * c);
    float mm = max(m, LAMINA_MIN_SLOPE);
    if (distribution == 2) {
      float t = mm * s / max(c, LAMINA_MIN_DENOM);
      lambda_up = 0.5f * (sqrt(1.0f + t * t) - 1.0f);
    } else if (distribution == 1) {
      lambda_up = lamina_blinn_lambda(c, blinn_exponent(mm));
    } else {
      float a = c / (mm * s);
      float inv_root_pi = 0.564189583547756f;
      if (a < 3.0f) {
        lambda_up = exp(-a * a) * (0.5f * inv_root_pi / max(a, LAMINA_MIN_DENOM) - 0.5f * lamina_erfc_poly(a));
      } else {
        float inv2 = 1.0f / (a * a);
        lambda_up = exp(-a * a) * 0.5f * inv_root_pi / a * inv2 * (0.5f - inv2 * (0.75f - inv2 * 1.875f));
      }
      lambda_up = max(lambda_up, 0.0f);
    }
  }
  return w.z >= 0.0f ? lambda_up : -1.0f - lambda_up;
}

// Smith's masking G1 of a direction of cosine cos_w (> 0) for the distribution of slope m:
// 1 / (1 + Lambda) (Walter et al. 2007, eq. 23's G1 for each distribution). The layered model's
// GGX lobes use the same term in g1_smith_ggx's cosine form.
LAMINA_FN float lamina_smith_g1(int distribution, float cos_w, float m) {
  if (cos_w <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + lamina_smith_lambda(distribution, vec3(0.0f, 0.0f, min(cos_w, 1.0f)), m));
}

// GGX uses its Smith term, the others the V-cavity term. Both are 0 unless the microfacet faces
// the view (cos_h > 0 and v.h > 0; the chi+ factor of Walter et al. 2007, eq. 34).
LAMINA_FN float g_microfacet(int distribution, float cos_l, float cos_v, float cos_h, float v_dot_h, float m) {
  if (distribution == 2) return (cos_h > 0.0f && v_dot_h > 0.0f) ? g_smith_ggx(cos_l, cos_v, m) : 0.0f;
  return g_vcavity(cos_l, cos_v, cos_h, v_dot_h);
}

// V.H and L.H are equal in exact arithmetic; their mean is bitwise the same when L and V swap, so
// rounding cannot break reciprocity where L + V nearly cancels (grazing, opposite directions).
LAMINA_FN float lamina_symmetric_dot(vec3 l, vec3 v, vec3 h) { return 0.5f * (dot(v, h) + dot(l, h)); }

LAMINA_FN vec3 torrance_sparrow(vec3 F, float D, float G, float cos_l, float cos_v) {
  if (cos_l <= 0.0f || cos_v <= 0.0f) return vec3(0.0f);
  // Weidlich and Wilkie course, eq. 2.1 (Walter et al. 2007, eq. 20): f = F D G / (4 cos_l cos_v).
  return F * (D * G / max(4.0f * cos_l * cos_v, LAMINA_MIN_DENOM));
}

// Samples a microfacet normal h with density D(h) cos_h per solid angle (plain NDF sampling,
// as in Walter et al. 2007). u in [0,1)^2; u.x is clamped below 1 so that log(1 - u.x) and
// 1/(1 - u.x) stay finite. Unknown distributions give vec3(0).
LAMINA_FN vec3 sample_microfacet_normal(int distribution, float m, vec2 u) {
  float ux = clamp(u.x, 0.0f, 0.99999988f);
  float mm = max(m, LAMINA_MIN_SLOPE);
  float cos2 = 1.0f;
  float sin2 = 0.0f;
  if (distribution == 0) {
    // Walter et al. 2007, eq. 28: tan^2 = -m^2 log(1 - u).
    float tan2 = -mm * mm * log(1.0f - ux);
    cos2 = 1.0f / (1.0f + tan2);
    sin2 = tan2 / (1.0f + tan2);
  } else if (distribution == 1) {
    // Walter et al. 2007 (Phong distribution): cos = u^(1 / (e + 2)), the inverse of the CDF
    // cos^(e + 2) of D cos over the hemisphere; written with 1 - u, uniform as well and never 0.
    // As cos^2 = exp(-y) with y = -2 log(1 - u) / (e + 2), so that sin^2 = 1 - exp(-y) keeps its
    // digits for narrow lobes, where cos^2 rounds to within a few ulp of 1.
    float y = -2.0f * log(1.0f - ux) / (blinn_exponent(mm) + 2.0f);
    cos2 = exp(-y);
    sin2 = lamina_one_minus_exp(y);
  } else if (distribution == 2) {
    // Walter et al. 2007, eq. 35: tan^2 = alpha^2 u / (1 - u), as cos^2 and sin^2 without a pole.
    float den = 1.0f - ux + mm * mm * ux;
    cos2 = (1.0f - ux) / den;
    sin2 = mm * mm * ux / den;
  } else {
    return vec3(0.0f);
  }
  // Walter et al. 2007, eq. 36: phi = 2 pi u.y.
  float phi = 2.0f * LAMINA_PI * u.y;
  float sin_theta = lamina_safe_sqrt(sin2);
  return vec3(sin_theta * cos(phi), sin_theta * sin(phi), sqrt(cos2));
}

// Walter et al. 2007, eq. 24: p(h) = D(h) cos_h.
LAMINA_FN float pdf_microfacet_normal(int distribution, float m, float cos_h) {
  if (cos_h <= 0.0f) return 0.0f;
  return d_microfacet(distribution, cos_h, m) * min(cos_h, 1.0f);
}
