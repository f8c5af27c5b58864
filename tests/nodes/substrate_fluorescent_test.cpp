// substrate/fluorescent: a Lambertian base whose albedo is a matrix (nodes/kernels/diffuse.glsl),
// carried through both compositions by light of a colour (nodes/kernels/stack.glsl). Checked
// against the matrix written out here, against the light's attenuation on its way down and up
// computed from Beer-Lambert's law, against a white Lambert base where the two must agree, and
// against the reference solver's random walks, which carry the matrix as their throughput.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "graph/cpu/reference.h"
#include "nodes/kernels/kernels.h"
#include "tests/graph/cpu_test_support.h"
#include "tests/test_support.h"

namespace k = lamina::kernels;
using glm::vec3;
using lamina::cpu::Evaluator;

namespace {

const vec3 kRed(1.0f, 0.0f, 0.0f), kGreen(0.0f, 1.0f, 0.0f), kBlue(0.0f, 0.0f, 1.0f);

// A material of one stack: `surface` its surface's node id, `nodes` the nodes' JSON.
std::string material(const std::string& model, const std::string& surface, const std::string& nodes) {
  return R"({"format": 1, "materials": [{"name": "m", "model": ")" + model + R"(", "surface": "@)" + surface +
         R"(", "nodes": [)" + nodes + "]}]}";
}

std::string fluorescent(const std::string& albedo, float green_to_red, float blue_to_red, float blue_to_green) {
  return R"({"id": "base", "type": "substrate/fluorescent", "albedo": )" + albedo + R"(, "green_to_red": )" +
         std::to_string(green_to_red) + R"(, "blue_to_red": )" + std::to_string(blue_to_red) +
         R"(, "blue_to_green": )" + std::to_string(blue_to_green) + "}";
}

std::string coat(float ior, float roughness_deg, const std::string& absorption, float thickness) {
  std::string medium = absorption.empty() ? "" : R"(, "medium": "@tint")";
  std::string nodes = R"({"id": "coat", "type": "layer", "interface": "@skin", "base": "@base")" + medium +
                      R"(}, {"id": "skin", "type": "interface/dielectric", "ior": )" + std::to_string(ior) +
                      R"(, "roughness_deg": )" + std::to_string(roughness_deg) + "}";
  if (!absorption.empty())
    nodes += R"(, {"id": "tint", "type": "medium/absorbing", "absorption": )" + absorption + R"(, "thickness": )" +
             std::to_string(thickness) + "}";
  return nodes;
}

vec3 direction(double theta_deg, double phi_deg) {
  return lamina::test::to_float(
      lamina::test::spherical(lamina::test::radians(theta_deg), lamina::test::radians(phi_deg)));
}

double relative(vec3 a, vec3 b) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(double(a[c]) - double(b[c])) / std::max(double(std::abs(b[c])), 1e-6));
  return worst;
}

}  // namespace

TEST_CASE("fluorescent: a bare base reflects its albedo matrix times the light over pi") {
  // Column j: what light of channel j leaves as. The albedo on the diagonal, the shifts toward the
  // longer wavelengths above it (red is channel 0).
  const float a[3] = {0.5f, 0.3f, 0.1f};
  const float g2r = 0.35f, b2r = 0.25f, b2g = 0.2f;
  const vec3 by_light[3] = {vec3(a[0], 0.0f, 0.0f), vec3(g2r, a[1], 0.0f), vec3(b2r, b2g, a[2])};
  for (const char* model : {"energy_conserving", "weidlich_wilkie"}) {
    CAPTURE(model);
    const Evaluator e =
        lamina::test::evaluator_from_text(material(model, "base", fluorescent("[0.5, 0.3, 0.1]", g2r, b2r, b2g)));
    const lamina::ShadingContext ctx;
    const vec3 wi = direction(35.0, 10.0), wo = direction(60.0, 200.0);
    const vec3 lights[3] = {kRed, kGreen, kBlue};
    vec3 white(0.0f);
    for (int j = 0; j < 3; ++j) {
      const vec3 f = e.eval(ctx, wi, wo, lights[j]);
      CHECK(relative(f, by_light[j] / float(lamina::test::kPi)) < 1e-6);
      white += by_light[j];
    }
    // White light sees the row sums: a fluorescent red may reflect more red than a white card.
    CHECK(relative(e.eval(ctx, wi, wo), white / float(lamina::test::kPi)) < 1e-6);
    // Below the horizon nothing is reflected, of any colour.
    CHECK(e.eval(ctx, direction(95.0, 0.0), wo, kBlue) == vec3(0.0f));
  }
}

