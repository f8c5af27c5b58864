// lamina kernels: paint of flakes, the fast two-layer model of Ershov, Kolchin and Myszkowski 2001
// ("Rendering pearlescent appearance based on paint-composition modelling", sec. 6): a binder of
// randomly oriented mirror flakes (colour r_p, passing t_p straight through) over a Lambertian
// substrate, under the binder's boundary. Seen from air its BRDF is gloss (the boundary) + glitter
// (flakes, eq. 36) + shade (the substrate through the flakes, eqs. 28 and 26), the last two behind
// the boundary's transmission (1 - F(l)) (1 - F(v)) / eta^2. The kernels here take directions
// inside the binder (l, v refracted, z > 0) and leave the boundary to the caller. The full model it
// approximates is graph/cpu/flake_slab.h (doubling and adding).
//
// Units: coverage = D <S> h (the flakes' area per unit area of paint), kappa_h the binder's
// absorption depth at normal incidence, m the Beckmann RMS slope of the flakes' normals.

// A paint's flakes at one shading point. Plain flakes reflect `colour` (at most 1 - transmittance)
// and pass `transmittance` straight through, at every angle, as the paper's (sec. 4). A coated
// flake (film one of LAMINA_FRESNEL_FILM_*) is an interference platelet: a lossless film of index
// film_eta over the binder's and depth film_depth (its thickness in nm times the binder's index, as
// film.glsl takes it) in the binder, which reflects the film's Airy reflectance R(alpha) with the
// binder on both sides and passes 1 - R(alpha) (mica coated with titanium dioxide: its colour in
// reflection, the complementary one through it, both moving with the angle).
struct LaminaFlakes {
  float coverage;
  vec3 colour;
  float transmittance;
  int film;
  vec3 film_eta;
  float film_depth;
  int distribution;
  float m;
};

// Plain flakes (no film).
LAMINA_FN LaminaFlakes lamina_flakes(float coverage, vec3 colour, float transmittance, int distribution, float m) {
  LaminaFlakes f;
  f.coverage = coverage;
  f.colour = colour;
  f.transmittance = transmittance;
  f.film = 0;
  f.film_eta = vec3(1.0f);
  f.film_depth = 0.0f;
  f.distribution = distribution;
  f.m = m;
  return f;
}

// A flake's reflectance r and straight transmittance t for light at cosine c to its normal. A coated
// flake's film is reached through LAMINA_FLAKE_FILM, lamina_fresnel_film in C++ and in a GLSL module
// with coated flakes, vec3(1.0) in the others (film.glsl's lamina_fresnel_base says why).
LAMINA_FN void lamina_flake_optics(LAMINA_IN(LaminaFlakes) f, float c, LAMINA_OUT(vec3) r, LAMINA_OUT(vec3) t) {
  if (lamina_is_film(f.film)) {
    r = LAMINA_FLAKE_FILM(f.film, c, f.film_eta, vec3(1.0f), vec3(0.0f), f.film_depth);
    t = vec3(1.0f) - r;
  } else {
    r = min(f.colour, vec3(1.0f - f.transmittance));
    t = vec3(f.transmittance);
  }
}

// P(beta): flake normals per solid angle, integral 1 over the hemisphere (the paper's
// Pr = 2 pi P(beta) sin beta d beta): a microfacet distribution D (normalised over the projected
// area) times cos beta. cos_beta is |n.z|.
LAMINA_FN float lamina_flake_orientation(int distribution, float cos_beta, float m) {
  return d_microfacet(distribution, cos_beta, m) * cos_beta;
}

// The angular part of a flake's reflection between binder directions l and v (z > 0), eq. 36's
// P(beta) / (4 cos l cos v), beta the angle of their half vector from the normal.
LAMINA_FN float lamina_flake_lobe(vec3 l, vec3 v, int distribution, float m) {
  if (l.z <= 0.0f || v.z <= 0.0f) return 0.0f;
  return lamina_flake_orientation(distribution, normalize(l + v).z, m) / (4.0f * l.z * v.z);
}

