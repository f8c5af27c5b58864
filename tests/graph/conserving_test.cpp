// The energy-conserving composition (nodes/kernels/stack.glsl, lamina_stack_eval_conserving)
// against closed forms it must reproduce. The physics suite (cpu_physics_test.cpp) holds its test
// materials and random stacks to the furnace, reciprocity and sampling checks with the others.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "graph/cpu/microsurface.h"
#include "graph/cpu/pcg32.h"
#include "graph/cpu/reference.h"
#include "graph/cpu_test_support.h"
#include "graph/glsl/glsl_text.h"
#include "nodes/kernels/kernels.h"
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

// Holds a point's albedo (Evaluator::albedo, 16384 points per lobe) at each angle to the reference
// solver's, within `relative` of it plus `std_errors` of its standard errors, every channel.
void check_albedo_against_reference(const cpu::ShadingPoint& point, std::initializer_list<double> angles,
                                    double relative, double std_errors, int walks) {
  cpu::ReferenceOptions options;
  options.walks = walks;
  for (double theta : angles) {
    const vec3 wo = test::to_float(test::spherical(test::radians(theta), 0.0));
    const vec3 model = point.albedo(wo, 16384);
    const cpu::ReferenceEstimate reference = cpu::reference_albedo(point, wo, options);
    for (int c = 0; c < 3; ++c) {
      CAPTURE(theta);
      CAPTURE(c);
      CAPTURE(model[c]);
      CAPTURE(reference.value[c]);
      CHECK(std::abs(double(model[c]) - double(reference.value[c])) <=
            relative * double(reference.value[c]) + std_errors * double(reference.std_error[c]));
    }
  }
}

// The directional albedo at cosine mu of a smooth clear coat of index eta over a Lambert base of
// albedo a: light enters with 1 - F(mu), the base reflects a diffusely, the coat sends back the
// internal hemispherical reflectance R = 1 - (1 - F_avg) / eta^2 (F_avg = 2 int F mu dmu), so the
// base's light leaves with a (1 - R) / (1 - a R): F + (1 - F) a (1 - R) / (1 - a R).
double coat_over_lambert_albedo(double mu, double eta, double a) {
  double f_avg = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n;
    f_avg += 2.0 * test::fresnel_reference(x, eta) * x / n;
  }
  const double r_internal = 1.0 - (1.0 - f_avg) / (eta * eta);
  const double f = test::fresnel_reference(mu, eta);
  return f + (1.0 - f) * a * (1.0 - r_internal) / (1.0 - a * r_internal);
}

// A smooth clear coat of index 1.5 over a checker of two Lambertian albedos a and b: the coat over
// a mix of the two bases, or (written out) a mix of the coat over each.
std::string coat_over_checker(double a, double b, bool coat_over_mix, const std::string& model) {
  const std::string paper = R"({"id": "paper_a", "type": "substrate/lambert", "albedo": [)" + std::to_string(a) +
                            ", 0.5, 0.5]}, " + R"({"id": "paper_b", "type": "substrate/lambert", "albedo": [)" +
                            std::to_string(b) + ", 0.5, 0.5]}, ";
  const std::string common =
      R"({"id": "tiles", "type": "texture/checker", "scale": [4.0, 4.0]},
    {"id": "glass", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 0.0}, )";
  const std::string stack =
      coat_over_mix ? R"({"id": "surface", "type": "layer", "interface": "@glass", "base": "@both"},
    {"id": "both", "type": "mix", "weight": "@tiles.value", "a": "@paper_a", "b": "@paper_b"})"
                    : R"({"id": "surface", "type": "mix", "weight": "@tiles.value", "a": "@coat_a", "b": "@coat_b"},
    {"id": "coat_a", "type": "layer", "interface": "@glass", "base": "@paper_a"},
    {"id": "coat_b", "type": "layer", "interface": "@glass", "base": "@paper_b"})";
  return R"({"format": 1, "materials": [{"name": "coat", "model": ")" + model +
         R"(", "surface": "@surface", "nodes": [)" + paper + common + stack + "]}]}";
}

}  // namespace

TEST_CASE("a smooth clear coat over a Lambert base reflects what the closed form of its interreflections says") {
  // coat_over_lambert_albedo's closed form.
  const double eta = 1.5;
  for (double a : {0.2, 0.8, 1.0}) {
    cpu::Evaluator e = test::evaluator_from_text(coat_over_lambert(eta, a, "energy_conserving"));
    for (double theta : {0.0, 30.0, 50.0, 70.0}) {
      double expected = coat_over_lambert_albedo(std::cos(test::radians(theta)), eta, a);
      vec3 albedo = e.albedo(ShadingContext{}, test::to_float(test::spherical(test::radians(theta), 0.0)), 16384);
      CAPTURE(a);
      CAPTURE(theta);
      // The table's interpolation (within 0.011 of F for a smooth boundary, less at these angles)
      // and the five-point quadrature of the interreflection.
      CHECK(double(albedo.x) == doctest::Approx(expected).epsilon(0.01).scale(0.0));
    }
  }
}

