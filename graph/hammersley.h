// The Hammersley point set that lamina's deterministic quadratures share.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace lamina {

// Van der Corput radical inverse in base 2 (the bits of i mirrored about the binary point).
inline float radical_inverse_base2(uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return float(bits) * 2.3283064365386963e-10f;  // 2^-32
}

// Point i of an n-point Hammersley set in [0, 1)^2, the first coordinate at the cell centre.
inline glm::vec2 hammersley(uint32_t i, uint32_t n) {
  return glm::vec2((float(i) + 0.5f) / float(n), radical_inverse_base2(i));
}

}  // namespace lamina
