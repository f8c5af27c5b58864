// lamina kernels: the reflectance of a thin transparent film over a base (a metal, or a dielectric
// that absorbs what enters it), per RGB channel. The film's two boundaries reflect waves that
// interfere: what leaves depends on the phase the film adds, 2 pi / lambda times the optical path
// difference 2 n_f d cos_f (Granier and Heidrich 2003, eqs. 1-4, for the mirror direction, which is
// what a microfacet sees). lamina takes the exact Airy sum of every reflection inside the film (Born
// and Wolf, Principles of Optics, sec. 7.6.1), per polarisation, rather than the Phong lobes of
// Granier and Heidrich's eq. 5: a film's reflectance then stays within [0, 1], where eq. 5's
// R + T + 2 cos(2 Phi) sqrt(R T) reaches 1.56 for a film of index 1.5 (their eq. 18, diffuse form).
//
// Two ways to fold the spectrum into RGB:
//   LAMINA_FRESNEL_FILM_RGB       the Airy reflectance at one wavelength per channel (645, 525 and
//                                 445 nm, Granier and Heidrich sec. 3.3): exact for monochromatic
//                                 light; for films whose fringes are narrower than a channel (an
//                                 optical path 2 n_f d above about 1 um) the three samples alias.
//   LAMINA_FRESNEL_FILM_SPECTRAL  the Airy reflectance as its Fourier series in the phase, each term
//                                 averaged over the channel's spectral response in closed form (Belcour
//                                 and Barla 2017, "A Practical Extension to Microfacet Theory for the
//                                 Modeling of Varying Iridescence", sec. 4): the colour a camera sees
//                                 of a film under white light, which fades to the incoherent mean as
//                                 the film thickens instead of aliasing.
// Relative indices as elsewhere: the film's eta_f and the base's eta + i k over the medium above;
// depth is the film's thickness in nm times the medium above's index, so that eta_f depth is the
// optical thickness n_f d. cos_i is the cosine at the film's top (a microfacet's V.H).

const int LAMINA_FRESNEL_FILM_RGB = 3;
const int LAMINA_FRESNEL_FILM_SPECTRAL = 4;

// Whether a Fresnel mode is one of a thin film's.
LAMINA_FN bool lamina_is_film(int mode) {
  return mode == LAMINA_FRESNEL_FILM_RGB || mode == LAMINA_FRESNEL_FILM_SPECTRAL;
}