TEST_CASE("a coat over a mix of bases is the mix of the coat over each, so each keeps its interreflections") {
  for (const char* model : {"energy_conserving", "weidlich_wilkie"}) {
    CAPTURE(model);
    const cpu::Evaluator over_mix = test::evaluator_from_text(coat_over_checker(0.2, 0.8, true, model));
    const cpu::Evaluator written_out = test::evaluator_from_text(coat_over_checker(0.2, 0.8, false, model));
    // The same stack, entry for entry: the same numbers to the bit, in every tile and where a
    // pixel's footprint blends them.
    cpu::Pcg32 rng(17, 3);
    for (int k = 0; k < 200; ++k) {
      ShadingContext ctx;
      ctx.uv = glm::vec2(rng.uniform(), rng.uniform());
      ctx.footprint = k % 2 == 0 ? 0.0f : 0.5f * rng.uniform();
      const vec3 wi = test::to_float(test::spherical(test::radians(85.0 * rng.uniform()), 6.3 * rng.uniform()));
      const vec3 wo = test::to_float(test::spherical(test::radians(85.0 * rng.uniform()), 6.3 * rng.uniform()));
      CAPTURE(k);
      CHECK(over_mix.eval(ctx, wi, wo) == written_out.eval(ctx, wi, wo));
      CHECK(over_mix.pdf(ctx, wi, wo) == written_out.pdf(ctx, wi, wo));
    }
  }
  // In the energy-conserving model each tile is the closed form of a coat over its own base
  // (coat_over_lambert_albedo): a (1 - R) / (1 - a R) of the light that enters, not a (1 - R)
  // without the interreflections of a coat over something that is not one base.
  const cpu::Evaluator e = test::evaluator_from_text(coat_over_checker(0.2, 0.8, true, "energy_conserving"));
  for (const auto& tile : {std::pair{glm::vec2(0.1f, 0.1f), 0.2}, std::pair{glm::vec2(0.3f, 0.1f), 0.8}}) {
    const double a = tile.second;
    ShadingContext ctx;
    ctx.uv = tile.first;
    const double expected = coat_over_lambert_albedo(1.0, 1.5, a);
    CAPTURE(a);
    CHECK(double(e.albedo(ctx, vec3(0.0f, 0.0f, 1.0f), 16384).x) == doctest::Approx(expected).epsilon(0.01));
  }
}

TEST_CASE("a layer over a layer keeps its base's diffuse light by the round trip of the base's own profile") {
  // The base's diffuse light leaves it as c_B u_B(mu) and what the boundary sends back at mu enters
  // it with u_B(mu) again, after bouncing between the two boundaries (R the upper one's reflection
  // from below, 1 under total internal reflection, R_B the lower one's from above), so the share
  // kept per round trip is K = c_B 2 pi int u_B^2 t^2 R / (1 - R R_B t^2) mu dmu, R less what
  // ends in the upper medium's guide (lamina_guide_keep), and c_B less what the lower boundary lets
  // into the guide, where the tint keeps it (lamina_guide_entry_keep). Here by a fine
  // midpoint rule over the kernels' own profile and boundary energy, against the five-point
  // quadrature of lamina_stack_resolve. The middle layer (index 1.45 under 1.7, a rough boundary)
  // makes u_B far from uniform, where the product c_B (int u_B cos)(int u_B t^2 R cos) / pi that
  // the model used before is 12% off, and is 0 beyond its boundary's critical angle, where five
  // nodes over the whole range were 2.5% off.
  const std::string text = R"({"format": 1, "materials": [{"name": "stack", "model": "energy_conserving",
    "surface": "@top", "nodes": [
    {"id": "top", "type": "layer", "interface": "@glass", "medium": "@tint", "base": "@lower"},
    {"id": "glass", "type": "interface/dielectric", "ior": 1.7, "roughness_deg": 1.0, "distribution": "ggx"},
    {"id": "tint", "type": "medium/absorbing", "thickness": 0.5, "absorption": [0.0, 0.2, 0.6]},
    {"id": "lower", "type": "layer", "interface": "@film", "base": "@paper"},
    {"id": "film", "type": "interface/dielectric", "ior": 1.45, "roughness_deg": 14.0, "distribution": "ggx"},
    {"id": "paper", "type": "substrate/lambert", "albedo": [0.9, 0.9, 0.9]}]}]})";
  cpu::Evaluator e = test::evaluator_from_text(text);
  const cpu::ShadingPoint point = e.bind(ShadingContext{});
  const cpu::ShadingPoint::Stack stack = point.stack();
  REQUIRE(stack.count == 3);
  const kernels::LaminaEntry* entries = stack.entries;
  const kernels::LaminaParams* params = stack.params;
  REQUIRE(entries[0].kind == kernels::LAMINA_LAYER);
  REQUIRE(entries[1].kind == kernels::LAMINA_LAYER);
  const double eta = params[0].eta;
  const double mu_critical = std::sqrt(1.0 - 1.0 / (eta * eta));
  // What the upper boundary sends back down loses what ends in its guide (lamina_guide).
  const kernels::LaminaGuide guide = kernels::lamina_guide(entries, params, 0, 1.45f);
  const int n = 20000;
  glm::dvec3 kept(0.0);
  for (int q = 0; q < n; ++q) {
    const double mu = (q + 0.5) / n;
    double reflected = 1.0;
    if (mu > mu_critical) {
      const double mu_out = std::sqrt(1.0 - eta * eta * (1.0 - mu * mu));
      float multiple = 0.0f;
      reflected = kernels::lamina_boundary_energy(entries[0].distribution, entries[0].fresnel, params[0].grid,
                                                  float(mu_out), params[0].eta, multiple);
    }
    float multiple = 0.0f;
    const double reflected_base = kernels::lamina_boundary_energy(entries[1].distribution, entries[1].fresnel,
                                                                  params[1].grid, float(mu), params[1].eta, multiple);
    const glm::dvec3 u(kernels::lamina_diffuse_profile(entries, params, 1, float(mu)));
    const glm::dvec3 t(kernels::one_way_absorption(params[0].absorption, params[0].thickness, float(mu)));
    const glm::dvec3 back = reflected * glm::dvec3(kernels::lamina_guide_keep(entries, 0, guide, float(mu)));
    kept += u * u * t * t * back * (mu / n) / (1.0 - back * reflected_base * t * t);
  }
  // The base's light, less what its rough boundary lets up into the guide and the tint keeps there.
  const glm::dvec3 c_base =
      glm::dvec3(params[1].diffuse) * glm::dvec3(kernels::lamina_guide_entry_keep(entries, params, 0, 1, 1.45f));
  const glm::dvec3 k = c_base * (2.0 * test::kPi) * kept;
  for (int c = 0; c < 3; ++c) {
    const double expected = c_base[c] / (eta * eta * (1.0 - k[c]));
    CAPTURE(c);
    CAPTURE(k[c]);
    CHECK(std::abs(double(params[0].diffuse[c]) / expected - 1.0) < 0.005);
  }
}

