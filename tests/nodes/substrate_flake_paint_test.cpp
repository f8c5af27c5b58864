// substrate/flake_paint: mirror flakes in a binder over a diffuse base (nodes/kernels/flakes.glsl,
// Ershov, Kolchin and Myszkowski 2001, sec. 6). Checked against eqs. 29, 32 and 36 written out here
// in double precision, and, as a material under a coat, against the full model of the same paint
// (graph/cpu/flake_slab.h, doubling and adding).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
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
  // Coated flakes (film_nm > 0): a film of index film_ior (absolute) in the medium above the
  // paint, of index `binder` (1 bare, the coat's under one), folded into RGB at 645, 525 and 445 nm.
  double film_nm = 0.0, binder = 1.0;
  glm::dvec3 film_ior{2.55, 2.65, 2.78};
};

// A coated flake's reflectance written out here: Airy's sum for a film of index n_f between two
// half-spaces of the binder's index n_b, per polarisation, with the Fresnel amplitude coefficients
// of Born and Wolf sec. 1.5.2 (r23 = -r12 for the film's lower face) and the phase
// 4 pi n_f d cos_f / lambda (sec. 7.6.1), s and p averaged.
double airy_flake(double cos_b, double n_b, double n_f, double d_nm, double lambda_nm) {
  const double sin2_f = (1.0 - cos_b * cos_b) * (n_b * n_b) / (n_f * n_f);
  if (sin2_f >= 1.0) return 1.0;
  const double cos_f = std::sqrt(1.0 - sin2_f);
  const double rs = (n_b * cos_b - n_f * cos_f) / (n_b * cos_b + n_f * cos_f);
  const double rp = (n_f * cos_b - n_b * cos_f) / (n_f * cos_b + n_b * cos_f);
  const std::complex<double> phase = std::polar(1.0, 4.0 * test::kPi * n_f * d_nm * cos_f / lambda_nm);
  auto reflectance = [&](double r) { return std::norm((r - r * phase) / (1.0 - r * r * phase)); };
  return 0.5 * (reflectance(rs) + reflectance(rp));
}

// A flake's reflectance and straight transmittance in channel c at cosine cos to its normal.
double flake_r(const Paint& p, int c, double cos) {
  const double lambda[3] = {645.0, 525.0, 445.0};
  return p.film_nm > 0.0 ? airy_flake(cos, p.binder, p.film_ior[c], p.film_nm, lambda[c]) : p.flake[c];
}
double flake_t(const Paint& p, int c, double cos) {
  return p.film_nm > 0.0 ? 1.0 - flake_r(p, c, cos) : p.transmittance;
}

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", x);
  return text;
}

std::string colour(const glm::dvec3& c) { return "[" + number(c.x) + ", " + number(c.y) + ", " + number(c.z) + "]"; }

// The paint as a node, and a material of it alone or under a smooth-ish coat of index 1.5.
std::string paint_node(const Paint& p) {
  const std::string flakes = p.film_nm > 0.0 ? R"(, "film_thickness_nm": )" + number(p.film_nm) + R"(, "film_ior": )" +
                                                   colour(p.film_ior) + R"(, "integration": "rgb")"
                                             : R"(, "flake_color": )" + colour(p.flake) +
                                                   R"(, "flake_transmittance": )" + number(p.transmittance);
  return R"({"id": "paint", "type": "substrate/flake_paint", "base_color": )" + colour(p.base) + flakes +
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

// Eqs. 36 (glitter), 21 (depth) and 28 (shade) for light l and view v inside the binder, in
// channel c: the flakes' reflectance at the angle between l and the flake that mirrors it into v,
// their transmittance at each direction's angle, Q of eq. 26 (the flakes' part only: the boundary
// is a layer's) by a fine midpoint sum over cos^2 theta.
double written_out(const Paint& p, const glm::dvec3& l, const glm::dvec3& v, int c) {
  // Eq. 21's depth without binder absorption, the flakes' projected area from Smith's identity.
  auto depth = [&](double cos_theta) {
    return p.coverage * (1.0 - flake_t(p, c, cos_theta)) * (1.0 + 2.0 * beckmann_lambda(cos_theta, p.slope));
  };
  const glm::dvec3 h = glm::normalize(l + v);
  const double tan2 = (1.0 - h.z * h.z) / (h.z * h.z), m2 = p.slope * p.slope;
  // P(beta): Beckmann's D times cos beta (Walter et al. 2007, eq. 25).
  const double orientation = std::exp(-tan2 / m2) / (test::kPi * m2 * std::pow(h.z, 4)) * h.z;
  const double x = depth(l.z) + depth(v.z);
  const double glitter =
      p.coverage * flake_r(p, c, glm::dot(l, h)) * (1.0 - std::exp(-x)) / x * orientation / (4.0 * l.z * v.z);
  double two_q = 0.0;
  const int n = 4000;
  for (int k = 0; k < n; ++k) {
    const double cos_theta = std::sqrt((k + 0.5) / n), d = 2.0 * depth(cos_theta);
    two_q += p.coverage * flake_r(p, c, cos_theta) * (1.0 - std::exp(-d)) / d / n;
  }
  return glitter + p.base[c] * std::exp(-x) / (test::kPi * (1.0 - p.base[c] * two_q));
}

TEST_CASE("flake paint: glitter and shade are eqs. 36, 21 and 28 of the fast model, written out here") {
  Paint coated;
  coated.film_nm = 160.0;
  coated.coverage = 1.0;
  // The kernels sum Q over 32 midpoints in cos^2 theta: exact to 1e-4 for plain flakes, to 1e-3 for
  // a film's reflectance, which varies with the angle (measured: 9e-4, green, 70 and 60 degrees).
  struct Case {
    std::string name;
    Paint paint;
    double tolerance;
  };
  const Case paints[] = {{"plain flakes", Paint{}, 1e-4}, {"coated flakes", coated, 1.5e-3}};
  const std::pair<vec3, vec3> pairs[] = {{direction(20, 0), direction(20, 180)},
                                         {direction(40, 10), direction(15, 200)},
                                         {direction(70, 0), direction(60, 90)},
                                         {direction(85, 0), direction(85, 180)}};
  for (const Case& paint : paints) {
    // Named, not bound: clang's lambdas (CAPTURE) cannot capture structured bindings before C++20's P1091.
    const Paint& p = paint.paint;
    const double tolerance = paint.tolerance;
    CAPTURE(paint.name);
    const cpu::Evaluator bare = test::evaluator_from_text(material(p, -1.0));
    for (const auto& pair : pairs) {
      const vec3 l = pair.first, v = pair.second;
      const vec3 f = bare.eval(ShadingContext{}, l, v);
      for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CAPTURE(l.z);
        CHECK(double(f[c]) ==
              doctest::Approx(written_out(p, test::to_double(l), test::to_double(v), c)).epsilon(tolerance));
      }
    }
  }
}