// tau(theta) h of eq. 21 along direction w, per channel, for flakes passing t along it:
// kappa h / cos theta + D <S> h <1 - t_p>(theta) / cos theta. The flakes' mean projected area
// <|cos alpha|> of eq. 10 is taken from Smith's identity for their distribution,
// int D(n) (w.n)+ dn = cos theta (1 + Lambda(w)) (the normalisation of Smith's masking,
// G1 = 1 / (1 + Lambda): Heitz 2014, "Understanding the masking-shadowing function"), counting
// both faces (the back faces add cos theta Lambda, since int D(n) (w.n) dn = cos theta) and cos beta
// as 1 (flakes close to the paint's plane, so that light meets them at theta, where t is taken):
// cos theta (1 + 2 Lambda(w)). Eq. 29 drops Lambda, which at grazing angles lets the glitter's lobe,
// whose integral grows as 1 + Lambda, reflect more light than the flakes intercept.
LAMINA_FN vec3 lamina_flake_depth_through(vec3 w, LAMINA_IN(LaminaFlakes) f, vec3 t, float kappa_h) {
  float lambda = max(lamina_smith_lambda(f.distribution, w, f.m), 0.0f);
  return vec3(kappa_h / max(w.z, LAMINA_MIN_DENOM)) + f.coverage * (1.0f + 2.0f * lambda) * (vec3(1.0f) - t);
}

LAMINA_FN vec3 lamina_flake_depth(vec3 w, LAMINA_IN(LaminaFlakes) f, float kappa_h) {
  vec3 r;
  vec3 t;
  lamina_flake_optics(f, w.z, r, t);
  return lamina_flake_depth_through(w, f, t, kappa_h);
}

// (1 - e^-x) / x: the share of a flake layer of optical depth x (both paths) that single
// scattering sees, its expansion near 0; per channel.
LAMINA_FN float lamina_flake_depth_share(float x) { return x < 1.0e-4f ? 1.0f - 0.5f * x : (1.0f - exp(-x)) / x; }
LAMINA_FN vec3 lamina_flake_depth_factor(vec3 x) {
  return vec3(lamina_flake_depth_share(x.x), lamina_flake_depth_share(x.y), lamina_flake_depth_share(x.z));
}

// Glitter, eq. 36 inside the boundary: D <S> h r_p(alpha) (1 - e^-x) / x P(beta) / (4 cos l cos v), x
// the depths along l and v (their sum, also returned), alpha the angle between l and the flake that
// mirrors it into v.
LAMINA_FN vec3 lamina_flake_glitter_and_depth(vec3 l, vec3 v, LAMINA_IN(LaminaFlakes) f, float kappa_h,
                                              LAMINA_OUT(vec3) x) {
  x = lamina_flake_depth(l, f, kappa_h) + lamina_flake_depth(v, f, kappa_h);
  vec3 r;
  vec3 t;
  lamina_flake_optics(f, dot(l, normalize(l + v)), r, t);
  return r * f.coverage * lamina_flake_depth_factor(x) * lamina_flake_lobe(l, v, f.distribution, f.m);
}

LAMINA_FN vec3 lamina_flake_glitter(vec3 l, vec3 v, LAMINA_IN(LaminaFlakes) f, float kappa_h) {
  if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
  vec3 x;
  return lamina_flake_glitter_and_depth(l, v, f, kappa_h, x);
}

// Q of eq. 26 as the paper approximates it after eq. 28: what the flake layer and the boundary
// above it return downwards of diffuse light from the substrate, halved,
//   Q = D<S>h / 2 int (1 - e^-2 tau h) / (2 tau h) r_p(theta) sin 2 theta d theta      (the flakes' part)
//       + 1/2 int e^-2 tau h r_{1/eta}(theta) sin 2 theta d theta                      (the boundary's),
// with sin 2 theta d theta = d(cos^2 theta): 32 midpoints in cos^2 theta. eta: binder over air.
LAMINA_FN vec3 lamina_flake_q_flakes(LAMINA_IN(LaminaFlakes) f, float kappa_h) {
  vec3 sum = vec3(0.0f);
  for (int k = 0; k < 32; ++k) {
    float c = sqrt((float(k) + 0.5f) / 32.0f);
    vec3 w = vec3(sqrt(1.0f - c * c), 0.0f, c);
    vec3 r;
    vec3 t;
    lamina_flake_optics(f, c, r, t);
    sum += lamina_flake_depth_factor(2.0f * lamina_flake_depth_through(w, f, t, kappa_h)) * r;
  }
  return (0.5f / 32.0f) * f.coverage * sum;
}