TEST_CASE("a lossless stack with a boundary down to a lower index reflects nearly all the light it receives") {
  // A smooth 1.7 coat over a rough 1.45 layer over white: nothing absorbs, so the reference reflects
  // exactly 1. The white base's light outside the 1.45 layer's exit cone crosses up into the 1.7
  // medium, is totally reflected by the coat and must pass the lower boundary again, bouncing
  // between the two: without that series (lamina_gap_series) the model kept 0.84 to 0.86 of it.
  // What is still lost is light the specular parts send into the boundaries from below.
  const std::string text = R"({"format": 1, "materials": [{"name": "stack", "model": "energy_conserving",
    "surface": "@top", "nodes": [
    {"id": "top", "type": "layer", "interface": "@glass", "base": "@lower"},
    {"id": "glass", "type": "interface/dielectric", "ior": 1.7, "roughness_deg": 0.0, "distribution": "ggx"},
    {"id": "lower", "type": "layer", "interface": "@film", "base": "@paper"},
    {"id": "film", "type": "interface/dielectric", "ior": 1.45, "roughness_deg": 14.0, "distribution": "ggx"},
    {"id": "paper", "type": "substrate/lambert", "albedo": [1.0, 1.0, 1.0]}]}]})";
  cpu::Evaluator e = test::evaluator_from_text(text);
  for (double theta : {0.0, 30.0, 60.0, 70.0, 80.0, 85.0}) {
    const vec3 albedo = e.albedo(ShadingContext{}, test::to_float(test::spherical(test::radians(theta), 0.0)), 16384);
    CAPTURE(theta);
    CHECK(double(albedo.x) > 0.965);
    CHECK(double(albedo.x) <= 1.0);
  }
}

namespace {

// A rough 10-degree GGX coat of 1.7 over a boundary down to 1.45 (`film`: its roughness and
// distribution) over a Lambert base, the coat's medium absorbing `absorption` per unit (clear for
// ""): in the coat's medium, beyond 58.5 degrees (the 1.45 boundary's critical angle) light can
// reach no base and is totally reflected by both boundaries, a guide.
std::string guided_stack(const std::string& film, const std::string& absorption) {
  const std::string tint = absorption.empty() ? "" : R"("medium": "@tint",)";
  const std::string medium =
      absorption.empty()
          ? ""
          : R"({"id": "tint", "type": "medium/absorbing", "thickness": 0.5, "absorption": )" + absorption + "},";
  return R"({"format": 1, "materials": [{"name": "guided", "model": "energy_conserving",
    "surface": "@top", "nodes": [
    {"id": "top", "type": "layer", "interface": "@glass", )" +
         tint + R"( "base": "@lower"},
    {"id": "glass", "type": "interface/dielectric", "ior": 1.7, "roughness_deg": 10.0, "distribution": "ggx"},
    {"id": "lower", "type": "layer", "interface": "@film", "base": "@paper"},
    {"id": "film", "type": "interface/dielectric", "ior": 1.45, )" +
         film + "}," + medium + R"(
    {"id": "paper", "type": "substrate/lambert", "albedo": [0.9, 0.85, 0.7]}]}]})";
}

// The lower boundary of guided_stack: nearly smooth, or rough enough to refract the base's light
// beyond its critical angle.
const char* const kSmoothFilm = R"("roughness_deg": 0.5)";
const char* const kRoughFilm = R"("roughness_deg": 14.0, "distribution": "beckmann")";

}  // namespace