TEST_CASE(
    "flake paint: a coated flake is its film: reflected and passed colours complementary, moving with the angle") {
  // The film of the two-tone example (160 nm of an index near 2.65 in a binder of 1.5): a lossless
  // flake reflects R and passes 1 - R, so what its reflection gains its transmission loses, and
  // the colour it reflects changes as light meets it more obliquely.
  Paint p;
  p.film_nm = 160.0;
  p.binder = 1.5;
  const glm::dvec3 normal{airy_flake(1.0, 1.5, p.film_ior[0], 160.0, 645.0),
                          airy_flake(1.0, 1.5, p.film_ior[1], 160.0, 525.0),
                          airy_flake(1.0, 1.5, p.film_ior[2], 160.0, 445.0)};
  const glm::dvec3 oblique{airy_flake(0.5, 1.5, p.film_ior[0], 160.0, 645.0),
                           airy_flake(0.5, 1.5, p.film_ior[1], 160.0, 525.0),
                           airy_flake(0.5, 1.5, p.film_ior[2], 160.0, 445.0)};
  kernels::LaminaFlakes flakes = kernels::lamina_flakes(1.0f, vec3(0.0f), 0.0f, 0, 0.15f);
  flakes.film = kernels::LAMINA_FRESNEL_FILM_RGB;
  flakes.film_eta = test::to_float(p.film_ior / 1.5);
  flakes.film_depth = float(160.0 * 1.5);
  for (const auto& [cos, expected] : {std::pair{1.0f, normal}, std::pair{0.5f, oblique}}) {
    vec3 r, t;
    kernels::lamina_flake_optics(flakes, cos, r, t);
    for (int c = 0; c < 3; ++c) {
      CHECK(double(r[c]) == doctest::Approx(expected[c]).epsilon(1e-4));
      CHECK(double(r[c] + t[c]) == doctest::Approx(1.0).epsilon(1e-6));
    }
  }
  // Green reflects most at normal incidence, red least; obliquely the peak moves towards blue.
  CHECK(normal.y > normal.x);
  CHECK(normal.y > normal.z);
  CHECK(oblique.z / oblique.y > normal.z / normal.y);
}

TEST_CASE("flake paint: a flake asked to reflect more than it does not pass reflects 1 - t_p") {
  // The checker refuses constant flake_color + flake_transmittance > 1; a texture's values are
  // taken so by the kernels.
  const vec3 asked(0.9f, 0.4f, 0.9f), kept(0.5f, 0.4f, 0.5f), l = direction(30, 0), v = direction(35, 170);
  const kernels::LaminaFlakes flakes_asked = kernels::lamina_flakes(1.0f, asked, 0.5f, 0, 0.2f);
  const kernels::LaminaFlakes flakes_kept = kernels::lamina_flakes(1.0f, kept, 0.5f, 0, 0.2f);
  vec3 x0_asked, x0_kept, diffuse_asked, diffuse_kept, albedo_asked, albedo_kept;
  kernels::lamina_flake_paint_resolve(flakes_asked, vec3(0.7f), x0_asked, diffuse_asked, albedo_asked);
  kernels::lamina_flake_paint_resolve(flakes_kept, vec3(0.7f), x0_kept, diffuse_kept, albedo_kept);
  CHECK(x0_asked == x0_kept);
  CHECK(diffuse_asked == diffuse_kept);
  CHECK(albedo_asked == albedo_kept);
  CHECK(kernels::lamina_flake_paint_eval(l, v, flakes_asked, diffuse_asked, x0_asked) ==
        kernels::lamina_flake_paint_eval(l, v, flakes_kept, diffuse_kept, x0_kept));
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
