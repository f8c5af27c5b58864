// The energy-conserving composition (nodes/kernels/stack.glsl, lamina_stack_eval_conserving)
// against closed forms it must reproduce. The physics suite (cpu_physics_test.cpp) holds its test
// materials and random stacks to the furnace, reciprocity and sampling checks with the others.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "graph/cpu_test_support.h"
#include "test_support.h"

using namespace lamina;
using glm::vec3;

namespace {

std::string coat_over_lambert(double ior, double albedo, const std::string& model) {
  return R"({"format": 1, "materials": [{"name": "coat", "model": ")" + model +
         R"(", "surface": "@coat", "nodes": [
    {"id": "coat", "type": "layer", "interface": "@glass", "base": "@paper"},
    {"id": "glass", "type": "interface/dielectric", "ior": )" +
         std::to_string(ior) + R"(, "roughness_deg": 0.0},
    {"id": "paper", "type": "substrate/lambert", "albedo": [)" +
         std::to_string(albedo) + ", " + std::to_string(albedo) + ", " + std::to_string(albedo) + "]}]}]}";
}

}  // namespace

TEST_CASE("a smooth clear coat over a Lambert base reflects what the closed form of its interreflections says") {
  // Light enters with 1 - F(mu), the base reflects albedo a diffusely, the coat sends back the
  // internal hemispherical reflectance R = 1 - (1 - F_avg) / eta^2 (F_avg = 2 int F mu dmu), so the
  // base's light leaves with a (1 - R) / (1 - a R): directional albedo F + (1 - F) a (1 - R) / (1 - a R).
  const double eta = 1.5;
  double f_avg = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    double mu = (i + 0.5) / n;
    f_avg += 2.0 * test::fresnel_reference(mu, eta) * mu / n;
  }
  const double r_internal = 1.0 - (1.0 - f_avg) / (eta * eta);
  for (double a : {0.2, 0.8, 1.0}) {
    cpu::Evaluator e = test::evaluator_from_text(coat_over_lambert(eta, a, "energy_conserving"));
    for (double theta : {0.0, 30.0, 50.0, 70.0}) {
      double mu = std::cos(test::radians(theta));
      double expected = test::fresnel_reference(mu, eta) +
                        (1.0 - test::fresnel_reference(mu, eta)) * a * (1.0 - r_internal) / (1.0 - a * r_internal);
      vec3 albedo = e.albedo(ShadingContext{}, test::to_float(test::spherical(test::radians(theta), 0.0)), 16384);
      CAPTURE(a);
      CAPTURE(theta);
      // The table's interpolation (within 0.011 of F for a smooth boundary, less at these angles)
      // and the five-point quadrature of the interreflection.
      CHECK(double(albedo.x) == doctest::Approx(expected).epsilon(0.01));
    }
  }
}

TEST_CASE(
    "lamina glsl refuses an energy-conserving material with exit 2, its file and the reason, and writes nothing") {
  test::TempDir dir;
  std::ofstream(dir.path() / "coat.json") << coat_over_lambert(1.5, 0.8, "energy_conserving");
  test::RunResult r = test::run_cli("glsl coat.json -o coat.glsl", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("coat.json") != std::string::npos);
  CHECK(r.err.find("energy_conserving") != std::string::npos);
  CHECK(test::listing(dir.path()) == std::vector<std::string>{"coat.json"});
  // The same stack under the default model compiles.
  std::ofstream(dir.path() / "coat.json") << coat_over_lambert(1.5, 0.8, "weidlich_wilkie");
  CHECK(test::run_cli("glsl coat.json -o coat.glsl", dir.path()).exit_code == 0);
}