TEST_CASE("light a rough coat spreads into the guide under it is lost to the guide's tint, none in a clear one") {
  // What the coat reflects back down beyond the lower boundary's critical angle travels on between
  // the two boundaries until the coat's roughness turns it back (lamina_guide). In a clear medium
  // all of it comes back: the guide changes nothing.
  cpu::Evaluator clear = test::evaluator_from_text(guided_stack(kSmoothFilm, ""));
  const cpu::ShadingPoint::Stack stack = clear.bind(ShadingContext{}).stack();
  const kernels::LaminaGuide clear_guide = kernels::lamina_guide(stack.entries, stack.params, 0, 1.45f);
  REQUIRE(clear_guide.guided);
  for (int c = 0; c < 3; ++c) CHECK(clear_guide.gain[c] == doctest::Approx(1.0f).epsilon(1e-6));
  // The spread's share beyond the edge grows toward it: the keep of a tinted guide falls.
  cpu::Evaluator tinted = test::evaluator_from_text(guided_stack(kSmoothFilm, "[0.6, 0.2, 0.05]"));
  const cpu::ShadingPoint point = tinted.bind(ShadingContext{});
  const kernels::LaminaGuide guide = kernels::lamina_guide(point.stack().entries, point.stack().params, 0, 1.45f);
  CHECK(guide.gain.x < guide.gain.y);
  CHECK(guide.gain.y < guide.gain.z);
  float previous = 1.0f;
  for (float mu : {1.0f, 0.9f, 0.8f, 0.7f, 0.6f, 0.55f}) {
    const float keep = kernels::lamina_guide_keep(point.stack().entries, 0, guide, mu).x;
    CAPTURE(mu);
    CHECK(keep < previous);
    previous = keep;
  }
  // Against the reference: the model was 10% to 11% too bright in red at 0 and 40 degrees while
  // that light stayed as if the coat had sent it back at its own angle; with the guide's loss, about
  // 6%. (Part of the gap remains: light near the edge, which the lower boundary almost totally
  // reflects, also crosses the tint many times.)
  check_albedo_against_reference(point, {0.0, 40.0}, 0.075, 0.0, test::kSanitized ? 1 << 13 : 1 << 16);
}

TEST_CASE("diffuse light a rough boundary lets up into the guide is lost to its tint, as much as the walks put there") {
  // Clear: all of it comes back out, and the base's light is kept whole.
  cpu::Evaluator clear = test::evaluator_from_text(guided_stack(kRoughFilm, ""));
  const cpu::ShadingPoint::Stack open = clear.bind(ShadingContext{}).stack();
  REQUIRE(open.count == 3);
  const vec3 clear_keep = kernels::lamina_guide_entry_keep(open.entries, open.params, 0, 1, 1.45f);
  for (int c = 0; c < 3; ++c) CHECK(clear_keep[c] == doctest::Approx(1.0f).epsilon(1e-6));
  // Tinted: red (optical depth 30 across) keeps nothing of what enters, so its keep is 1 - g, g
  // the share of the base's light that the boundary lets up beyond its critical angle. The
  // boundary's own random walks (the reference's interfaces) measure g independently: Lambertian
  // light from below, the share of what crosses that leaves beyond the edge.
  cpu::Evaluator tinted = test::evaluator_from_text(guided_stack(kRoughFilm, "[60.0, 0.6, 0.05]"));
  const cpu::ShadingPoint point = tinted.bind(ShadingContext{});
  const cpu::ShadingPoint::Stack stack = point.stack();
  const vec3 keep = kernels::lamina_guide_entry_keep(stack.entries, stack.params, 0, 1, 1.45f);
  CHECK(keep.x < keep.y);
  CHECK(keep.y < keep.z);
  const cpu::MicrosurfaceBoundary b{stack.params[1].eta, stack.entries[1].distribution, stack.entries[1].fresnel,
                                    stack.params[1].m};
  const double mu_edge = std::sqrt(1.0 - double(b.eta) * double(b.eta));
  cpu::Pcg32 pcg(11, 12);
  double up = 0.0;
  double beyond = 0.0;
  const int draws = test::kSanitized ? 1 << 15 : 1 << 18;
  for (int d = 0; d < draws; ++d) {
    // A cosine-weighted direction under the boundary, pointing away from it.
    const double r = std::sqrt(pcg.uniform());
    const double phi = 2.0 * test::kPi * pcg.uniform();
    const vec3 x(float(r * std::cos(phi)), float(r * std::sin(phi)), -float(std::sqrt(std::max(0.0, 1.0 - r * r))));
    const cpu::MicrosurfaceSample s = cpu::microsurface_sample(b, x, pcg);
    if (s.direction.z <= 0.0f) continue;
    up += s.weight;
    if (s.direction.z < mu_edge) beyond += s.weight;
  }
  const double g = beyond / up;
  CAPTURE(g);
  CAPTURE(keep.x);
  CHECK(g > 0.03);
  CHECK(1.0 - double(keep.x) == doctest::Approx(g).epsilon(0.15));
  // Against the reference, under three_interfaces' tint (which, with a 1.3 coat over this guide,
  // was 6.5% too red without the loss).
  cpu::Evaluator paint = test::evaluator_from_text(guided_stack(kRoughFilm, "[0.6, 0.2, 0.05]"));
  check_albedo_against_reference(paint.bind(ShadingContext{}), {0.0, 40.0}, 0.04, 0.0,
                                 test::kSanitized ? 1 << 13 : 1 << 16);
}

TEST_CASE("a coat over a metal follows the light the metal traps from where the metal's lobe puts it") {
  // gold_metallic_paint (a 1-degree coat of index 1.85 over 13-degree gold): from 40 to 70 degrees
  // the metal sends much of what it reflects just beyond the coat's critical angle, whence it soon
  // returns into the cone. Followed at the mean cosine of light spread evenly outside the cone, it
  // was largely lost: 5.6% to 8.3% below the reference there; from where the lobe puts it, within
  // 2%.
  std::string text = test::read_file(test::source_dir() / "examples" / "materials" / "gold_metallic_paint.json");
  text = glsl::replace_all(text, R"("surface")", R"("model": "energy_conserving", "surface")");
  cpu::Evaluator e = test::evaluator_from_text(text);
  REQUIRE(e.program().model == kernels::LAMINA_MODEL_ENERGY_CONSERVING);
  check_albedo_against_reference(e.bind(ShadingContext{}), {40.0, 50.0, 60.0, 70.0}, 0.04, 0.0,
                                 test::kSanitized ? 1 << 13 : 1 << 16);
}

