// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms
// for Random Number Generation", the XSH RR 64/32 member): a 64-bit LCG whose state is output
// through a xorshift and a data-dependent rotation; `stream` selects one of 2^63 sequences. The
// reference solver's random numbers.
#pragma once

#include <bit>
#include <cstdint>
#include <glm/glm.hpp>

namespace lamina::cpu {

class Pcg32 {
 public:
  Pcg32(uint64_t seed, uint64_t stream) : inc_((stream << 1u) | 1u) {
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const auto rotation = uint32_t(old >> 59u);
    return std::rotr(xorshifted, int(rotation));
  }
  // Uniform in [0, 1): the top 24 bits, exactly representable as a float.
  float uniform() { return float(next() >> 8u) * 0x1p-24f; }
  glm::vec3 uniform3() {
    const float a = uniform(), b = uniform();
    return glm::vec3(a, b, uniform());
  }

 private:
  uint64_t state_ = 0;
  uint64_t inc_;
};

}  // namespace lamina::cpu
