// The `normal` input of interfaces and substrates (nodes/normal_param.cpp) and the tilted entries of
// the kernels' walks (nodes/kernels/stack.glsl, "tilted entries"), against values worked out here.
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

// One material: a Lambert base of albedo 0.6, or a clear coat of 1.5 over it, with the given
// "normal" members ("" for none) on the base and the coat's interface.
cpu::Evaluator tilted(bool coated, const std::string& base_normal, const std::string& coat_normal = "") {
  const std::string base = R"({"id": "base", "type": "substrate/lambert", "albedo": [0.6, 0.6, 0.6])" +
                           (base_normal.empty() ? "" : R"(, "normal": )" + base_normal) + "}";
  const std::string coat = R"({"id": "coat", "type": "layer", "interface": "@top", "base": "@base"},
      {"id": "top", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 10)" +
                           (coat_normal.empty() ? "" : R"(, "normal": )" + coat_normal) + "}, ";
  return test::evaluator_from_text(R"({"format": 1, "materials": [{"name": "m", "surface": ")" +
                                   std::string(coated ? "@coat" : "@base") + R"(", "nodes": [)" + (coated ? coat : "") +
                                   base + "]}]}");
}

vec3 random_upper(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float z = u(rng), phi = 2.0f * float(test::kPi) * u(rng), s = std::sqrt(1.0f - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

}  // namespace

TEST_CASE("an entry's frame is orthonormal around its normal, and the identity for +z, bit for bit") {
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const vec3 n = k::lamina_entry_normal(random_upper(rng) + vec3(0.0f, 0.0f, 0.05f));
    vec3 x(0.0f), y(0.0f);
    k::lamina_entry_tangents(n, x, y);
    CHECK(std::abs(glm::dot(x, y)) < 1e-6f);
    CHECK(std::abs(glm::dot(x, n)) < 1e-6f);
    CHECK(std::abs(glm::length(x) - 1.0f) < 1e-6f);
    CHECK(glm::length(glm::cross(x, y) - n) < 1e-5f);  // right-handed: x cross y = n
  }
  vec3 x(0.0f), y(0.0f);
  k::lamina_entry_tangents(vec3(0.0f, 0.0f, 1.0f), x, y);
  k::LaminaParams p{};
  p.normal = vec3(0.0f, 0.0f, 1.0f);
  p.frame_x = x;
  p.frame_y = y;
  for (int i = 0; i < 1000; ++i) {
    const vec3 w = random_upper(rng);
    CHECK(k::lamina_to_entry(p, w) == w);
    CHECK(k::lamina_from_entry(p, w) == w);
  }
}

TEST_CASE("a normal input is normalised, and one at or below the horizon is raised to z = 0.05") {
  CHECK(k::lamina_entry_normal(vec3(0.0f)) == vec3(0.0f, 0.0f, 1.0f));
  CHECK(glm::length(k::lamina_entry_normal(vec3(0.0f, 0.0f, 3.0f)) - vec3(0.0f, 0.0f, 1.0f)) < 1e-7f);
  const vec3 flipped = k::lamina_entry_normal(vec3(1.0f, 0.0f, -1.0f));
  CHECK(flipped.z == doctest::Approx(0.05 / std::sqrt(1.0 + 0.05 * 0.05)).epsilon(1e-6));
  CHECK(flipped.x == doctest::Approx(1.0 / std::sqrt(1.0 + 0.05 * 0.05)).epsilon(1e-6));
}

TEST_CASE("a normal of +z changes no bit of a stack's BRDF, sampling or pdf") {
  const cpu::Evaluator plain = tilted(true, ""), explicit_z = tilted(true, "[0, 0, 1]", "[0, 0, 1]");
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const vec3 wi = random_upper(rng), wo = random_upper(rng);
    CHECK(plain.eval({}, wi, wo) == explicit_z.eval({}, wi, wo));
    CHECK(plain.pdf({}, wi, wo) == explicit_z.pdf({}, wi, wo));
    const glm::vec2 r(u(rng), u(rng));
    const float lobe = u(rng);
    CHECK(plain.sample({}, wo, r, lobe).wi == explicit_z.sample({}, wo, r, lobe).wi);
  }
}

TEST_CASE("a tilted Lambert base reflects albedo / pi times min(1, cos_n / cos_z) for each direction") {
  // n = (0.6, 0, 0.8), tilted 36.9 degrees towards +x. The weight of each side: its cosine about n
  // over its cosine about +z, at most 1; nothing where either direction is behind n's horizon.
  const glm::dvec3 n(0.6, 0.0, 0.8);
  const cpu::Evaluator e = tilted(false, "[0.6, 0, 0.8]");
  std::mt19937 rng(7);
  int behind = 0;
  for (int i = 0; i < 2000; ++i) {
    const vec3 wi = random_upper(rng), wo = random_upper(rng);
    const double ci = glm::dot(glm::dvec3(wi), n), co = glm::dot(glm::dvec3(wo), n);
    double want = 0.0;
    if (ci > 0.0 && co > 0.0) want = 0.6 / test::kPi * std::min(1.0, ci / wi.z) * std::min(1.0, co / wo.z);
    behind += want == 0.0;
    CHECK(double(e.eval({}, wi, wo).x) == doctest::Approx(want).epsilon(2e-6).scale(1.0));
  }
  CHECK(behind > 0);  // some pairs lie behind the tilted horizon
}

TEST_CASE("tilted stacks keep energy and reciprocity where the tilt raises the cosines most") {
  // A tilted base under a coat and a tilted coat over it, seen from grazing angles on the side the
  // tilt faces: there the entry's cosine exceeds the surface's by the most.
  struct Case {
    std::string base, coat;
  };
  for (const Case& c :
       {Case{"[0.5, 0, 0.866]", ""}, Case{"", "[0.5, 0, 0.866]"}, Case{"[0.7, 0.2, 0.686]", "[-0.3, 0, 0.954]"}}) {
    CAPTURE(c.base);
    CAPTURE(c.coat);
    const cpu::Evaluator e = tilted(true, c.base, c.coat);
    for (double theta : {0.0, 40.0, 70.0, 85.0})
      for (double phi : {0.0, 180.0}) {
        const double a = theta * test::kPi / 180.0, b = phi * test::kPi / 180.0;
        const vec3 wo(float(std::sin(a) * std::cos(b)), float(std::sin(a) * std::sin(b)), float(std::cos(a)));
        CHECK(e.albedo({}, wo, 4096).x <= 1.0f + 0.005f);
      }
    std::mt19937 rng(11);
    for (int i = 0; i < 500; ++i) {
      const vec3 wi = random_upper(rng), wo = random_upper(rng);
      const vec3 f = e.eval({}, wi, wo), g = e.eval({}, wo, wi);
      CHECK(std::abs(double(f.x - g.x)) <= 1e-5 * std::max(1.0, double(f.x)));
    }
  }
}