TEST_CASE("what a smooth coat sends back of a metal's light near the cone's edge is read where that light lies") {
  // silver_paint (a 7-degree coat of index 1.7 over 10-degree silver) at grazing views: the light
  // reaches the metal at the exit cone's edge, and the part of its lobe inside the cone lies well
  // inside it, where the coat lets most of it out. With the echo read at the arriving angle, the
  // model was 5.6% to 9.6% above the reference from 70 to 89 degrees (and a near-perfect mirror
  // under the same coat reflected 1.05, conserving_mirror); read at the mean angle of the lobe's
  // part inside the cone (lamina_exit_reflected), within 3.1%.
  cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples" / "materials" / "silver_paint.json",
                                          kernels::LAMINA_MODEL_ENERGY_CONSERVING);
  check_albedo_against_reference(e.bind(ShadingContext{}), {70.0, 80.0, 85.0, 89.0}, 0.045, 4.0,
                                 test::kSanitized ? 1 << 13 : 1 << 16);
}

TEST_CASE("a rough coat over black reflects what the reference's multiply scattering boundary does, never more") {
  // Only the coat reflects. Its single-scattering lobe alone falls 6% to 11% short of the Smith
  // microsurface the reference walks between 60 and 89 degrees; raised by the surplus M (energy.glsl)
  // it comes within 4%, except where a wide lobe at grazing views meets directions of smaller gain
  // (GGX from 85 degrees: up to 17% short at 89), and it never reflects more than the microsurface.
  for (const std::string roughness : {"10.0", "25.0"}) {
    for (const std::string distribution : {"beckmann", "ggx"}) {
      const std::string text =
          glsl::replace_all(coat_over_lambert(1.5, 0.0, "energy_conserving"), R"("roughness_deg": 0.0)",
                            R"("roughness_deg": )" + roughness + R"(, "distribution": ")" + distribution + R"(")");
      cpu::Evaluator e = test::evaluator_from_text(text);
      const cpu::ShadingPoint point = e.bind(ShadingContext{});
      cpu::ReferenceOptions options;
      options.walks = test::kSanitized ? 1 << 13 : 1 << 16;
      for (double theta : {0.0, 45.0, 70.0, 80.0, 85.0, 89.0}) {
        const vec3 wo = test::to_float(test::spherical(test::radians(theta), 0.0));
        const double model = double(point.albedo(wo, 16384).x);
        const cpu::ReferenceEstimate reference = cpu::reference_albedo(point, wo, options);
        CAPTURE(roughness);
        CAPTURE(distribution);
        CAPTURE(theta);
        CAPTURE(model);
        CAPTURE(reference.value.x);
        CAPTURE(reference.std_error.x);
        const double noise = 4.0 * reference.std_error.x;
        CHECK(model <= 1.01 * reference.value.x + noise);
        if (distribution == "beckmann" || theta <= 80.0)
          CHECK(std::abs(model - reference.value.x) <= 0.04 * reference.value.x + noise);
      }
    }
  }
}

TEST_CASE("a smooth clear coat over a smooth metal reflects the series of its two parallel mirrors") {
  // Light enters with 1 - F(mu), the metal reflects R(mu') at the refracted cosine, the coat sends
  // F(mu) of it back down and lets 1 - F(mu) out, every round trip along the same direction:
  // F + (1 - F)^2 R / (1 - F R). Without the echo the model reflects F + (1 - F)^2 R. From 58
  // degrees on, before block C had a cosine axis aligned with the exit cone, the model read part of
  // the metal's mirror direction as outside the cone and also returned it as trapped light: 1.03 at
  // 60 degrees, 1.15 at 70, more than it receives; lobe samplers alone never saw it (pdf 0 there).
  const double eta = 1.5;
  const std::complex<double> silver(0.155, 3.6);  // absolute; relative to the coat below
  cpu::Evaluator e =
      test::evaluator_from_text(R"({"format": 1, "materials": [{"name": "mirror", "model": "energy_conserving",
    "surface": "@coat", "nodes": [
    {"id": "coat", "type": "layer", "interface": "@glass", "base": "@metal"},
    {"id": "glass", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 0.0},
    {"id": "metal", "type": "substrate/conductor", "n": [0.155, 0.155, 0.155], "k": [3.6, 3.6, 3.6], "roughness_deg": 0.0}]}]})");
  for (double theta : {0.0, 20.0, 40.0, 60.0, 70.0, 80.0, 85.0}) {
    const double mu = std::cos(test::radians(theta));
    const double mu_below = std::sqrt(1.0 - (1.0 - mu * mu) / (eta * eta));
    const double f = test::fresnel_reference(mu, eta);
    const double r = test::fresnel_reference(mu_below, silver / eta);
    const double expected = f + (1.0 - f) * (1.0 - f) * r / (1.0 - f * r);
    const double once = f + (1.0 - f) * (1.0 - f) * r;
    vec3 albedo = e.albedo(ShadingContext{}, test::to_float(test::spherical(test::radians(theta), 0.0)), 16384);
    CAPTURE(theta);
    CAPTURE(expected);
    CAPTURE(once);
    // The table's smooth E (within 0.011 of F) and its cone shares, interpolated in the cosine.
    CHECK(double(albedo.x) == doctest::Approx(expected).epsilon(0.01).scale(0.0));
  }
}

