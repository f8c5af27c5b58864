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

// P(beta): flake normals per solid angle, integral 1 over the hemisphere (the paper's
// Pr = 2 pi P(beta) sin beta d beta): Beckmann's D times cos beta. cos_beta is |n.z|.
LAMINA_FN float lamina_flake_orientation(float cos_beta, float m) { return d_beckmann(cos_beta, m) * cos_beta; }

// tau(theta) h of eq. 21 with eq. 29's <1 - t_p>(theta) = (1 - t_p) cos theta (flakes close to the
// paint's plane): kappa h / cos theta + D <S> h (1 - t_p).
LAMINA_FN float lamina_flake_depth(float cos_theta, float coverage, float transmittance, float kappa_h) {
  return kappa_h / max(cos_theta, LAMINA_MIN_DENOM) + coverage * (1.0f - transmittance);
}

// (1 - e^-x) / x: the share of a flake layer of optical depth x (both paths) that single
// scattering sees, its expansion near 0.
LAMINA_FN float lamina_flake_depth_factor(float x) { return x < 1.0e-4f ? 1.0f - 0.5f * x : (1.0f - exp(-x)) / x; }

// Glitter, eq. 36 inside the boundary: D <S> h r_p P(beta) (1 - e^-x) / (4 x cos l cos v), x the
// depths along l and v and beta the angle of their half vector from the normal.
LAMINA_FN vec3 lamina_flake_glitter(vec3 l, vec3 v, float coverage, vec3 reflectance, float transmittance,
                                    float kappa_h, float m) {
  if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(l + v);
  float x = lamina_flake_depth(l.z, coverage, transmittance, kappa_h) +
            lamina_flake_depth(v.z, coverage, transmittance, kappa_h);
  return reflectance *
         (coverage * lamina_flake_orientation(h.z, m) * lamina_flake_depth_factor(x) / (4.0f * l.z * v.z));
}

// Q of eq. 26 as the paper approximates it after eq. 28: what the flake layer and the boundary
// above it return downwards of diffuse light from the substrate, halved,
//   Q = D<S>h / 2 int (1 - e^-2 tau h) / (2 tau h) r_p sin 2 theta d theta
//       + 1/2 int e^-2 tau h r_{1/eta}(theta) sin 2 theta d theta,
// with sin 2 theta d theta = d(cos^2 theta): 32 midpoints in cos^2 theta. eta: binder over air.
LAMINA_FN vec3 lamina_flake_shade_q(float coverage, vec3 reflectance, float transmittance, float kappa_h, float eta) {
  float flakes = 0.0f;
  float boundary = 0.0f;
  for (int k = 0; k < 32; ++k) {
    float c = sqrt((float(k) + 0.5f) / 32.0f);
    float tau = 2.0f * lamina_flake_depth(c, coverage, transmittance, kappa_h);
    flakes += lamina_flake_depth_factor(tau);
    boundary += exp(-tau) * fresnel_dielectric(c, 1.0f / eta);
  }
  return (0.5f / 32.0f) * (coverage * reflectance * flakes + vec3(boundary));
}

// Shade, eq. 28 inside the boundary: the substrate's r_s / pi through the flakes both ways,
// e^-(tau(l) + tau(v)) h, raised by the light the layer sends back to it, 1 / (1 - 2 r_s Q).
LAMINA_FN vec3 lamina_flake_shade(vec3 l, vec3 v, float coverage, float transmittance, float kappa_h, vec3 substrate,
                                  vec3 q) {
  if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
  float x = lamina_flake_depth(l.z, coverage, transmittance, kappa_h) +
            lamina_flake_depth(v.z, coverage, transmittance, kappa_h);
  return substrate * (exp(-x) * LAMINA_INV_PI) / max(vec3(1.0f) - 2.0f * substrate * q, vec3(LAMINA_MIN_DENOM));
}