LAMINA_FN vec3 lamina_flake_q_boundary(LAMINA_IN(LaminaFlakes) f, float kappa_h, float eta) {
  vec3 sum = vec3(0.0f);
  for (int k = 0; k < 32; ++k) {
    float c = sqrt((float(k) + 0.5f) / 32.0f);
    vec3 w = vec3(sqrt(1.0f - c * c), 0.0f, c);
    sum += exp(-2.0f * lamina_flake_depth(w, f, kappa_h)) * fresnel_dielectric(c, 1.0f / eta);
  }
  return (0.5f / 32.0f) * sum;
}

// Shade, eq. 28 inside the boundary: the substrate's r_s / pi through the flakes both ways,
// e^-(tau(l) + tau(v)) h, raised by the light the layer sends back to it, 1 / (1 - 2 r_s Q); x the
// two depths' sum.
LAMINA_FN vec3 lamina_flake_shade_through(vec3 x, vec3 substrate, vec3 q) {
  return substrate * exp(-x) * LAMINA_INV_PI / max(vec3(1.0f) - 2.0f * substrate * q, vec3(LAMINA_MIN_DENOM));
}

LAMINA_FN vec3 lamina_flake_shade(vec3 l, vec3 v, LAMINA_IN(LaminaFlakes) f, float kappa_h, vec3 substrate, vec3 q) {
  if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
  return lamina_flake_shade_through(lamina_flake_depth(l, f, kappa_h) + lamina_flake_depth(v, f, kappa_h), substrate,
                                    q);
}

// --- substrate/flake_paint: the fast model under a layer -------------------------------------------
// Without binder absorption; the boundary above is the layer's, whose bounces the composition sums,
// so Q keeps only the flakes' part. A plain flake reflects at most what it does not pass (the
// checker refuses more for constants; a texture's values are taken so here). The shade splits into
// its value at normal incidence, a Lambertian term (the energy-conserving model's diffuse part), and
// the rest, which the flakes' longer paths at grazing angles take away (part of the lobe).

// What a shading point fixes of a flake paint: x0, the flake layer's depth at normal incidence both
// ways; the shade's Lambertian part, the shade at normal incidence both ways; and the paint's albedo
// there as lobe selection estimates it, the glitter's D <S> h r_p (1 - e^-x0) / x0 (its lobe
// integrates to about 1 there) plus pi times that part. A coated flake's film is taken at normal
// incidence once here and once in Q's loop: a shader then holds two copies of its kernel.
LAMINA_FN void lamina_flake_paint_resolve(LAMINA_IN(LaminaFlakes) f, vec3 substrate, LAMINA_OUT(vec3) x0,
                                          LAMINA_OUT(vec3) diffuse, LAMINA_OUT(vec3) albedo) {
  vec3 r;
  vec3 t;
  lamina_flake_optics(f, 1.0f, r, t);
  x0 = 2.0f * lamina_flake_depth_through(vec3(0.0f, 0.0f, 1.0f), f, t, 0.0f);
  diffuse = lamina_flake_shade_through(x0, substrate, lamina_flake_q_flakes(f, 0.0f));
  albedo = r * f.coverage * lamina_flake_depth_factor(x0) + LAMINA_PI * diffuse;
}

// A flake paint's BRDF inside the binder: glitter + shade, the shade's Lambertian part `diffuse`
// scaled by the longer paths' attenuation, from x0 to the depths along l and v (both from
// lamina_flake_paint_resolve). Straight-line code: the same three optics taken in a loop compiled
// four times slower on llvmpipe, for plain flakes too.
LAMINA_FN vec3 lamina_flake_paint_eval(vec3 l, vec3 v, LAMINA_IN(LaminaFlakes) f, vec3 diffuse, vec3 x0) {
  if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
  vec3 x;
  vec3 glitter = lamina_flake_glitter_and_depth(l, v, f, 0.0f, x);
  return glitter + diffuse * exp(x0 - x);
}

// The share of a flake paint's draws its glitter takes, by the glitter's albedo against the whole
// paint's (`albedo`, the glitter's plus pi times the diffuse part): the rest are cosine-weighted.
LAMINA_FN float lamina_flake_glitter_share(vec3 albedo, vec3 diffuse) {
  float total = lamina_luminance(albedo);
  return total > 0.0f ? clamp(lamina_luminance(albedo - LAMINA_PI * diffuse) / total, 0.0f, 1.0f) : 0.0f;
}