TEST_CASE("light a rough metal traps under a rough coat comes back out as the reference's does") {
  // Most of what a rough metal reflects under a coat of index 1.7 leaves the exit cone and is
  // totally reflected back; the reference follows it out. Without the trapped light the model fell
  // 28% to 42% short of the reference here (conserving_silver); with it, it comes within 8%.
  cpu::Evaluator e = test::load_evaluator(test::source_dir() / "tests" / "data" / "physics" / "conserving_silver.json");
  check_albedo_against_reference(e.bind(ShadingContext{}), {0.0, 30.0, 60.0, 80.0}, 0.08, 4.0,
                                 test::kSanitized ? 1 << 12 : 1 << 16);
}

TEST_CASE("light under a rough coat goes on deeper than Snell's law, where the coat's own walks send it") {
  // The facets a grazing ray sees tilt towards it, and those facing it let more through
  // (lamina_arrival_cosine). The walks of a 10- and an 18-degree Beckmann coat of 1.5: the mean
  // angle of the light they let through, against the kernel's.
  for (double roughness : {10.0, 18.0}) {
    const cpu::MicrosurfaceBoundary b{1.5f, 0, 0, float(std::tan(test::radians(roughness)))};
    cpu::Pcg32 pcg(21, 22);
    const int draws = test::kSanitized ? 1 << 14 : 1 << 17;
    for (double theta : {30.0, 60.0, 80.0, 85.0, 89.0}) {
      const vec3 x = test::to_float(test::spherical(test::radians(theta), 0.0));
      double weight = 0.0;
      double angle = 0.0;
      for (int d = 0; d < draws; ++d) {
        const cpu::MicrosurfaceSample s = cpu::microsurface_sample(b, x, pcg);
        if (s.direction.z >= 0.0f) continue;
        weight += s.weight;
        angle += s.weight * std::acos(double(-s.direction.z));
      }
      const double walks = angle / weight * 180.0 / test::kPi;
      const float mu = float(std::cos(test::radians(theta)));
      const float snell = kernels::lamina_cosine_below(mu, b.eta);
      const double model = std::acos(double(kernels::lamina_arrival_cosine(mu, snell, b.eta, b.m))) * 180.0 / test::kPi;
      CAPTURE(roughness);
      CAPTURE(theta);
      CAPTURE(walks);
      CAPTURE(model);
      CHECK(std::abs(model - walks) < 0.6);
      CHECK(model >= std::acos(double(snell)) * 180.0 / test::kPi - 0.01);
    }
  }
  // A smooth coat refracts by Snell's law.
  const float snell = kernels::lamina_cosine_below(0.3f, 1.5f);
  CHECK(kernels::lamina_arrival_cosine(0.3f, snell, 1.5f, 0.0f) == snell);
}

TEST_CASE("what a rough boundary lets through beyond its critical angle falls off as its walks say") {
  // lamina_edge_ramp from the table's two sides, against the boundary's own walks from its denser
  // side: T at the edge, and a ramp (Beckmann) or an exponential (GGX) of the same flux past it.
  struct Case {
    int distribution;
    double degrees;
    float ior;
  };
  cpu::Pcg32 pcg(31, 32);
  const int draws = test::kSanitized ? 1 << 14 : 1 << 16;
  for (const Case c : {Case{0, 17.0, 1.35f}, Case{2, 8.0, 1.45f}}) {
    // Light from below, the dense side.
    const cpu::MicrosurfaceBoundary b{c.ior, c.distribution, 0, float(std::tan(test::radians(c.degrees)))};
    const float eta = 1.0f / c.ior;  // seen from the dense side
    const vec3 ramp = kernels::lamina_edge_ramp(c.distribution, 0, kernels::lamina_albedo_grid_xy(b.m, eta),
                                                kernels::lamina_albedo_grid_xy(b.m, c.ior), eta);
    const double edge = std::asin(double(eta));
    for (double past : {0.0, 4.0, 8.0, 12.0}) {
      const double theta = edge + test::radians(past);
      const vec3 x(float(std::sin(theta)), 0.0f, -float(std::cos(theta)));
      double up = 0.0;
      for (int d = 0; d < draws; ++d) {
        const cpu::MicrosurfaceSample s = cpu::microsurface_sample(b, x, pcg);
        if (s.direction.z > 0.0f) up += s.weight;
      }
      const double walks = up / draws;
      const double gap = (std::cos(edge) - std::cos(theta)) / double(ramp.y);
      const double model = double(ramp.x) * (c.distribution == 2 ? std::exp(-2.0 * gap) : std::max(1.0 - gap, 0.0));
      CAPTURE(c.distribution);
      CAPTURE(past);
      CAPTURE(walks);
      CAPTURE(model);
      CHECK(std::abs(model - walks) < 0.03);
    }
  }
}

