// substrate/flake_paint: mirror flakes in a binder over a diffuse base (nodes/kernels/flakes.glsl,
// Ershov, Kolchin and Myszkowski 2001, sec. 6). Checked against eqs. 29, 32 and 36 written out here
// in double precision, and, as a material under a coat, against the full model of the same paint
// (graph/cpu/flake_slab.h, doubling and adding).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "graph/cpu/flake_slab.h"
#include "nodes/kernels/kernels.h"
#include "tests/graph/cpu_test_support.h"
#include "tests/test_support.h"

namespace lamina::flake_paint_test {
namespace {

using glm::vec3;

struct Paint {
  double coverage = 1.2, slope = 0.15, transmittance = 0.68;
  glm::dvec3 flake{0.3, 0.28, 0.24}, base{0.8, 0.8, 0.78};
};

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", x);
  return text;
}

std::string colour(const glm::dvec3& c) { return "[" + number(c.x) + ", " + number(c.y) + ", " + number(c.z) + "]"; }

// The paint as a node, and a material of it alone or under a smooth-ish coat of index 1.5.
std::string paint_node(const Paint& p) {
  return R"({"id": "paint", "type": "substrate/flake_paint", "base_color": )" + colour(p.base) +
         R"(, "flake_color": )" + colour(p.flake) + R"(, "flake_transmittance": )" + number(p.transmittance) +
         R"(, "coverage": )" + number(p.coverage) + R"(, "alpha": )" + number(p.slope) + "}";
}

std::string material(const Paint& p, double coat_roughness_deg) {
  std::string nodes = paint_node(p);
  std::string surface = "paint";
  if (coat_roughness_deg >= 0.0) {
    surface = "coat";
    nodes += R"(, {"id": "coat", "type": "layer", "interface": "@skin", "base": "@paint"})"
             R"(, {"id": "skin", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": )" +
             number(coat_roughness_deg) + "}";
  }
  return R"({"format": 1, "materials": [{"name": "m", "surface": "@)" + surface + R"(", "nodes": [)" + nodes + "]}]}";
}

vec3 direction(double theta_deg, double phi_deg) {
  return test::to_float(test::spherical(test::radians(theta_deg), test::radians(phi_deg)));
}

}  // namespace

// Smith's Lambda of Beckmann's distribution (Walter et al. 2007, eq. 27's G1 = 1 / (1 + Lambda)):
// (erf(a) - 1) / 2 + e^-a^2 / (2 a sqrt(pi)), a = 1 / (m tan theta).
double beckmann_lambda(double cos_theta, double m) {
  if (cos_theta >= 1.0) return 0.0;
  const double a = cos_theta / (m * std::sqrt(1.0 - cos_theta * cos_theta));
  return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(test::kPi));
}

TEST_CASE("flake paint: glitter and shade are eqs. 36, 21 and 28 of the fast model, written out here") {
  const Paint p;
  const cpu::Evaluator bare = test::evaluator_from_text(material(p, -1.0));
  // Eq. 21's depth without binder absorption, the flakes' projected area from Smith's identity.
  auto depth = [&](double cos_theta) {
    return p.coverage * (1.0 - p.transmittance) * (1.0 + 2.0 * beckmann_lambda(cos_theta, p.slope));
  };
  const std::pair<vec3, vec3> pairs[] = {{direction(20, 0), direction(20, 180)},
                                         {direction(40, 10), direction(15, 200)},
                                         {direction(70, 0), direction(60, 90)},
                                         {direction(85, 0), direction(85, 180)}};
  for (const auto& pair : pairs) {
    const vec3 l = pair.first, v = pair.second;
    const glm::dvec3 h = glm::normalize(test::to_double(l) + test::to_double(v));
    const double tan2 = (1.0 - h.z * h.z) / (h.z * h.z), m2 = p.slope * p.slope;
    // P(beta): Beckmann's D times cos beta (Walter et al. 2007, eq. 25).
    const double orientation = std::exp(-tan2 / m2) / (test::kPi * m2 * std::pow(h.z, 4)) * h.z;
    const double x = depth(double(l.z)) + depth(double(v.z));
    const vec3 f = bare.eval(ShadingContext{}, l, v);
    for (int c = 0; c < 3; ++c) {
      CAPTURE(c);
      CAPTURE(l.z);
      const double glitter = p.coverage * p.flake[c] * (1.0 - std::exp(-x)) / x * orientation / (4.0 * l.z * v.z);
      // Q of eq. 26, the flakes' part only (the boundary is a layer's), by a fine midpoint sum over
      // cos^2 theta.
      double two_q = 0.0;
      const int n = 4000;
      for (int k = 0; k < n; ++k) {
        const double d = 2.0 * depth(std::sqrt((k + 0.5) / n));
        two_q += p.coverage * p.flake[c] * (1.0 - std::exp(-d)) / d / n;
      }
      const double shade = p.base[c] * std::exp(-x) / (test::kPi * (1.0 - p.base[c] * two_q));
      CHECK(double(f[c]) == doctest::Approx(glitter + shade).epsilon(1e-4));
    }
  }
}

