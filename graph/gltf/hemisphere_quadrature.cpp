#include "graph/gltf/hemisphere_quadrature.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "graph/hammersley.h"

namespace lamina::gltf {

namespace {

constexpr float kPi = 3.14159265358979323846f;

float cosine_pdf(glm::vec3 wi) { return wi.z > 0.0f ? wi.z / kPi : 0.0f; }

// Density of wi when the half-vector is drawn with density D(h) cos(theta_h) and wo reflected about
// it: D(h) cos(theta_h) / (4 |wo.h|) (Walter et al. 2007, eq. 14 and 38).
float ggx_pdf(float alpha, glm::vec3 wi, glm::vec3 wo) {
  glm::vec3 sum = wi + wo;
  float length = glm::length(sum);
  if (wi.z <= 0.0f || length <= 0.0f) return 0.0f;
  glm::vec3 h = sum / length;
  float wo_dot_h = std::abs(glm::dot(wo, h));
  if (h.z <= 0.0f || wo_dot_h <= 0.0f) return 0.0f;
  return ggx_d(alpha, h) * h.z / (4.0f * wo_dot_h);
}

}  // namespace

float ggx_d(float alpha, glm::vec3 h) {
  if (h.z <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  // (N.H)^2 (alpha^2 - 1) + 1 = (N.H)^2 alpha^2 + (1 - (N.H)^2).
  float denominator = h.z * h.z * a2 + (h.x * h.x + h.y * h.y);
  return a2 / (kPi * denominator * denominator);
}

std::vector<WeightedDirection> hemisphere_quadrature(glm::vec3 wo, std::span<const float> alphas, int per_strategy) {
  std::vector<WeightedDirection> out;
  if (per_strategy <= 0 || wo.z <= 0.0f) return out;
  const int strategies = 1 + int(alphas.size());
  const float total = float(strategies * per_strategy);
  out.reserve(size_t(strategies * per_strategy));
  for (int s = 0; s < strategies; ++s) {
    for (int i = 0; i < per_strategy; ++i) {
      const glm::vec2 u = hammersley(uint32_t(i), uint32_t(per_strategy));
      const float u1 = u.x, phi = 2.0f * kPi * u.y;
      glm::vec3 wi;
      if (s == 0) {
        // Cosine-weighted: Malley's method (a uniform disk point projected up).
        float r = std::sqrt(u1);
        wi = glm::vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1)));
      } else {
        // GGX half-vector: tan(theta_h) = alpha sqrt(u1 / (1 - u1)) (Walter et al. 2007, eq. 35).
        float tan_theta = alphas[size_t(s - 1)] * std::sqrt(u1 / (1.0f - u1));
        float cos_theta = 1.0f / std::sqrt(1.0f + tan_theta * tan_theta);
        float sin_theta = tan_theta * cos_theta;
        glm::vec3 h(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
        wi = 2.0f * glm::dot(wo, h) * h - wo;
      }
      WeightedDirection d;
      d.wi = wi;
      if (wi.z > 0.0f) {
        float pdf = cosine_pdf(wi);
        for (float alpha : alphas) pdf += ggx_pdf(alpha, wi, wo);
        pdf /= float(strategies);
        if (pdf > 0.0f) d.weight = wi.z / (total * pdf);
      }
      out.push_back(d);
    }
  }
  return out;
}

}  // namespace lamina::gltf