TEST_CASE("a boundary's table read from below gives what it lets out of a metal's lobe") {
  // A metal under a coat reflects light from normal incidence into its lobe; of the part inside the
  // exit cone the coat lets out, in its own walks from below, what the table's T = 1 - E - M read
  // from below says. (Read from above at the Snell direction, as the carry's T(v) is, it says more
  // for such a wide lobe: 0.95 against the walks' 0.87 under the GGX coat, 0.91 against 0.72 under
  // the coat of 1.7; README, ggx_lacquer_metal.)
  struct Case {
    int distribution;
    double coat_degrees;
    float ior;
    double metal_degrees;
  };
  cpu::Pcg32 pcg(41, 42);
  const int draws = test::kSanitized ? 1 << 16 : 1 << 17;
  for (const Case c : {Case{2, 8.0, 1.45f, 15.0}, Case{0, 18.0, 1.7f, 18.0}}) {
    // Light from below, the dense side.
    const cpu::MicrosurfaceBoundary b{c.ior, c.distribution, 0, float(std::tan(test::radians(c.coat_degrees)))};
    const float m_metal = float(std::tan(test::radians(c.metal_degrees)));
    const glm::vec2 below = kernels::lamina_albedo_grid_xy(b.m, 1.0f / c.ior);
    const float mu_edge = kernels::lamina_cos_critical(c.ior);
    const vec3 l(0.0f, 0.0f, 1.0f);
    double lobe = 0.0;
    double walks = 0.0;
    double table = 0.0;
    for (int d = 0; d < draws; ++d) {
      // The metal's lobe D G / (4 cos_l cos_v) cos_v drawn by its normals: weight G (l.h) / (cos_l cos_h).
      const float u1 = pcg.uniform();  // one draw per statement: the same sequence under every compiler
      const float u2 = pcg.uniform();
      const vec3 h = kernels::sample_microfacet_normal(c.distribution, m_metal, glm::vec2(u1, u2));
      const float lh = glm::dot(l, h);
      const vec3 w = 2.0f * lh * h - l;
      if (w.z <= mu_edge || lh <= 0.0f) continue;
      const double weight = kernels::g_microfacet(c.distribution, l.z, w.z, h.z, lh, m_metal) * lh / (l.z * h.z);
      const cpu::MicrosurfaceSample s = cpu::microsurface_sample(b, vec3(w.x, w.y, -w.z), pcg);
      float multiple = 0.0f;
      lobe += weight;
      walks += s.direction.z > 0.0f ? weight * s.weight : 0.0;
      table += weight * (1.0f - kernels::lamina_boundary_energy(c.distribution, 0, below, w.z, 1.0f / c.ior, multiple));
    }
    CAPTURE(c.ior);
    CAPTURE(walks / lobe);
    CAPTURE(table / lobe);
    CHECK(table / lobe == doctest::Approx(walks / lobe).epsilon(0.03));
  }
}

TEST_CASE("a rough coat over a metal lets out what the reference does, where the metal's light really goes") {
  // ggx_lacquer_metal (an 8-degree GGX coat over a wider 15-degree GGX metal) was 4.5% to 6.4% too
  // bright at every angle while the carry let the metal's light out as the coat passes light from
  // above (lamina_exit_reflected's keep); unclamped_metal (an 18-degree coat over a 3-degree metal)
  // was 8.7% too bright at 85 degrees while the metal's share inside the cone was read at the mean
  // arrival (lamina_arrival_reflected, lamina_trap_gain's deeper stream). Both within 5% here.
  const char* files[] = {"tests/data/physics/ggx_lacquer_metal.json", "tests/data/physics/unclamped_metal.json"};
  for (const char* file : files) {
    CAPTURE(file);
    cpu::Evaluator e = test::load_evaluator(test::source_dir() / file);
    check_albedo_against_reference(e.bind(ShadingContext{}), {0.0, 50.0, 75.0, 85.0}, 0.05, 4.0,
                                   test::kSanitized ? 1 << 12 : 1 << 16);
  }
}

TEST_CASE("a rough coat over a metal lets the light it traps out at its first return, as the reference does") {
  // blue_metallic (a 17-degree coat of 1.35 over aluminium, tinted) and schlick_gold (a 10-degree
  // coat of 1.5 over 8-degree gold): with the metal's light split where the coat really sends it
  // (lamina_arrival_cosine) and the trapped light let out just beyond the edge (lamina_trap_gain's
  // d), within 5% of the reference from 0 to 89 degrees; without, up to 6.8% and 5.6% too bright
  // at grazing views.
  for (const char* file : {"examples/materials/blue_metallic.json", "tests/data/physics/schlick_gold.json"}) {
    cpu::Evaluator e = test::load_evaluator(test::source_dir() / file);
    REQUIRE(e.program().model == kernels::LAMINA_MODEL_ENERGY_CONSERVING);
    CAPTURE(file);
    check_albedo_against_reference(e.bind(ShadingContext{}), {0.0, 60.0, 85.0, 89.0}, 0.05, 2.0,
                                   test::kSanitized ? 1 << 12 : 1 << 16);
  }
}

