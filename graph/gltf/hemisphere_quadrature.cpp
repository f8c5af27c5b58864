#include "graph/gltf/hemisphere_quadrature.h"

#include <cstdint>

#include "graph/hammersley.h"
#include "nodes/kernels/kernels.h"

namespace lamina::gltf {

namespace k = lamina::kernels;

float ggx_reflection_pdf(float alpha, glm::vec3 wi, glm::vec3 wo) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  // The layered lobes' reflection density (stack.glsl): D(h) cos(theta_h) / (4 |wo.h|).
  return k::lamina_reflection_density(kGgx, alpha, wo, wi);
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
      // Strategy 0 is cosine-weighted; the others reflect wo about a GGX normal of their alpha.
      const glm::vec3 wi =
          s == 0 ? k::sample_cosine(u) : glm::reflect(-wo, k::sample_microfacet_normal(kGgx, alphas[size_t(s - 1)], u));
      WeightedDirection d;
      d.wi = wi;
      if (wi.z > 0.0f) {
        float pdf = k::pdf_cosine(wi.z);
        for (float alpha : alphas) pdf += ggx_reflection_pdf(alpha, wi, wo);
        pdf /= float(strategies);
        if (pdf > 0.0f) d.weight = wi.z / (total * pdf);
      }
      out.push_back(d);
    }
  }
  return out;
}

}  // namespace lamina::gltf
