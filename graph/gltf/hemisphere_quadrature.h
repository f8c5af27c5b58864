// A deterministic direction set over the upper hemisphere for integrating f(wi, wo) cos(theta_i) at a
// fixed wo: a Hammersley point set driven through several sampling strategies (cosine-weighted and
// GGX half-vector sampling at given alphas) and combined by the balance heuristic (Veach 1997,
// sec. 9.2.2), so each direction's weight is 1 / (total count * mixture pdf).
#pragma once

#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace lamina::gltf {

// GGX / Trowbridge-Reitz normal distribution D(h) for a unit half-vector h in the local frame
// (Walter et al. 2007, eq. 33); 1 - (N.H)^2 is taken as hx^2 + hy^2 so that tiny alphas stay exact.
float ggx_d(float alpha, glm::vec3 h);

struct WeightedDirection {
  glm::vec3 wi{0.0f, 0.0f, 1.0f};
  float weight = 0.0f;  // cos(theta_i) / (count * mixture pdf): sum of f * weight estimates the albedo
};

// `per_strategy` points through each of 1 + alphas.size() strategies; directions below the horizon
// are kept with weight 0 (they still count in the total, which keeps the estimator unbiased).
std::vector<WeightedDirection> hemisphere_quadrature(glm::vec3 wo, std::span<const float> alphas, int per_strategy);

}  // namespace lamina::gltf
