// glTF 2.0's reference BRDF (specification, Appendix B, "Sample Implementation" sec. B.3) with
// KHR_materials_ior, KHR_materials_specular and KHR_materials_clearcoat, as their specifications'
// "Implementation" sections compose it.
#include <algorithm>
#include <array>
#include <cmath>

#include "graph/gltf/hemisphere_quadrature.h"
#include "graph/gltf/pbr_fit.h"

namespace lamina::gltf {

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kMinAlpha = 1.0e-6f;

float pow5(float x) { return (x * x) * (x * x) * x; }
float alpha_of(float roughness) { return std::max(roughness * roughness, kMinAlpha); }

// specular_brdf(alpha) = Vis * D (Appendix B, sec. B.3.2 "Specular BRDF"), with the separable Smith
// visibility Vis = chi(H.L) / (|N.L| + sqrt(a^2 + (1 - a^2)(N.L)^2)) * chi(H.V) / (|N.V| + sqrt(...)).
float specular_brdf(float alpha, glm::vec3 wi, glm::vec3 wo, glm::vec3 h) {
  float a2 = alpha * alpha;
  if (glm::dot(h, wi) <= 0.0f || glm::dot(h, wo) <= 0.0f) return 0.0f;
  float n_dot_l = std::abs(wi.z), n_dot_v = std::abs(wo.z);
  float vis_l = 1.0f / (n_dot_l + std::sqrt(a2 + (1.0f - a2) * n_dot_l * n_dot_l));
  float vis_v = 1.0f / (n_dot_v + std::sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v));
  return vis_l * vis_v * ggx_d(alpha, h);
}

float max_value(glm::vec3 c) { return std::max(c.x, std::max(c.y, c.z)); }

}  // namespace

PbrAffine pbr_eval_affine(const PbrParams& p, glm::vec3 wi, glm::vec3 wo) {
  PbrAffine out;
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return out;
  glm::vec3 h = glm::normalize(wi + wo);
  // fresnel_w = (1 - |V.H|)^5 (sec. B.3.3 "Fresnel", Schlick 1994).
  float fresnel_w = pow5(1.0f - std::min(std::abs(glm::dot(wo, h)), 1.0f));
  float specular = specular_brdf(alpha_of(p.roughness), wi, wo, h);

  // Dielectric (sec. B.3.4; KHR_materials_ior replaces 0.04 with ((ior - 1)/(ior + 1))^2;
  // KHR_materials_specular, "Implementation": dielectric_f0 = min(f0_ior * specularColor, 1) *
  // specular, dielectric_f90 = specular, and the diffuse weighted by 1 - max_value(fresnel)).
  float ior_ratio = (p.ior - 1.0f) / (p.ior + 1.0f);
  glm::vec3 dielectric_f0 = glm::min(ior_ratio * ior_ratio * p.specular_color, glm::vec3(1.0f)) * p.specular;
  glm::vec3 dielectric_fresnel = glm::mix(dielectric_f0, glm::vec3(p.specular), fresnel_w);
  glm::vec3 dielectric_a = dielectric_fresnel * specular;
  glm::vec3 dielectric_b = glm::vec3((1.0f - max_value(dielectric_fresnel)) / kPi);

  // Metal (sec. B.3.4): specular_brdf * (baseColor + (1 - baseColor) fresnel_w), affine in baseColor.
  float metal_a = specular * fresnel_w;
  float metal_b = specular * (1.0f - fresnel_w);

  // material = mix(dielectric_brdf, metal_brdf, metallic) (sec. B.3.4).
  out.a = glm::mix(dielectric_a, glm::vec3(metal_a), p.metallic);
  out.b = glm::mix(dielectric_b, glm::vec3(metal_b), p.metallic);

  if (p.clearcoat > 0.0f) {
    // KHR_materials_clearcoat, "Implementation": clearcoat_fresnel = f0 + (1 - f0)(1 - |V.Nc|)^5 with
    // f0 from ior 1.5 and Nc = N; coated = mix(material, clearcoat_brdf, clearcoat * clearcoat_fresnel).
    constexpr float kCoatRatio = (1.5f - 1.0f) / (1.5f + 1.0f);
    constexpr float kCoatF0 = kCoatRatio * kCoatRatio;
    float coat_fresnel = kCoatF0 + (1.0f - kCoatF0) * pow5(1.0f - std::min(wo.z, 1.0f));
    float coat_weight = p.clearcoat * coat_fresnel;
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