TEST_CASE("fluorescent: where a texture gives more than the energy bound, the shifts of that column are scaled back") {
  const glm::mat3 m = k::lamina_fluorescent_albedo(vec3(0.5f, 0.9f, 0.7f), vec3(0.5f, 0.4f, 0.2f));
  // Green returns 0.9 + 0.5 and blue 0.7 + 0.6: their shifts shrink until each column sums to 1, in
  // proportion; the albedo keeps its value, and red, which nothing leaves, is untouched.
  CHECK(m[1][1] == doctest::Approx(0.9f));
  CHECK(m[1][0] == doctest::Approx(0.1f));
  CHECK(m[2][0] == doctest::Approx(0.2f));
  CHECK(m[2][1] == doctest::Approx(0.1f));
  CHECK(m[2][2] == doctest::Approx(0.7f));
  CHECK(m[0][0] == doctest::Approx(0.5f));
  CHECK(m[0][1] == 0.0f);
  CHECK(m[0][2] == 0.0f);
  CHECK(m[1][2] == 0.0f);
  for (int j = 0; j < 3; ++j) CHECK(m[j][0] + m[j][1] + m[j][2] <= 1.0f + 1e-6f);
}

TEST_CASE("fluorescent: without shifts it is a Lambert base of the same albedo, under any light and layer") {
  const std::string lambert = R"({"id": "base", "type": "substrate/lambert", "albedo": [0.6, 0.4, 0.2]})";
  const std::string glowless = fluorescent("[0.6, 0.4, 0.2]", 0.0f, 0.0f, 0.0f);
  const std::string coated = coat(1.5f, 12.0f, "[0.3, 0.6, 1.2]", 0.8f);
  for (const char* model : {"energy_conserving", "weidlich_wilkie"})
    for (bool layered : {false, true}) {
      CAPTURE(model);
      CAPTURE(layered);
      const std::string surface = layered ? "coat" : "base";
      const Evaluator a =
          lamina::test::evaluator_from_text(material(model, surface, (layered ? coated + ", " : "") + lambert));
      const Evaluator b =
          lamina::test::evaluator_from_text(material(model, surface, (layered ? coated + ", " : "") + glowless));
      const lamina::ShadingContext ctx;
      for (double theta_i : {0.0, 40.0, 75.0})
        for (double theta_o : {10.0, 55.0, 85.0}) {
          const vec3 wi = direction(theta_i, 0.0), wo = direction(theta_o, 150.0);
          const vec3 light(0.3f, 1.0f, 0.6f);
          CHECK(relative(b.eval(ctx, wi, wo, light), a.eval(ctx, wi, wo) * light) < 1e-5);
        }
    }
}

TEST_CASE("fluorescent: Weidlich-Wilkie absorbs the light's colour on the way down and the new colour on the way up") {
  // Blue light leaving as red has no gloss of its own, so it is the base's term alone:
  // T t a_blue(l') G_rb / pi a_red(v'), a(w) = exp(-sigma d / cos w) along the refracted direction.
  // Raising the coat's blue absorption by delta scales it by exp(-delta d / cos l'); raising its red
  // absorption, by exp(-delta d / cos v').
  const float d = 0.7f, delta = 0.9f;
  const std::string base = fluorescent("[0.4, 0.3, 0.1]", 0.3f, 0.4f, 0.2f);
  auto red_from_blue = [&](const std::string& absorption, vec3 wi, vec3 wo) {
    const Evaluator e = lamina::test::evaluator_from_text(
        material("weidlich_wilkie", "coat", coat(1.5f, 8.0f, absorption, d) + ", " + base));
    return double(e.eval(lamina::ShadingContext{}, wi, wo, kBlue).x);
  };
  const vec3 wi = direction(20.0, 0.0), wo = direction(65.0, 180.0);
  auto refracted_cos = [](vec3 w) { return std::sqrt(1.0 - (1.0 - double(w.z) * double(w.z)) / (1.5 * 1.5)); };
  const double plain = red_from_blue("[0.2, 0.2, 0.2]", wi, wo);
  REQUIRE(plain > 0.0);
  const double bluer = red_from_blue("[0.2, 0.2, " + std::to_string(0.2f + delta) + "]", wi, wo);
  const double redder = red_from_blue("[" + std::to_string(0.2f + delta) + ", 0.2, 0.2]", wi, wo);
  CHECK(bluer / plain == doctest::Approx(std::exp(-double(delta * d) / refracted_cos(wi))).epsilon(1e-4));
  CHECK(redder / plain == doctest::Approx(std::exp(-double(delta * d) / refracted_cos(wo))).epsilon(1e-4));
}

