// math/smoothstep: the kernel against values worked by hand, and the node driving a mix weight
// through the whole pipeline (checker, lowering, CPU run, stack).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/load.h"
#include "nodes/kernels/kernels.h"

using namespace lamina;
namespace k = lamina::kernels;

TEST_CASE("math/smoothstep's kernel is t^2 (3 - 2t) of the clamped position between its edges") {
  // t = 0.25: 0.0625 (3 - 0.5) = 0.15625; t = 0.5 gives 0.5 whatever the edges.
  CHECK(k::smoothstep_value(0.25f, 0.0f, 1.0f) == doctest::Approx(0.15625).epsilon(1e-7).scale(0.0));
  CHECK(k::smoothstep_value(2.0f, 1.0f, 3.0f) == doctest::Approx(0.5).epsilon(1e-7).scale(0.0));
  // Outside the edges it holds 0 and 1.
  CHECK(k::smoothstep_value(-1.0f, 0.0f, 1.0f) == 0.0f);
  CHECK(k::smoothstep_value(5.0f, 0.0f, 1.0f) == 1.0f);
  // Reversed edges fall: t = (0.25 - 1) / (0 - 1) = 0.75, 0.5625 (3 - 1.5) = 0.84375.
  CHECK(k::smoothstep_value(0.25f, 1.0f, 0.0f) == doctest::Approx(0.84375).epsilon(1e-7).scale(0.0));
  // Equal edges are a step at the edge, not a division by zero.
  CHECK(k::smoothstep_value(0.5f, 0.5f, 0.5f) == 1.0f);
  CHECK(k::smoothstep_value(0.4f, 0.5f, 0.5f) == 0.0f);
  // The largest numbers a file may hold, and edges so close that the quotient overflows, stay finite.
  const float big = k::LAMINA_MAX_VALUE;
  CHECK(k::smoothstep_value(big, 0.0f, 1.0e-30f) == 1.0f);
  CHECK(k::smoothstep_value(-big, big, -big) == 1.0f);
  CHECK(std::isfinite(k::smoothstep_value(0.0f, -big, big)));
}

TEST_CASE("a math/smoothstep of a checker's value weighs a mix on the CPU") {
  // Weight w = smoothstep(checker value, -1, 3) mixes a white Lambert base (a) with a black one (b),
  // so f pi = 1 - w at normal incidence: 1 - 0.15625 on the checker's even squares (value 0,
  // t = 0.25) and 1 - 0.5 on its odd ones (value 1, t = 0.5).
  const char* text = R"({"format": 1, "materials": [{"name": "smooth_mix", "surface": "@top", "nodes": [
      {"id": "tiles", "type": "texture/checker"},
      {"id": "smooth", "type": "math/smoothstep", "value": "@tiles.value", "edge0": -1.0, "edge1": 3.0},
      {"id": "top", "type": "mix", "weight": "@smooth.value", "a": "@white", "b": "@black"},
      {"id": "white", "type": "substrate/lambert", "albedo": [1, 1, 1]},
      {"id": "black", "type": "substrate/lambert", "albedo": [0, 0, 0]}]}]})";
  CheckedFile checked = check_text(text, "smooth_mix.json");
  REQUIRE(checked.ok());
  cpu::Evaluator e(compile(*checked.graphs[0], "smooth_mix.json"));
  const glm::vec3 up(0.0f, 0.0f, 1.0f);
  ShadingContext even, odd;
  even.uv = glm::vec2(0.1f, 0.1f);  // default scale 8: floor(0.8) + floor(0.8) = 0
  odd.uv = glm::vec2(0.2f, 0.1f);   // floor(1.6) + floor(0.8) = 1
  CHECK(double(e.eval(even, up, up).x) * std::numbers::pi == doctest::Approx(0.84375).epsilon(1e-6).scale(0.0));
  CHECK(double(e.eval(odd, up, up).x) * std::numbers::pi == doctest::Approx(0.5).epsilon(1e-6).scale(0.0));
}

TEST_CASE("math/smoothstep refuses a value that is not a float") {
  const char* text = R"({"format": 1, "materials": [{"name": "bad", "surface": "@base", "nodes": [
      {"id": "tiles", "type": "texture/checker"},
      {"id": "smooth", "type": "math/smoothstep", "value": "@tiles.color"},
      {"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
      {"id": "top", "type": "mix", "weight": "@smooth.value", "a": "@base", "b": "@base"}]}]})";
  CheckedFile checked = check_text(text, "bad.json");
  REQUIRE_FALSE(checked.ok());
  CHECK(checked.diagnostics.errors().front().pointer.find("/nodes/1/value") != std::string::npos);
}
