// A deterministic direction set over the upper hemisphere for integrating f(wi, wo) cos(theta_i) at a
// fixed wo: a Hammersley point set driven through several sampling strategies (cosine-weighted and
// GGX half-vector sampling at given alphas) and combined by the balance heuristic (Veach 1997,
// sec. 9.2.2), so each direction's weight is 1 / (total count * mixture pdf). The sampling and the
// densities are lamina's kernels (nodes/kernels/diffuse.glsl and microfacet.glsl).
#pragma once

#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace lamina::gltf {

// GGX in the kernels' numbering of microfacet distributions (microfacet.glsl: 0 Beckmann, 1 Blinn,
// 2 GGX with alpha = m).
inline constexpr int kGgx = 2;

// Density per solid angle of wi when a GGX normal h of the given alpha is drawn with density
// D(h) cos(theta_h) (kernels::sample_microfacet_normal) and wo is reflected about it; 0 unless wi
// and wo are both above the horizon.
float ggx_reflection_pdf(float alpha, glm::vec3 wi, glm::vec3 wo);

struct WeightedDirection {
  glm::vec3 wi{0.0f, 0.0f, 1.0f};
  float weight = 0.0f;  // cos(theta_i) / (count * mixture pdf): sum of f * weight estimates the albedo
};

// `per_strategy` points through each of 1 + alphas.size() strategies; directions below the horizon
// are kept with weight 0 (they still count in the total, which keeps the estimator unbiased).
std::vector<WeightedDirection> hemisphere_quadrature(glm::vec3 wo, std::span<const float> alphas, int per_strategy);

}  // namespace lamina::gltf