TEST_CASE("fluorescent: a base returning every channel whole gives back under a clear coat what a white one does") {
  // Each column sums to 1, so no light is lost at the base, only moved to other channels; the
  // energy-conserving model then returns per channel the energy a white Lambert base returns under
  // the same coat (its series of round trips, (I - C W)^-1 C, keeps column sums as 1 / (1 - w)).
  const std::string white = R"({"id": "base", "type": "substrate/lambert", "albedo": [1.0, 1.0, 1.0]})";
  const std::string whole = fluorescent("[1.0, 0.6, 0.3]", 0.4f, 0.5f, 0.2f);
  const std::string clear = coat(1.5f, 17.0f, "", 0.0f);
  const Evaluator a = lamina::test::evaluator_from_text(material("energy_conserving", "coat", clear + ", " + white));
  const Evaluator b = lamina::test::evaluator_from_text(material("energy_conserving", "coat", clear + ", " + whole));
  for (double theta : {0.0, 45.0, 80.0}) {
    const vec3 wi = direction(theta, 0.0);
    const vec3 expected = a.energy(lamina::ShadingContext{}, wi);
    const vec3 energy = b.energy(lamina::ShadingContext{}, wi);
    CAPTURE(theta);
    CHECK(relative(energy, expected) < 2e-3);
    // And its white-light albedo shows the shift: more red than the white base, less blue.
    const vec3 albedo = b.albedo(lamina::ShadingContext{}, wi);
    CHECK(albedo.x > expected.x);
    CHECK(albedo.z < expected.z);
  }
}

TEST_CASE("fluorescent: the model agrees with the reference solver's walks under coloured light") {
  // The walks carry a matrix throughput through the base (graph/cpu/reference.cpp); the model its
  // series of round trips. Green light on the fluorescent card: the gloss stays green, the body red.
  const Evaluator e =
      lamina::test::load_evaluator(lamina::test::source_dir() / "examples/materials/fluorescent_card.json");
  const lamina::cpu::ShadingPoint point = e.bind(lamina::ShadingContext{});
  lamina::cpu::ReferenceOptions options;
  options.walks = int64_t(1) << (lamina::test::kSanitized ? 12 : 15);
  for (vec3 light : {kGreen, kBlue}) {
    options.light = light;
    for (const std::pair<double, double>& angles :
         {std::pair{0.0, 30.0}, std::pair{40.0, 40.0}, std::pair{70.0, 20.0}}) {
      const double theta_i = angles.first, theta_o = angles.second;  // clang 14 cannot capture a binding
      const vec3 wi = direction(theta_i, 0.0), wo = direction(theta_o, 180.0);
      const vec3 model = point.eval(wi, wo, light);
      const lamina::cpu::ReferenceEstimate ref = lamina::cpu::reference_eval(point, wi, wo, options);
      for (int c = 0; c < 3; ++c) {
        CAPTURE(theta_i);
        CAPTURE(theta_o);
        CAPTURE(c);
        CHECK(std::abs(double(model[c]) - ref.value[c]) <= 5.0 * ref.std_error[c] + 0.03 * ref.value[c] + 1e-4);
      }
    }
  }
  // The card's body glows red under green light: more red than green leaves at normal view.
  const vec3 glow = point.eval(direction(30.0, 0.0), direction(0.0, 0.0), kGreen);
  CHECK(glow.x > glow.y);
}