TEST_CASE("lamina glsl writes an energy-conserving material's table into the side file the host binds it from") {
  test::TempDir dir;
  // A smooth GGX boundary with the exact Fresnel term: one combination of the table.
  std::ofstream(dir.path() / "coat.json")
      << glsl::replace_all(coat_over_lambert(1.5, 0.8, "energy_conserving"), R"("roughness_deg": 0.0)",
                           R"("roughness_deg": 0.0, "distribution": "ggx", "fresnel": "exact")");
  test::RunResult r = test::run_cli("glsl coat.json -o coat.glsl", dir.path());
  REQUIRE(r.exit_code == 0);
  CHECK(test::listing(dir.path()) == std::vector<std::string>{"coat.glsl", "coat.json", "coat.uniforms.json"});
  std::ifstream side(dir.path() / "coat.uniforms.json");
  const nlohmann::json json = nlohmann::json::parse(side);
  REQUIRE(json["tables"].size() == 1);
  const nlohmann::json& table = json["tables"][0];
  CHECK(table["format"] == "R16UI");
  const int width = table["width"], height = table["height"];
  REQUIRE(table["texels"].size() == size_t(width) * size_t(height));
  // The integers C++ reads for that combination.
  namespace k = lamina::kernels;
  CHECK(height == k::LAMINA_ALBEDO_ETAS);
  const int combo = k::lamina_albedo_combo(2, 0);
  for (int y = 0; y < height; y += 5)
    for (int x = 0; x < width; x += 7)
      CHECK(table["texels"][size_t(y * width + x)] ==
            int(k::lamina_albedo_texel(x, k::LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[combo] + y)));
  std::ifstream module(dir.path() / "coat.glsl");
  const std::string text((std::istreambuf_iterator<char>(module)), std::istreambuf_iterator<char>());
  CHECK(text.find("uniform highp usampler2D " + table["name"].get<std::string>() + ";") != std::string::npos);
}

TEST_CASE("lamina glsl -o - refuses an energy-conserving material without --interface, and writes nothing") {
  test::TempDir dir;
  std::ofstream(dir.path() / "coat.json") << coat_over_lambert(1.5, 0.8, "energy_conserving");
  test::RunResult r = test::run_cli("glsl coat.json -o -", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("coat.json") != std::string::npos);
  CHECK(r.err.find("--interface") != std::string::npos);
  CHECK(test::listing(dir.path()) == std::vector<std::string>{"coat.json"});
  CHECK(test::run_cli("glsl coat.json -o - --interface coat.side.json", dir.path()).exit_code == 0);
  CHECK(test::listing(dir.path()) == std::vector<std::string>{"coat.json", "coat.side.json"});
  // The same stack under the Weidlich-Wilkie model reads no table and needs no side file.
  std::ofstream(dir.path() / "ww.json") << coat_over_lambert(1.5, 0.8, "weidlich_wilkie");
  test::RunResult ww = test::run_cli("glsl ww.json -o -", dir.path());
  CHECK(ww.exit_code == 0);
  CHECK(ww.out.find("usampler2D") == std::string::npos);
}

TEST_CASE("a coat over a near-perfect mirror never reflects more than it receives, whatever the two roughnesses") {
  // The examples' metals absorb a few percent at every bounce, which hides energy a composition
  // creates; a conductor of n 0.1, k 40 reflects more than 0.999. Every coat index, distribution
  // and pair of roughnesses below, with Elek's clamp and without (a rough coat over a smoother
  // metal), from normal incidence to 89 degrees, densest where the trapped light is most (grazing):
  // no channel above 1 + 0.005, the furnace test's tolerance, on the finer quadrature where the
  // coarse one comes near 1. Under the sanitisers, every fourth stack.
  const std::vector<double> angles = test::kSanitized
                                         ? std::vector<double>{0.0, 60.0, 85.0, 89.0}
                                         : std::vector<double>{0.0, 30.0, 60.0, 75.0, 80.0, 85.0, 87.0, 89.0};
  int stacks = 0, combination = 0;
  double largest = 0.0;
  for (const char* ior : {"1.2", "1.5", "2.0", "2.6"})
    for (const char* distribution : {"ggx", "beckmann"})
      for (const char* coat : {"0.0", "4.0", "15.0", "35.0"})
        for (const char* metal : {"1.0", "10.0", "30.0"})
          for (const char* clamp : {"true", "false"}) {
            const std::string text = std::string(R"({"format": 1, "materials": [{"name": "mirror",
              "model": "energy_conserving", "clamp_lower_roughness": )") +
                                     clamp + R"(, "surface": "@coat", "nodes": [
              {"id": "coat", "type": "layer", "interface": "@glass", "base": "@mirror"},
              {"id": "glass", "type": "interface/dielectric", "ior": )" +
                                     ior + R"(, "roughness_deg": )" + coat + R"(, "distribution": ")" + distribution +
                                     R"("},
              {"id": "mirror", "type": "substrate/conductor", "n": [0.1, 0.1, 0.1], "k": [40.0, 40.0, 40.0],
               "roughness_deg": )" + metal +
                                     R"(, "distribution": ")" + distribution + R"("}]}]})";
            if (test::kSanitized && combination++ % 4 != 0) continue;
            cpu::Evaluator e = test::evaluator_from_text(text);
            ++stacks;
            for (double theta : angles) {
              const vec3 wo = test::to_float(test::spherical(test::radians(theta), 0.0));
              vec3 albedo = e.albedo(ShadingContext{}, wo, 1024);
              if (double(glm::max(albedo.x, glm::max(albedo.y, albedo.z))) > 0.95)
                albedo = e.albedo(ShadingContext{}, wo, 16384);
              CAPTURE(ior);
              CAPTURE(distribution);
              CAPTURE(coat);
              CAPTURE(metal);
              CAPTURE(clamp);
              CAPTURE(theta);
              CHECK(double(albedo.x) <= 1.005);
              largest = std::max(largest, double(albedo.x));
            }
          }
  MESSAGE("largest albedo of " << stacks << " coats over a near-perfect mirror: " << largest);
  CHECK(stacks > 0);
}