TEST_CASE("flake paint: a flake asked to reflect more than it does not pass reflects 1 - t_p") {
  // The checker refuses constant flake_color + flake_transmittance > 1; a texture's values are
  // taken so by the kernels.
  const vec3 asked(0.9f, 0.4f, 0.9f), kept(0.5f, 0.4f, 0.5f), l = direction(30, 0), v = direction(35, 170);
  const vec3 diffuse_asked = kernels::lamina_flake_paint_diffuse(1.0f, asked, 0.5f, vec3(0.7f), 0, 0.2f);
  const vec3 diffuse_kept = kernels::lamina_flake_paint_diffuse(1.0f, kept, 0.5f, vec3(0.7f), 0, 0.2f);
  CHECK(diffuse_asked == diffuse_kept);
  CHECK(kernels::lamina_flake_paint_eval(l, v, 1.0f, asked, 0.5f, diffuse_asked, 0, 0.2f) ==
        kernels::lamina_flake_paint_eval(l, v, 1.0f, kept, 0.5f, diffuse_kept, 0, 0.2f));
}

TEST_CASE("flake paint: under a smooth coat its albedo is the full model's within the fast model's error") {
  // The full model solves the same paint (its boundary the coat's) by doubling and adding, with
  // every order of scattering; the fast model keeps single scattering by the flakes, and the layer
  // sums the shade's bounces under the coat. Dense translucent flakes lose what light scattered
  // more than once adds (README, "Flake paint").
  const Paint p;
  const cpu::Evaluator coated = test::evaluator_from_text(material(p, 0.0));
  const std::vector<double> views{1.0, std::cos(test::radians(30.0)), std::cos(test::radians(60.0))};
  cpu::FlakeSlabOptions options;
  if (test::kSanitized) options = cpu::FlakeSlabOptions::coarse();
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    cpu::FlakeSlab slab;
    slab.eta = 1.5;
    slab.coverage = p.coverage;
    slab.flake_slope = p.slope;
    slab.flake_reflectance = p.flake[c];
    slab.flake_transmittance = p.transmittance;
    slab.substrate_albedo = p.base[c];
    const cpu::FlakeSlabSolution full(slab, views, options);
    for (size_t i = 0; i < views.size(); ++i) {
      const vec3 wo(float(std::sqrt(1.0 - views[i] * views[i])), 0.0f, float(views[i]));
      const double model = double(coated.albedo(ShadingContext{}, wo)[c]);
      const double reference = full.albedo(i) + full.mirror(i);
      std::printf("flake paint under a smooth coat, channel %d, view %.0f deg: albedo %.4f, full model %.4f\n", c,
                  test::degrees(std::acos(views[i])), model, reference);
      worst = std::max(worst, std::abs(model - reference) / reference);
      CHECK(model <= reference);  // only what multiple scattering adds is missing
    }
  }
  MESSAGE("the pearlescent paint's albedo under a smooth coat within " << 100.0 * worst << "% of the full model's");
  CHECK(worst <= 0.3);  // measured: 25.7%, in red at 60 degrees
}

}  // namespace lamina::flake_paint_test
