// How a rendered radiance becomes a displayed value: the exposure, a tone map, the sRGB curve.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

#include "nodes/kernels/kernels.h"

namespace lamina::render {

enum class ToneMap {
  Clip,      // linear, clipped at 1: what a comparison with a shader wants
  Reinhard,  // x / (1 + x) per channel (Reinhard et al. 2002, eq. 3): highlights roll off instead of clipping
};

// The sRGB-encoded value of `radiance` times `scale` (2^exposure) after the tone map; black where it
// is not finite.
inline glm::vec3 display_srgb(glm::vec3 radiance, float scale, ToneMap tone_map) {
  glm::vec3 c = radiance * scale;
  if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))) return glm::vec3(0.0f);
  c = glm::max(c, glm::vec3(0.0f));
  if (tone_map == ToneMap::Reinhard) c = c / (glm::vec3(1.0f) + c);
  return kernels::srgb_from_linear(glm::min(c, glm::vec3(1.0f)));
}

}  // namespace lamina::render