// Complex arithmetic on vec2 (real, imaginary).
LAMINA_FN vec2 lamina_cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
LAMINA_FN vec2 lamina_cdiv(vec2 a, vec2 b) {
  return vec2(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / max(dot(b, b), LAMINA_MIN_DENOM);
}
// The principal square root (real part >= 0; for a negative real argument, +i sqrt).
LAMINA_FN vec2 lamina_csqrt(vec2 z) {
  float r = length(z);
  float im = lamina_safe_sqrt(0.5f * (r - z.x));
  return vec2(lamina_safe_sqrt(0.5f * (r + z.x)), z.y < 0.0f ? -im : im);
}

// The amplitude reflection coefficients of the film's boundaries for one channel: r12 (s in x, p in
// y), real, from the medium above into the film, and r23 (s in xy, p in zw), complex, from the film
// into the base, with the Fresnel formulae in one sign convention for both (Born and Wolf, sec.
// 1.5.2; for the base's complex index, sec. 14.2), so that Airy's sum holds for each polarisation.
// Returns the cosine inside the film, or -1 when light from above cannot enter it (total internal
// reflection, only where the film's index is below the medium above's; the wave that tunnels
// through a film thinner than a wavelength is not followed).
LAMINA_FN float lamina_film_boundaries(float cos_i, float eta_f, vec2 base, LAMINA_OUT(vec2) r12,
                                       LAMINA_OUT(vec4) r23) {
  float c1 = clamp(cos_i, 0.0f, 1.0f);
  float sin2_f = (1.0f - c1 * c1) / (eta_f * eta_f);
  r12 = vec2(-1.0f, 1.0f);
  r23 = vec4(0.0f);
  if (sin2_f >= 1.0f) return -1.0f;
  float cf = sqrt(1.0f - sin2_f);
  r12 = vec2((c1 - eta_f * cf) / (c1 + eta_f * cf), (eta_f * c1 - cf) / max(eta_f * c1 + cf, LAMINA_MIN_DENOM));
  // The base's index over the film's, N, and its complex cosine sqrt(1 - sin_f^2 / N^2).
  vec2 n = base / eta_f;
  vec2 cb = lamina_csqrt(vec2(1.0f, 0.0f) - sin2_f * lamina_cdiv(vec2(1.0f, 0.0f), lamina_cmul(n, n)));
  vec2 n_cb = lamina_cmul(n, cb);
  vec2 n_cf = n * cf;
  vec2 cf2 = vec2(cf, 0.0f);
  r23 = vec4(lamina_cdiv(cf2 - n_cb, cf2 + n_cb), lamina_cdiv(n_cf - cb, n_cf + cb));
  return cf;
}

// Airy's reflectance |(r12 + r23 e^{i delta}) / (1 + r12 r23 e^{i delta})|^2 of one polarisation
// (Born and Wolf, sec. 7.6.1, eq. 55 with absorption in the base).
LAMINA_FN float lamina_airy(float r12, vec2 r23, vec2 phase) {
  vec2 t = lamina_cmul(r23, phase);
  vec2 num = vec2(r12, 0.0f) + t;
  vec2 den = vec2(1.0f, 0.0f) + r12 * t;
  return dot(num, num) / max(dot(den, den), LAMINA_MIN_DENOM);
}

// The channel responses the spectral fold averages over: the CIE 1931 colour matching functions as
// Gaussians in wavenumber nu (Belcour and Barla 2017, supplemental: x as two lobes, y and z one
// each), here by each lobe's integral, centre (per nm) and Fourier variance v (per nm^2: a Gaussian of
// variance 2 v), the integrals scaled so that y's is 1; then to linear Rec. 709 RGB (IEC 61966-2-1,
// D65). The mean of cos(2 pi opd nu + s) over a lobe is its Fourier transform, A cos(2 pi opd mu + s)
// exp(-(2 pi opd)^2 v). lamina_film_weights gives the lobes' weights in channel c, divided by the
// channel's response to a flat spectrum, so that the fold maps a constant reflectance to grey.
const vec4 LAMINA_FILM_LOBE_AREA = vec4(0.846402f, 1.0f, 1.000900f, 0.153834f);
const vec4 LAMINA_FILM_LOBE_CENTRE = vec4(1.6810e-3f, 1.7953e-3f, 2.2084e-3f, 2.2399e-3f);
const vec4 LAMINA_FILM_LOBE_VARIANCE = vec4(4.3278e-9f, 9.3046e-9f, 6.6121e-9f, 4.5282e-9f);
LAMINA_FN vec3 lamina_film_rgb_row(int c) {
  return c == 0   ? vec3(3.2404542f, -1.5371385f, -0.4985314f)
         : c == 1 ? vec3(-0.9692660f, 1.8760108f, 0.0415560f)
                  : vec3(0.0556434f, -0.2040259f, 1.0572252f);
}
LAMINA_FN vec3 lamina_film_rgb_of_xyz(vec3 xyz) {
  return vec3(dot(lamina_film_rgb_row(0), xyz), dot(lamina_film_rgb_row(1), xyz), dot(lamina_film_rgb_row(2), xyz));
}
LAMINA_FN vec4 lamina_film_weights(int c) {
  vec3 row = lamina_film_rgb_row(c);
  vec4 w = vec4(row.x, row.y, row.z, row.x) * LAMINA_FILM_LOBE_AREA;
  return w / (w.x + w.y + w.z + w.w);
}

// The orders of the series the spectral fold averages over the channel's response; the rest are
// taken at the channel's wavelength. The terms fall as (R12 R23)^(m/2): eight orders keep the fold
// within 0.001 of the integral over gold at 73 degrees, where six were 0.0014 and four 0.008 off
// (substrate_thin_film_test.cpp).
const int LAMINA_FILM_ORDERS = 8;

// Two complex products at once, one per polarisation: s in xy, p in zw.
LAMINA_FN vec4 lamina_film_cmul2(vec4 a, vec4 b) {
  return vec4(lamina_cmul(vec2(a.x, a.y), vec2(b.x, b.y)), lamina_cmul(vec2(a.z, a.w), vec2(b.z, b.w)));
}

// One channel's reflectance. rgb: Airy's sum at the wavelength lambda (nm), per polarisation.
// spectral: the same sum written as its Fourier series in the phase (Belcour and Barla 2017, sec. 4:
// with a real r12, R23 = |r23|^2 and T121 = 1 - R12, the constant R12 + T121^2 R23 / (1 - R12 R23)
// and the m-th harmonic 2 C_m cos(m (delta + phi21 + phi23)), C_m = (T121^2 R23 / (1 - R12 R23) -
// T121) (R12 R23)^(m/2)), with its first LAMINA_FILM_ORDERS harmonics averaged over the channel's
// response instead of taken at lambda: each is the real part of u^m Z_m, Z_m the weighted sum over
// the response's lobes of A g^(m^2) z^m, z = exp(i 2 pi opd mu), g = exp(-(2 pi opd)^2 v), which
// depends on neither polarisation. Belcour and Barla drop the harmonics beyond; lamina keeps them at
// lambda, so that a film of no thickness is exactly the bare base and grazing light, where R12 R23
// nears 1 and the series converges slowly, loses nothing. c selects the channel's response.
LAMINA_FN float lamina_film_channel(bool spectral, int c, float cos_i, float eta_f, vec2 base, float depth,
                                    float lambda) {
  vec2 r12;
  vec4 r23;
  float cf = lamina_film_boundaries(cos_i, eta_f, base, r12, r23);
  if (cf < 0.0f) return 1.0f;
  float opd = 2.0f * eta_f * depth * cf;
  float delta = 2.0f * LAMINA_PI * opd / lambda;
  vec2 phase = vec2(cos(delta), sin(delta));
  vec2 r23_s = vec2(r23.x, r23.y);
  vec2 r23_p = vec2(r23.z, r23.w);
  float total = 0.5f * (lamina_airy(r12.x, r23_s, phase) + lamina_airy(r12.y, r23_p, phase));
  if (spectral) {
    vec2 r_12 = r12 * r12;
    vec2 t_121 = vec2(1.0f) - r_12;
    vec2 r_23 = vec2(dot(r23_s, r23_s), dot(r23_p, r23_p));
    vec2 r_123 = r_12 * r_23;
    vec2 cm = t_121 * t_121 * r_23 / max(vec2(1.0f) - r_123, vec2(1.0e-6f)) - t_121;
    vec2 root = sqrt(r_123);
    // The round trip's phase shift as a unit complex number: r21 = -r12 (0 or pi) and arg r23.
    vec2 flip = vec2(r12.x > 0.0f ? -1.0f : 1.0f, r12.y > 0.0f ? -1.0f : 1.0f);
    vec4 u = vec4(flip.x * (r_23.x > 0.0f ? r23_s / sqrt(r_23.x) : vec2(1.0f, 0.0f)),
                  flip.y * (r_23.y > 0.0f ? r23_p / sqrt(r_23.y) : vec2(1.0f, 0.0f)));
    vec4 u_lambda = lamina_film_cmul2(u, vec4(phase, phase));
    vec4 um = vec4(1.0f, 0.0f, 1.0f, 0.0f);
    vec4 um_lambda = um;
    float k = 2.0f * LAMINA_PI * opd;
    vec4 angle = LAMINA_FILM_LOBE_CENTRE * k;
    vec4 z_re = cos(angle);
    vec4 z_im = sin(angle);
    vec4 g = exp(-LAMINA_FILM_LOBE_VARIANCE * (k * k));
    vec4 w = lamina_film_weights(c);
    vec4 zm_re = vec4(1.0f);
    vec4 zm_im = vec4(0.0f);
    vec4 g_m = vec4(1.0f);  // g^(m^2), raised by g^(2m - 1) at each order
    vec4 g_step = g;
    for (int m = 1; m <= LAMINA_FILM_ORDERS; ++m) {
      vec4 re = zm_re * z_re - zm_im * z_im;
      zm_im = zm_re * z_im + zm_im * z_re;
      zm_re = re;
      g_m *= g_step;
      g_step *= g * g;
      vec4 amp = w * g_m;
      vec2 zm = vec2(dot(amp, zm_re), dot(amp, zm_im));
      cm *= root;
      um = lamina_film_cmul2(um, u);
      um_lambda = lamina_film_cmul2(um_lambda, u_lambda);
      // Re(u^m Z_m) replaces Re(u_lambda^m), per polarisation, each weighted by 2 C_m / 2.
      vec2 averaged = vec2(lamina_cmul(vec2(um.x, um.y), zm).x, lamina_cmul(vec2(um.z, um.w), zm).x);
      total += dot(cm, averaged - vec2(um_lambda.x, um_lambda.z));
    }
  }
  return clamp(total, 0.0f, 1.0f);
}

// The film's reflectance per channel: film_eta the film's relative index per channel (dispersion),
// eta + i k the base's. mode is LAMINA_FRESNEL_FILM_RGB or LAMINA_FRESNEL_FILM_SPECTRAL.
LAMINA_FN vec3 lamina_fresnel_film(int mode, float cos_i, vec3 film_eta, vec3 eta, vec3 k, float depth) {
  bool spectral = mode == LAMINA_FRESNEL_FILM_SPECTRAL;
  return vec3(lamina_film_channel(spectral, 0, cos_i, film_eta.x, vec2(eta.x, k.x), depth, 645.0f),
              lamina_film_channel(spectral, 1, cos_i, film_eta.y, vec2(eta.y, k.y), depth, 525.0f),
              lamina_film_channel(spectral, 2, cos_i, film_eta.z, vec2(eta.z, k.z), depth, 445.0f));
}

// The Fresnel term of a metal-like base (substrate/conductor, substrate/thin_film): the film's when
// `mode` is one of the film's, else the conductor's term `mode` selects (lamina_fresnel_conductor).
// The film's is reached through LAMINA_FILM_FRESNEL, which each back end defines: C++ as
// lamina_fresnel_film; GLSL as lamina_fresnel_film in a module with a film, and as vec3(1.0)
// otherwise, so that no other module inlines the film's code wherever a conductor's Fresnel term is
// taken (it tripled llvmpipe's compile times of every material with a metal).
LAMINA_FN vec3 lamina_fresnel_base(int mode, float cos_i, vec3 eta, vec3 k, vec3 film_eta, float depth) {
  if (lamina_is_film(mode)) return LAMINA_FILM_FRESNEL(mode, cos_i, film_eta, eta, k, depth);
  return lamina_fresnel_conductor(mode, cos_i, eta, k);
}
