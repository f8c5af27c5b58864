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

}  // namespace

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
  glm::vec3 f0 = glm::min(dielectric_f0(p.ior) * p.specular_color, glm::vec3(1.0f)) * p.specular;
  glm::vec3 dielectric_fresnel = glm::mix(f0, glm::vec3(p.specular), fresnel_w);
  glm::vec3 dielectric_a = dielectric_fresnel * specular;
  glm::vec3 dielectric_b = k::lambert(glm::vec3(1.0f - max_value(dielectric_fresnel)));

  // Metal (sec. B.3.5): specular_brdf * (baseColor + (1 - baseColor) fresnel_w), affine in baseColor.
  float metal_a = specular * fresnel_w;
  float metal_b = specular * (1.0f - fresnel_w);

  // material = mix(dielectric_brdf, metal_brdf, metallic) (sec. B.3.5).
  out.a = glm::mix(dielectric_a, glm::vec3(metal_a), p.metallic);
  out.b = glm::mix(dielectric_b, glm::vec3(metal_b), p.metallic);

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
