// texture/flakes (nodes/texture_flakes.cpp): Elek's flake normals, against the formula's own
// distribution drawn here with an independent generator, and through the evaluator.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "graph/cpu/evaluator.h"
#include "graph/cpu_test_support.h"
#include "nodes/kernels/kernels.h"
#include "test_support.h"

using namespace lamina;
namespace k = lamina::kernels;
using glm::vec3;

namespace {

// The share of normals tilted more than `degrees` from +z.
template <class Normal>
double share_beyond(double degrees, int count, Normal normal) {
  int beyond = 0;
  for (int i = 0; i < count; ++i) beyond += normal(i).z < std::cos(degrees * test::kPi / 180.0);
  return double(beyond) / count;
}

}  // namespace

TEST_CASE("flake normals follow Elek's normalize(max(d, 1) z + 2 c - 1) with c uniform per cell") {
  // The formula's distribution, drawn with the standard library's generator: the share of flakes
  // tilted beyond 20, 40 and 60 degrees at view distances 1 and 4, against 40000 cells' hashes.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int count = 40000;
  for (float d : {1.0f, 4.0f}) {
    CAPTURE(d);
    for (double degrees : {20.0, 40.0, 60.0}) {
      CAPTURE(degrees);
      const double expected = share_beyond(degrees, count, [&](int) {
        const glm::dvec3 c(u(rng), u(rng), u(rng));
        return glm::normalize(glm::dvec3(0.0, 0.0, double(d)) + 2.0 * c - 1.0);
      });
      const double got = share_beyond(degrees, count, [&](int i) {
        return k::lamina_flake_normal(vec3(float(i % 200) + 0.5f, float(i / 200) + 0.5f, 0.0f), 7u, d);
      });
      CHECK(std::abs(got - expected) <= 0.01);  // both within about 0.0025 (one standard error)
    }
  }
}

TEST_CASE("a flake is one normal across its cell, unit, above the horizon, and closer to +z further away") {
  const vec3 a = k::lamina_flake_normal(vec3(3.1f, 5.2f, 0.0f), 2u, 1.0f);
  CHECK(k::lamina_flake_normal(vec3(3.9f, 5.8f, 0.0f), 2u, 1.0f) == a);  // unfiltered: the same flake
  CHECK(k::lamina_flake_normal(vec3(4.1f, 5.2f, 0.0f), 2u, 1.0f) != a);  // the next one differs
  CHECK(k::lamina_flake_normal(vec3(3.1f, 5.2f, 0.0f), 3u, 1.0f) != a);  // and another seed
  double tilt_near = 0.0, tilt_far = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const vec3 p(float(i) + 0.5f, 0.5f, 0.0f);
    const vec3 n = k::lamina_flake_normal(p, 0u, 1.0f), f = k::lamina_flake_normal(p, 0u, 8.0f);
    CHECK(std::abs(glm::length(n) - 1.0f) < 1e-6f);
    CHECK(n.z >= 0.0f);
    tilt_near += std::acos(double(n.z));
    tilt_far += std::acos(double(f.z));
  }
  CHECK(tilt_far < 0.25 * tilt_near);
  // A distance that is not a number, or below 1, reads as 1 (Elek's max).
  for (float d : {std::nanf(""), -3.0f, 0.0f, 0.5f}) CHECK(k::lamina_flake_normal(vec3(3.1f, 5.2f, 0.0f), 2u, d) == a);
}

TEST_CASE("flake car paint sparkles: its BRDF differs between flakes, not within one, and fades with distance") {
  const cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples" / "materials" / "flake_car_paint.json");
  const vec3 wi = glm::normalize(vec3(0.3f, 0.1f, 1.0f)), wo = glm::normalize(vec3(-0.4f, 0.0f, 1.0f));
  auto at = [&](glm::vec2 uv, float distance) {
    ShadingContext c;
    c.uv = uv;
    c.view_distance = distance;
    return e.eval(c, wi, wo);
  };
  // 1000 flakes per unit: (0.2501, 0.5001) and (0.2509, 0.5009) share a flake.
  CHECK(at({0.2501f, 0.5001f}, 1.0f) == at({0.2509f, 0.5009f}, 1.0f));
  int differ = 0;
  for (int i = 0; i < 20; ++i)
    differ += at({0.2505f + 0.001f * float(i), 0.5005f}, 1.0f) != at({0.2505f, 0.5005f}, 1.0f);
  CHECK(differ >= 15);
  // Far away the flakes lie nearly flat: their spread of f shrinks.
  double spread_near = 0.0, spread_far = 0.0;
  for (int i = 0; i < 20; ++i) {
    const glm::vec2 uv(0.0005f + 0.001f * float(i), 0.3005f);
    spread_near += std::abs(double(at(uv, 1.0f).y - at({0.0005f, 0.3005f}, 1.0f).y));
    spread_far += std::abs(double(at(uv, 50.0f).y - at({0.0005f, 0.3005f}, 50.0f).y));
  }
  CHECK(spread_far < 0.2 * spread_near);
}
