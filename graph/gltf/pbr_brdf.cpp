// glTF 2.0's reference BRDF (specification, Appendix B "BRDF Implementation", sec. B.3 "Sample
// Implementation") with KHR_materials_ior, KHR_materials_specular and KHR_materials_clearcoat, as
// their specifications' "Implementation" sections compose it. Every leaf formula (D, G, Schlick's
// Fresnel, Lambert, F0 from an index) is lamina's kernel (nodes/kernels/*.glsl); this file only
// composes them as the specifications do.
#include <algorithm>
#include <array>
#include <cmath>

#include "graph/gltf/hemisphere_quadrature.h"
#include "graph/gltf/pbr_fit.h"
#include "nodes/kernels/kernels.h"

namespace lamina::gltf {

namespace {

namespace k = lamina::kernels;

// alpha = roughness^2 (Appendix B, sec. B.2.3 "Microfacet Surfaces"). Roughness 0 is a delta lobe,
// which no BRDF value represents: alpha is clamped to a small positive value, as the note in
// sec. B.3.2 asks (added by KhronosGroup/glTF#2556), the kernels' smooth limit.
float alpha_of(float roughness) { return std::max(roughness * roughness, k::LAMINA_MIN_SLOPE); }

// specular_brdf(alpha) = G D / (4 |N.L| |N.V|) (sec. B.3.2 "Specular BRDF") with the GGX D and the
// separable Smith G = G1(L) G1(V) times chi+(H.L) chi+(H.V), as sec. B.3.2 wrote it before
// KhronosGroup/glTF#2541 (see pbr_fit.h). Its G1(X) = 2 |N.X| / (|N.X| + sqrt(alpha^2 +
// (1 - alpha^2)(N.X)^2)) is g1_smith_ggx, since alpha^2 + (1 - alpha^2) c^2 = c^2 + alpha^2 (1 - c^2);
// so this is torrance_sparrow with F = 1, and G / (4 |N.L| |N.V|) is the section's
// Vis = 1 / ((|N.L| + sqrt(...)) (|N.V| + sqrt(...))). wi and wo are above the horizon here.
float specular_brdf(float alpha, glm::vec3 wi, glm::vec3 wo, glm::vec3 h) {
  if (glm::dot(h, wi) <= 0.0f || glm::dot(h, wo) <= 0.0f) return 0.0f;
  float d = k::d_microfacet_h(kGgx, h, alpha);
  float g = k::g_smith_ggx(wi.z, wo.z, alpha);
  return k::torrance_sparrow(glm::vec3(1.0f), d, g, wi.z, wo.z).x;
}

// F0 of a dielectric of index ior under air: ((ior - 1) / (ior + 1))^2 (sec. B.3.4 "Fresnel"), the
// kernels' conductor_f0 without absorption.
float dielectric_f0(float ior) { return k::conductor_f0(glm::vec3(ior), glm::vec3(0.0f)).x; }

float max_value(glm::vec3 c) { return std::max(c.x, std::max(c.y, c.z)); }

// The extension's sensitivity: Belcour and Barla's Gaussian fits of the CIE 1931 functions, Fourier
// transformed at the optical path difference opd (nm), each lobe's phase shifted by `shift`, to
// linear Rec. 709 without balancing to white (as published).
glm::vec3 iridescence_sensitivity(float opd, float shift) {
  const float phase = 2.0f * k::LAMINA_PI * opd * 1.0e-9f;
  const glm::vec3 val(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  const glm::vec3 pos(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  const glm::vec3 var(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  glm::vec3 xyz =
      val * glm::sqrt(2.0f * k::LAMINA_PI * var) * glm::cos(pos * phase + shift) * glm::exp(-(phase * phase) * var);
  xyz.x += 9.7470e-14f * std::sqrt(2.0f * k::LAMINA_PI * 4.5282e+09f) * std::cos(2.2399e+06f * phase + shift) *
           std::exp(-4.5282e+09f * phase * phase);
  xyz /= 1.0685e-7f;
  return k::lamina_film_rgb_of_xyz(xyz);
}

}  // namespace

glm::vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos1, float thickness, glm::vec3 base_f0) {
  auto ior_to_f0 = [](glm::vec3 t, float i) { return (t - i) / (t + i) * ((t - i) / (t + i)); };
  // A film thinner than 30 nm fades into the medium above (smoothstep), as the sample renderer does.
  const float film = glm::mix(outside_ior, film_ior, glm::smoothstep(0.0f, 0.03f, thickness));
  const float sin2 = (outside_ior / film) * (outside_ior / film) * (1.0f - cos1 * cos1);
  if (sin2 >= 1.0f) return glm::vec3(1.0f);
  const float cos2 = std::sqrt(1.0f - sin2);
  const float r12 = k::fresnel_schlick(cos1, ior_to_f0(glm::vec3(film), outside_ior).x), t121 = 1.0f - r12;
  const float phi21 = k::LAMINA_PI - (film < outside_ior ? k::LAMINA_PI : 0.0f);
  const glm::vec3 root_f0 = glm::sqrt(base_f0 + 0.0001f);
  const glm::vec3 base_ior = (1.0f + root_f0) / (1.0f - root_f0);
  const glm::vec3 r23 = k::fresnel_schlick_rgb(cos2, ior_to_f0(base_ior, film));
  const float opd = 2.0f * film * thickness * cos2;
  const glm::vec3 r123 = glm::clamp(r12 * r23, 1e-5f, 0.9999f), root = glm::sqrt(r123);
  const glm::vec3 rs = t121 * t121 * r23 / (1.0f - r123);
  glm::vec3 out = r12 + rs, cm = rs - t121;
  for (int m = 1; m <= 2; ++m) {
    cm *= root;
    // Each channel's phase: phi21 and the base's (0 over a denser base, pi under a rarer one); the
    // sensitivity at each of the two, once.
    const glm::vec3 denser = iridescence_sensitivity(float(m) * opd, float(m) * phi21);
    const glm::vec3 rarer = iridescence_sensitivity(float(m) * opd, float(m) * (phi21 + k::LAMINA_PI));
    glm::vec3 s;
    for (int c = 0; c < 3; ++c) s[c] = base_ior[c] < film ? rarer[c] : denser[c];
    out += cm * 2.0f * s;
  }
  return glm::max(out, glm::vec3(0.0f));
}

PbrAffine pbr_eval_affine(const PbrParams& p, glm::vec3 wi, glm::vec3 wo) {
  PbrAffine out;
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return out;
  glm::vec3 h = glm::normalize(wi + wo);
  // fresnel_w = (1 - |V.H|)^5 (sec. B.3.5 "Metal BRDF and Dielectric BRDF"): Schlick's polynomial
  // (sec. B.3.4) with f0 = 0.
  float fresnel_w = k::fresnel_schlick(std::abs(glm::dot(wo, h)), 0.0f);
  float specular = specular_brdf(alpha_of(p.roughness), wi, wo, h);

  // Dielectric (sec. B.3.5; KHR_materials_ior replaces 0.04 with ((ior - 1)/(ior + 1))^2;
  // KHR_materials_specular, "Implementation": dielectric_f0 = min(f0_ior * specularColor, 1) *
  // specular, dielectric_f90 = specular, dielectric_fresnel = mix(dielectric_f0, dielectric_f90,
  // fresnel_w), and the diffuse_brdf (sec. B.3.3, Lambert) weighted by 1 - max_value(fresnel)).
  const glm::vec3 f0_coloured = glm::min(dielectric_f0(p.ior) * p.specular_color, glm::vec3(1.0f));
  glm::vec3 f0 = f0_coloured * p.specular;
  glm::vec3 dielectric_fresnel = glm::mix(f0, glm::vec3(p.specular), fresnel_w);
  glm::vec3 dielectric_a = dielectric_fresnel * specular;
  glm::vec3 dielectric_b = k::lambert(glm::vec3(1.0f - max_value(dielectric_fresnel)));

  // Metal (sec. B.3.5): specular_brdf * (baseColor + (1 - baseColor) fresnel_w), affine in baseColor.
  glm::vec3 metal_a(specular * fresnel_w);
  glm::vec3 metal_b(specular * (1.0f - fresnel_w));

  if (p.iridescence > 0.0f) {
    // KHR_materials_iridescence, "Implementation Notes": F = mix(F_schlick, F_iridescence,
    // iridescenceFactor) in both BRDFs, over air, at the V.H Schlick's term takes (the sample
    // renderer takes N.V); the dielectric's base F0 is its own (scaled by specularFactor as its
    // Fresnel term is), the metal's its base colour.
    const float cos1 = std::abs(glm::dot(wo, h));
    const float t = p.iridescence;
    // Each film only where its BRDF has weight (the fit's films are wholly metallic).
    if (p.metallic < 1.0f) {
      const glm::vec3 film_dielectric =
          iridescence_fresnel(1.0f, p.iridescence_ior, cos1, p.iridescence_thickness, f0_coloured);
      dielectric_fresnel = glm::mix(dielectric_fresnel, film_dielectric * p.specular, t);
      dielectric_a = dielectric_fresnel * specular;
      dielectric_b = k::lambert(glm::vec3(1.0f - max_value(dielectric_fresnel)));
    }
    if (p.metallic > 0.0f) {
      const glm::vec3 film_metal =
          iridescence_fresnel(1.0f, p.iridescence_ior, cos1, p.iridescence_thickness, p.base_color);
      metal_a = metal_a * (1.0f - t) + film_metal * (specular * t);
      metal_b *= 1.0f - t;
    }
  }

  // material = mix(dielectric_brdf, metal_brdf, metallic) (sec. B.3.5).
  out.a = glm::mix(dielectric_a, metal_a, p.metallic);
  out.b = glm::mix(dielectric_b, metal_b, p.metallic);

  if (p.clearcoat > 0.0f) {
    // KHR_materials_clearcoat, "Implementation": clearcoat_fresnel = f0 + (1 - f0)(1 - |V.Nc|)^5 with
    // f0 from ior 1.5 and Nc = N; coated = mix(material, clearcoat_brdf, clearcoat * clearcoat_fresnel).
    float coat_weight = p.clearcoat * k::fresnel_schlick(wo.z, dielectric_f0(1.5f));
    float coat = specular_brdf(alpha_of(p.clearcoat_roughness), wi, wo, h);
    out.a = out.a * (1.0f - coat_weight) + glm::vec3(coat_weight * coat);
    out.b *= 1.0f - coat_weight;
  }
  return out;
}

glm::vec3 pbr_eval(const PbrParams& p, glm::vec3 wi, glm::vec3 wo) {
  PbrAffine t = pbr_eval_affine(p, wi, wo);
  return t.a + t.b * p.base_color;
}

glm::vec3 pbr_albedo(const PbrParams& p, glm::vec3 wo, int points) {
  if (!(wo.z > 0.0f) || points <= 0) return glm::vec3(0.0f);
  // Cosine-weighted sampling for the diffuse term plus GGX sampling at each lobe's alpha.
  std::array<float, 2> alphas{alpha_of(p.roughness), alpha_of(p.clearcoat_roughness)};
  size_t lobes = p.clearcoat > 0.0f ? 2 : 1;
  int per_strategy = std::max(1, points / int(lobes + 1));
  glm::vec3 sum(0.0f);
  for (const WeightedDirection& d : hemisphere_quadrature(wo, std::span(alphas.data(), lobes), per_strategy))
    if (d.weight > 0.0f) sum += pbr_eval(p, d.wi, wo) * d.weight;
  return sum;
}

}  // namespace lamina::gltf
