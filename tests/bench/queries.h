// The random queries the CPU benchmarks (evaluator_bench.cpp) and the instruction counts
// (query_driver.cpp, tools/count_instructions.sh) run: the same directions in both, so that a
// count and a time speak of the same work.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <random>
#include <vector>

namespace lamina::bench {

struct Queries {
  std::vector<glm::vec3> wi, wo;  // upper-hemisphere directions, cosines from 0.01 up
  std::vector<glm::vec2> u;       // a lobe's two uniform numbers
  std::vector<float> u_lobe;      // the lobe choice's

  explicit Queries(size_t count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    auto direction = [&] {
      float z = std::max(uniform(rng), 0.01f), phi = 6.2831853f * uniform(rng);
      float s = std::sqrt(1.0f - z * z);
      return glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
    };
    for (size_t i = 0; i < count; ++i) {
      wi.push_back(direction());
      wo.push_back(direction());
      u.emplace_back(uniform(rng), uniform(rng));
      u_lobe.push_back(uniform(rng));
    }
  }
};

}  // namespace lamina::bench
