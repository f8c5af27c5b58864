// Physical and statistical properties of the CPU evaluator on every example material (DESIGN.md,
// Testing): finite and non-negative values, reciprocity, the white furnace, chi-square goodness of
// fit of sample() against pdf() as pbrt tests its BSDFs, pdf normalisation, consistency of the
// entry points, an independent double-precision transcription of Elek's Algorithm 1, and the mix.
// Every random number comes from a fixed-seed std::mt19937_64.
#include <doctest/doctest.h>

#include <chrono>
#include <complex>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cpu_test_support.h"
#include "graph/cpu/reference.h"
#include "nodes/kernels/kernels.h"
#include "random_stacks.h"
#include "test_support.h"

using namespace lamina;
using glm::dvec3;
using glm::vec2;
using glm::vec3;

namespace {

enum class Origin {
  Bundled,  // an example of examples/materials
  Physics,  // a test material of tests/data/physics
  Random,   // a random valid stack of tests/random_stacks.h
};

struct Example {
  std::string name;
  std::string text;  // the material file, with this one material
  cpu::Evaluator evaluator;
  bool textured;
  Origin origin;
};

// How many random valid stacks join the examples, and their seed: nested layers and mixes, every
// substrate, distribution and Fresnel term, some parameters textured (tests/random_stacks.h).
constexpr int kRandomStacks = 6;
constexpr uint32_t kRandomSeed = 2;

// tests/data/physics/*.json, sorted: materials for what the examples leave out (GGX, normalised
// Blinn, clamp_lower_roughness false, the approximate Fresnel terms, three distinct interfaces).
std::vector<std::filesystem::path> physics_test_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(test::source_dir() / "tests" / "data" / "physics"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Every example, every physics test material and kRandomStacks random valid stacks; the suite runs
// on all of them.
const std::vector<Example>& examples() {
  static const std::vector<Example> all = [] {
    std::vector<Example> list;
    auto add = [&](std::string name, std::string text, cpu::Evaluator e, Origin origin) {
      bool textured = !e.program().ops.empty();
      list.push_back({std::move(name), std::move(text), std::move(e), textured, origin});
    };
    for (bool bundled : {true, false})
      for (const auto& file : bundled ? test::example_files() : physics_test_files())
        add(file.stem().string(), test::read_file(file), test::load_evaluator(file),
            bundled ? Origin::Bundled : Origin::Physics);
    const nlohmann::json random = nlohmann::json::parse(test::RandomStacks(kRandomSeed).file(kRandomStacks));
    for (const auto& material : random.at("materials")) {
      std::string text = nlohmann::json{{"format", random.at("format")}, {"materials", {material}}}.dump();
      add(material.at("name").get<std::string>(), text, test::evaluator_from_text(text), Origin::Random);
    }
    REQUIRE(list.size() >= 23 + kRandomStacks);
    return list;
  }();
  return all;
}

// The seeds' Weidlich-Wilkie model of every example and test material that does not name its
// model (they get the energy-conserving default in examples()), composed as `--model` does. The
// tests that are about the model itself (values, reciprocity, the furnace's documented excess,
// Elek's transcription) run on these too; the random stacks already hold both models.
const std::vector<Example>& weidlich_wilkie_copies() {
  static const std::vector<Example> all = [] {
    std::vector<Example> list;
    for (bool bundled : {true, false})
      for (const auto& file : bundled ? test::example_files() : physics_test_files()) {
        std::string text = test::read_file(file);
        if (nlohmann::json::parse(text).at("materials").at(0).contains("model")) continue;
        cpu::Evaluator e = test::load_evaluator(file, lamina::kernels::LAMINA_MODEL_WEIDLICH_WILKIE);
        bool textured = !e.program().ops.empty();
        list.push_back({file.stem().string(), std::move(text), std::move(e), textured,
                        bundled ? Origin::Bundled : Origin::Physics});
      }
    REQUIRE(list.size() >= 20);
    return list;
  }();
  return all;
}

// examples() and weidlich_wilkie_copies(), for the tests about each model's own properties.
std::vector<const Example*> examples_in_both_models() {
  std::vector<const Example*> out;
  for (const auto* list : {&examples(), &weidlich_wilkie_copies()})
    for (const Example& e : *list) out.push_back(&e);
  return out;
}

// An example's name with its model when the model is not the default.
std::string label(const Example& e) {
  return e.evaluator.program().model == lamina::kernels::LAMINA_MODEL_WEIDLICH_WILKIE && e.origin != Origin::Random
             ? e.name + " (weidlich_wilkie)"
             : e.name;
}

// The example or test material of that name; fails the test when there is none.
const Example& example_named(const std::string& name) {
  auto it = std::find_if(examples().begin(), examples().end(), [&](const Example& e) { return e.name == name; });
  REQUIRE_MESSAGE(it != examples().end(), "no example " << name);
  return *it;
}

float to_unit_float(double u) { return std::min(float(u), 0x1.fffffep-1f); }

ShadingContext at_uv(vec2 uv) {
  ShadingContext ctx;
  ctx.uv = uv;
  return ctx;
}

vec2 random_uv(std::mt19937_64& rng) { return {to_unit_float(test::uniform(rng)), to_unit_float(test::uniform(rng))}; }

bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool non_negative(vec3 v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }
float max_component(vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

std::string describe(vec3 v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

// A direction in a mix that stresses the evaluator: uniform cosines, cosines log-uniform down to
// 1e-6, exactly grazing (z = 0), exactly normal, below the horizon (z = -0 included), and near the
// mirror of `partner` (inside the narrow lobes) when one is given.
vec3 stress_direction(std::mt19937_64& rng, const vec3* partner) {
  double kind = test::uniform(rng);
  double phi = 2.0 * test::kPi * test::uniform(rng);
  if (kind < 0.30) return test::to_float(test::from_cosine(test::uniform(rng), phi));
  if (kind < 0.50) return test::to_float(test::from_cosine(std::pow(10.0, -6.0 * test::uniform(rng)), phi));
  if (kind < 0.55) return vec3(float(std::cos(phi)), float(std::sin(phi)), 0.0f);
  if (kind < 0.58) return vec3(0.0f, 0.0f, 1.0f);
  if (kind < 0.60) return vec3(float(std::cos(phi)), float(std::sin(phi)), -0.0f);
  if (kind < 0.70) return test::to_float(test::from_cosine(-test::uniform(rng), phi));
  if (partner == nullptr || partner->z <= 0.0f) return test::to_float(test::from_cosine(test::uniform(rng), phi));
  // Within 1e-5 to 0.3 rad (log-uniform) of the mirror direction.
  double angle = std::pow(10.0, -5.0 + 4.5 * test::uniform(rng));
  return test::to_float(test::Frame(test::mirror(test::to_double(*partner))).direction(angle, phi));
}

// An ordinary direction above the horizon: cosine uniform in [1e-4, 1] (70%) or log-uniform in
// [1e-4, 1] (30%), or, with a partner, log-uniformly within `max_angle` of its mirror direction.
dvec3 upper_direction(std::mt19937_64& rng, const dvec3* partner, double mirror_share, double min_angle,
                      double max_angle) {
  double kind = test::uniform(rng);
  double phi = 2.0 * test::kPi * test::uniform(rng);
  if (partner != nullptr && kind < mirror_share) {
    double angle = min_angle * std::pow(max_angle / min_angle, test::uniform(rng));
    dvec3 w = test::Frame(test::mirror(*partner)).direction(angle, phi);
    if (w.z > 1.0e-4) return w;
  }
  double cos_theta = test::uniform(rng) < 0.7 ? 1.0e-4 + (1.0 - 1.0e-4) * test::uniform(rng)
                                              : std::pow(10.0, -4.0 * test::uniform(rng));
  return test::from_cosine(cos_theta, phi);
}

}  // namespace

// --- the statistics helpers themselves ------------------------------------------------------

TEST_CASE("the chi-square p-value matches closed forms of the incomplete gamma function") {
  // Q(1, x) = e^-x (dof 2); Q(1/2, x) = erfc(sqrt(x)) (dof 1); Q(2, x) = (1 + x) e^-x (dof 4).
  for (double x : {1.0e-3, 0.1, 0.5, 1.0, 2.0, 5.0, 20.0, 100.0}) {
    CAPTURE(x);
    CHECK(test::gamma_q(1.0, x) == doctest::Approx(std::exp(-x)).epsilon(1.0e-12).scale(0.0));
    CHECK(test::gamma_q(0.5, x) == doctest::Approx(std::erfc(std::sqrt(x))).epsilon(1.0e-10).scale(0.0));
    CHECK(test::gamma_q(2.0, x) == doctest::Approx((1.0 + x) * std::exp(-x)).epsilon(1.0e-12).scale(0.0));
  }
  // Large degrees of freedom, as the binned tests use: the median of chi2(k) is about
  // k (1 - 2/(9k))^3, and the upper 1% point of chi2(1000) is 1106.969 (standard tables).
  for (int dof : {100, 1000, 3000}) {
    double k = double(dof);
    CHECK(test::chi_square_p_value(k * std::pow(1.0 - 2.0 / (9.0 * k), 3.0), dof) ==
          doctest::Approx(0.5).epsilon(2e-3).scale(0.0));
  }
  CHECK(test::chi_square_p_value(1106.969, 1000) == doctest::Approx(0.01).epsilon(1e-3).scale(0.0));
  CHECK(test::sidak(0.01, 1) == doctest::Approx(0.01));
}

// --- 1 and 6: values ---------------------------------------------------------------------------

TEST_CASE("every example gives finite, non-negative f and pdf, exactly 0 below the horizon, and eval_pdf agrees") {
  const int pairs = 100000 / test::kSanitizerDivisor;
  for (const Example* each : examples_in_both_models()) {
    const Example& example = *each;
    CAPTURE(label(example));
    std::mt19937_64 rng(0x5eed0001);
    long bad_value = 0, nonzero_below = 0, eval_pdf_differs = 0, grazing = 0;
    std::string first_bad, first_below, first_differs;
    for (int i = 0; i < pairs; ++i) {
      vec3 wo = stress_direction(rng, nullptr);
      vec3 wi = stress_direction(rng, &wo);
      ShadingContext ctx = at_uv(random_uv(rng));
      vec3 f = example.evaluator.eval(ctx, wi, wo);
      float pdf = example.evaluator.pdf(ctx, wi, wo);
      cpu::EvalPdf both = example.evaluator.eval_pdf(ctx, wi, wo);
      auto where = [&] {
        return "wi " + describe(wi) + " wo " + describe(wo) + " uv " + describe(vec3(ctx.uv, 0.0f)) + ": f " +
               describe(f) + " pdf " + std::to_string(pdf) + "; eval_pdf " + describe(both.f) + " " +
               std::to_string(both.pdf);
      };
      if (wi.z <= 0.0f || wo.z <= 0.0f) {
        if (f != vec3(0.0f) || pdf != 0.0f || both.f != vec3(0.0f) || both.pdf != 0.0f) {
          if (nonzero_below++ == 0) first_below = where();
        }
        continue;
      }
      if (std::min(wi.z, wo.z) < 1.0e-3f) ++grazing;
      if (!finite(f) || !non_negative(f) || !std::isfinite(pdf) || pdf < 0.0f) {
        if (bad_value++ == 0) first_bad = where();
      }
      // The same arithmetic on the same inputs: equal bit for bit.
      if (both.f != f || both.pdf != pdf) {
        if (eval_pdf_differs++ == 0) first_differs = where();
      }
    }
    CHECK_MESSAGE(bad_value == 0, first_bad);
    CHECK_MESSAGE(nonzero_below == 0, first_below);
    CHECK_MESSAGE(eval_pdf_differs == 0, first_differs);
    CHECK(grazing > pairs / 10);  // the grazing cases were exercised
  }
}

// --- 2: reciprocity ----------------------------------------------------------------------------

TEST_CASE("every example is reciprocal: f(wi, wo) = f(wo, wi)") {
  const int pairs = 10000 / test::kSanitizerDivisor;
  std::string summary =
      "reciprocity, max |f(wi,wo) - f(wo,wi)| / max(|f|, 1e-6 max_c f), " + std::to_string(pairs) + " pairs:\n";
  for (const Example* each : examples_in_both_models()) {
    const Example& example = *each;
    CAPTURE(label(example));
    // Fluorescence is not reciprocal: light re-radiated at a longer wavelength cannot go back. What
    // holds there is that the adjoint is the transpose (the next test).
    if (example.evaluator.bind(ShadingContext{}).fluorescent()) continue;
    std::mt19937_64 rng(0x5eed0002);
    double worst = 0.0;
    std::string worst_where;
    for (int i = 0; i < pairs; ++i) {
      dvec3 wo_d = upper_direction(rng, nullptr, 0.0, 0.0, 0.0);
      dvec3 wi_d = upper_direction(rng, &wo_d, 0.3, 1.0e-5, 0.3);
      vec3 wo = test::to_float(wo_d), wi = test::to_float(wi_d);
      ShadingContext ctx = at_uv(random_uv(rng));
      vec3 a = example.evaluator.eval(ctx, wi, wo), b = example.evaluator.eval(ctx, wo, wi);
      double floor = 1.0e-6 * double(std::max(max_component(a), max_component(b)));
      for (int c = 0; c < 3; ++c) {
        double scale = std::max(double(std::max(a[c], b[c])), floor);
        if (scale <= 0.0) continue;
        double error = std::abs(double(a[c]) - double(b[c])) / scale;
        if (error > worst) {
          worst = error;
          worst_where = "wi " + describe(wi) + " wo " + describe(wo) + ": " + describe(a) + " vs " + describe(b);
        }
      }
    }
    CHECK_MESSAGE(worst <= 1.0e-5, worst_where);
    char line[200];
    std::snprintf(line, sizeof line, "  %-40s %.3g\n", label(example).c_str(), worst);
    summary += line;
  }
  MESSAGE(summary);
}

TEST_CASE("every example's adjoint is its transpose: y . f(wi, wo) x = x . f^T(wi, wo) y, for lights x and weights y") {
  // Without fluorescence this is reciprocity again, per channel; through a fluorescent base it is
  // the transposed matrix a path traced from the viewer needs.
  const int pairs = 2000 / test::kSanitizerDivisor;
  for (const Example* each : examples_in_both_models()) {
    const Example& example = *each;
    CAPTURE(label(example));
    std::mt19937_64 rng(0x5eed0012);
    double worst = 0.0;
    for (int i = 0; i < pairs; ++i) {
      dvec3 wo_d = upper_direction(rng, nullptr, 0.0, 0.0, 0.0);
      dvec3 wi_d = upper_direction(rng, &wo_d, 0.3, 1.0e-5, 0.3);
      const vec3 wo = test::to_float(wo_d), wi = test::to_float(wi_d);
      const vec3 x(float(test::uniform(rng)), float(test::uniform(rng)), float(test::uniform(rng)));
      const vec3 y(float(test::uniform(rng)), float(test::uniform(rng)), float(test::uniform(rng)));
      const ShadingContext ctx = at_uv(random_uv(rng));
      const double forward = double(glm::dot(y, example.evaluator.eval(ctx, wi, wo, x)));
      const double adjoint = double(glm::dot(x, example.evaluator.eval_adjoint(ctx, wi, wo, y)));
      const double scale = std::max({std::abs(forward), std::abs(adjoint), 1.0e-6});
      worst = std::max(worst, std::abs(forward - adjoint) / scale);
    }
    CHECK(worst <= 1.0e-5);
  }
}

// --- 3: white furnace --------------------------------------------------------------------------

namespace {

// The uvs at which textured examples are probed: 4 squares of an 8 x 8 checker along u (both
// colours of checker_tiles twice), and 6 random points (2 and 2 under the sanitisers).
std::vector<vec2> probe_uvs(const Example& example) {
  if (!example.textured) return {vec2(0.5f)};
  std::vector<vec2> uvs;
  for (int i = 0; i < (test::kSanitized ? 2 : 4); ++i) uvs.push_back(vec2((float(i) + 0.5f) / 8.0f, 0.5f / 8.0f));
  std::mt19937_64 rng(0x5eed0003);
  for (int i = 0; i < (test::kSanitized ? 2 : 6); ++i) uvs.push_back(random_uv(rng));
  return uvs;
}

// The model of Weidlich and Wilkie is only approximately energy conserving (README, "Energy"),
// and these examples and test materials exceed 1 in the white furnace. Two causes, both properties
// of the model as Elek's Algorithm 1 defines it, not of the implementation:
//  - a glossy lobe below an interface of index n is evaluated at refracted directions, which
//    squeezes the outer hemisphere into the refracted cone; its albedo seen from outside grows by
//    up to n^2 (silver under n = 1.7: 0.97 * 0.93 * 2.89 = 2.6 for a lobe entirely inside the
//    cone; the radiance factor 1/n^2 of crossing back out is not part of the model), largest at
//    normal incidence;
//  - T = 1 - F(V.H) rather than 1 - F(theta_o), so at grazing incidence the layers below receive
//    far more than the Fresnel transmittance of the macro surface: the excess at 89 deg.
// Each bound is the largest albedo measured over theta_o in 0..89 deg (and the probed uvs), plus
// 3%, so a change in the model that adds energy fails here. Where it peaks is given beside it.
// README ("Energy") lists the examples with the same numbers. The bounds apply to the model's
// copies in weidlich_wilkie_copies(); every material of the default model is held to 1.
const std::map<std::string, double>& documented_excess() {
  static const std::map<std::string, double> bounds = {
      {"acrylic_lacquer", 1.010 * 1.03},           // 89 deg, G: T = 1 - F(V.H) at grazing only
      {"aventurine_glass", 1.835 * 1.03},          // 89 deg, R: copper under IOR 1.56, and T at V.H
      {"brass", 1.767 * 1.03},                     // 0 deg, R: gold under IOR 2
      {"car_paint", 1.076 * 1.03},                 // 89 deg, B
      {"ceramic_glaze", 1.801 * 1.03},             // 89 deg, B
      {"checker_tiles", 2.041 * 1.03},             // 0 deg, R, on a gold square
      {"christmas_orb", 1.846 * 1.03},             // 0 deg, R
      {"concrete_ball", 1.138 * 1.03},             // 89 deg, B
      {"flake_car_paint", 1.029 * 1.03},           // 89 deg, B: as car_paint, at one of 16 flakes probed once
      {"gold_metallic_paint", 1.978 * 1.03},       // 0 deg, R
      {"gold_paint", 1.570 * 1.03},                // 0 deg, R
      {"house_paint", 1.199 * 1.03},               // 89 deg, B
      {"lavender_lepidolite", 2.086 * 1.03},       // 0 deg, R: silver glitter under IOR 1.56
      {"patina_map_copper", 1.950 * 1.03},         // 0 deg, R, where the patina is thin
      {"pearlescent_white", 1.415 * 1.03},         // 89 deg, R: T at V.H, over a white base
      {"procedural_patina_copper", 1.680 * 1.03},  // 0 deg, R, bare copper under its tarnish
      {"red_lacquer", 1.689 * 1.03},               // 89 deg, R
      {"silver_paint", 2.399 * 1.03},              // 0 deg, R: silver under IOR 1.7
      {"sugar", 1.188 * 1.03},                     // 89 deg, R
      {"two_tone_pearl", 1.259 * 1.03},            // 89 deg, G: T at V.H, coated flakes over grey
      {"sunstone", 1.918 * 1.03},                  // 9 deg, R: copper glitter under IOR 1.58
      // Test materials (tests/data/physics), for the same two reasons.
      {"blinn_glaze", 1.296 * 1.03},        // 89 deg, R
      {"ggx_lacquer_metal", 1.104 * 1.03},  // 0 deg, B: a GGX metal under IOR 1.45
      {"lazanyi_copper", 1.500 * 1.03},     // 0 deg, R
      {"schlick_gold", 2.023 * 1.03},       // 0 deg, R: gold under IOR 1.5
      {"three_interfaces", 1.322 * 1.03},   // 89 deg, R
      {"unclamped_metal", 2.036 * 1.03},    // 0 deg, R: a narrow silver lobe under IOR 1.5
  };
  return bounds;
}

// A material without a documented excess may reach at most 1 + this, on an estimate accurate to
// about 0.1%: where the default quadrature (1024 points per lobe, within 0.3% of an adaptive one,
// see the next test) reads above kRefineAbove, Evaluator::albedo is computed again with
// kRefinedPoints per lobe.
constexpr double kUndocumentedTolerance = 0.005;
constexpr double kRefineAbove = 0.95;
constexpr int kRefinedPoints = 16384;

}  // namespace

TEST_CASE("every example's white furnace albedo at 0..89 deg is non-negative and within its documented bound") {
  // The energy each channel's light leaves with (Evaluator::energy): the albedo, but for a
  // fluorescent base, whose white-light albedo may exceed 1 in a channel that others feed.
  // Every degree from 0 to 89 (every sixth under the sanitisers, and 89); a textured example, probed
  // at several uvs, every third degree and each from 85 on, where the excesses peak.
  auto angles_of = [](const Example& example) {
    std::vector<int> angles;
    const int step = test::kSanitized ? 6 : example.textured ? 3 : 1;
    for (int a = 0; a < 90; a += step) angles.push_back(a);
    for (int a = test::kSanitized ? 89 : 85; a < 90; ++a)
      if (std::find(angles.begin(), angles.end(), a) == angles.end()) angles.push_back(a);
    return angles;
  };
  std::string report =
      "white furnace: directional albedo, largest channel (and over the probed uvs), Evaluator::albedo with 1024 "
      "points per lobe; rows of 10 degrees from theta_o = 0; R G B at 0, 60, 85 and 89 deg\n";
  for (const Example* each : examples_in_both_models()) {
    const Example& example = *each;
    CAPTURE(label(example));
    std::vector<vec2> uvs = probe_uvs(example);
    const std::vector<int> angles = angles_of(example);
    const bool conserving = example.evaluator.program().model == lamina::kernels::LAMINA_MODEL_ENERGY_CONSERVING;
    auto documented = documented_excess().find(example.name);
    const bool excess_documented = !conserving && documented != documented_excess().end();
    // Random stacks of the Weidlich-Wilkie model are held to finite, non-negative albedos only: the
    // model's excess over 1 is a property of each stack (see above), which nobody has measured and
    // written down for them. The energy-conserving model is held to 1 everywhere.
    const bool bounded = example.origin != Origin::Random || conserving;
    long bad = 0;
    double largest = 0.0, largest_checked = 0.0;
    std::string where, where_checked;
    std::map<int, vec3> by_angle;
    for (int theta : angles) {
      vec3 wo = test::to_float(test::spherical(test::radians(double(theta)), 0.0));
      vec3 most(0.0f);
      for (vec2 uv : uvs) {
        vec3 albedo = example.evaluator.energy(at_uv(uv), wo);
        if (!finite(albedo) || !non_negative(albedo)) ++bad;
        // Near or above 1, an undocumented material's value is checked on the finer quadrature.
        vec3 checked = albedo;
        if (bounded && !excess_documented && double(max_component(albedo)) > kRefineAbove)
          checked = example.evaluator.energy(at_uv(uv), wo, kRefinedPoints);
        for (int c = 0; c < 3; ++c) {
          char text[160];
          std::snprintf(text, sizeof text, "theta_o %d deg, channel %c, uv (%.3f, %.3f)", theta, "RGB"[c], double(uv.x),
                        double(uv.y));
          if (double(albedo[c]) > largest) {
            largest = double(albedo[c]);
            where = text;
          }
          if (double(checked[c]) > largest_checked) {
            largest_checked = double(checked[c]);
            where_checked = text;
          }
        }
        most = glm::max(most, albedo);
      }
      by_angle[theta] = most;
    }
    CHECK(bad == 0);
    if (!bounded) {
      // nothing more to check
    } else if (excess_documented) {
      CHECK_MESSAGE(largest <= documented->second, "largest albedo " << largest << " at " << where);
      // A textured example's excess may be one state's that the probed uvs miss (flake_car_paint's is
      // one flake's, at 89 degrees: 1.029 over 16 flakes, 0.93 over these 10 uvs).
      if (!example.textured)
        CHECK_MESSAGE(largest > 1.0 + kUndocumentedTolerance,
                      "no longer exceeds 1: drop it from documented_excess() and the README");
    } else {
      CHECK_MESSAGE(largest_checked <= 1.0 + kUndocumentedTolerance,
                    "albedo " << largest_checked << " at " << where_checked << " (" << kRefinedPoints
                              << " points per lobe) exceeds 1: find out why, then document it in "
                                 "documented_excess() and the README");
    }
    char head[200];
    std::snprintf(head, sizeof head, "%s%s: largest %.4f at %s%s\n", label(example).c_str(),
                  example.origin == Origin::Bundled   ? ""
                  : example.origin == Origin::Physics ? " (test material)"
                                                      : " (random stack)",
                  largest, where.c_str(),
                  example.textured ? (" (" + std::to_string(uvs.size()) + " uvs)").c_str() : "");
    report += head;
    std::string row;
    for (size_t i = 0; i < angles.size(); ++i) {
      if (angles[i] / 10 != (i == 0 ? -1 : angles[i - 1] / 10)) {
        if (!row.empty()) report += row + "\n";
        char label[16];
        std::snprintf(label, sizeof label, "  %2d:", angles[i] / 10 * 10);
        row = label;
      }
      char cell[16];
      std::snprintf(cell, sizeof cell, " %.3f", double(max_component(by_angle[angles[i]])));
      row += cell;
    }
    report += row + "\n  RGB:";
    for (int theta : {0, 60, 85, 89}) {
      if (!by_angle.count(theta)) continue;
      vec3 a = by_angle[theta];
      char cell[80];
      std::snprintf(cell, sizeof cell, "  %d deg %.2f %.2f %.2f", theta, double(a.x), double(a.y), double(a.z));
      report += cell;
    }
    report += "\n";
  }
  for (const auto& [name, bound] : documented_excess()) {
    bool known = false;
    for (const Example& example : weidlich_wilkie_copies()) known = known || example.name == name;
    const std::string& material = name;  // clang 14 cannot capture a structured binding
    CHECK_MESSAGE(known, material << " in documented_excess() is not an example or test material of the "
                                     "Weidlich-Wilkie model");
  }
  MESSAGE(report);
}

TEST_CASE("Evaluator::albedo agrees with an adaptive quadrature of f cos") {
  // Independent of the evaluator's sampling: the adaptive quadrature of the chi-square test on
  // 20 x 40 cells of the hemisphere, per channel, refined around the mirror direction. With its
  // default 1024 points per lobe Evaluator::albedo is within 0.3% (schlick_gold and gold_paint at
  // 60 deg). On the lobes' samplers alone, without its cosine-weighted points, it was 1.2% low for
  // blue_metallic at 85 deg and up to 28% low for the energy-conserving model over a smooth metal.
  const std::vector<double> angles =
      test::kSanitized ? std::vector<double>{85.0} : std::vector<double>{0.0, 60.0, 85.0};
  std::vector<std::vector<double>> differences(examples().size());
  test::parallel_for(examples().size(), [&](size_t index) {
    const Example& example = examples()[index];
    // One point, its stack resolved once (a textured example's would be per evaluation).
    const cpu::ShadingPoint point = example.evaluator.bind(at_uv(probe_uvs(example).front()));
    for (double theta : angles) {
      vec3 wo = glm::normalize(test::to_float(test::spherical(test::radians(theta), 0.0)));
      vec3 fast = point.albedo(wo);
      double difference = 0.0;
      for (int c = 0; c < 3; ++c) {
        auto density = [&](const dvec3& w) -> double {
          if (w.z <= 0.0) return 0.0;
          return double(point.eval(test::to_float(w), wo)[c]) * w.z;
        };
        test::SphericalQuadrature q(density, test::Frame(), {test::mirror(test::to_double(wo))}, 1.0e5);
        double albedo = 0.0;
        for (int i = 0; i < 20; ++i)
          for (int j = 0; j < 40; ++j)
            albedo += q.integrate(0.5 * test::kPi * i / 20, 0.5 * test::kPi * (i + 1) / 20, 2.0 * test::kPi * j / 40,
                                  2.0 * test::kPi * (j + 1) / 40);
        difference = std::max(difference, std::abs(double(fast[c]) - albedo) / std::max(albedo, 1.0e-3));
      }
      differences[index].push_back(difference);
    }
  });
  std::string report = "albedo, Evaluator::albedo vs quadrature of f cos, largest relative difference over RGB:\n";
  for (size_t index = 0; index < examples().size(); ++index) {
    CAPTURE(examples()[index].name);
    report += "  " + examples()[index].name + ":";
    for (size_t a = 0; a < angles.size(); ++a) {
      CAPTURE(angles[a]);
      CHECK(differences[index][a] <= 0.006);
      char text[60];
      std::snprintf(text, sizeof text, " %.0f deg %.2g", angles[a], differences[index][a]);
      report += text;
    }
    report += "\n";
  }
  MESSAGE(report);
}

// --- 4 and 5: sampling -------------------------------------------------------------------------

namespace {

constexpr int kThetaBins = 40;  // uniform in theta over [0, pi/2]
constexpr int kPhiBins = 80;    // uniform in phi over [0, 2 pi)
constexpr int kZoomRadial = 16;
constexpr int kZoomAzimuthal = 32;

struct SamplingCase {
  const Example* example;
  double theta_deg, phi_deg;
  vec2 uv;
  long samples;
};

struct SamplingResult {
  test::ChiSquareResult global;
  bool zoomed = false;
  double zoom_radius_deg = 0.0;
  test::ChiSquareResult zoom;
  double integral_grid = 0.0;         // adaptive quadrature over the chi-square bins
  double integral_halfvector = -1.0;  // adaptive quadrature over half vectors (negative: not run)
  long samples = 0, failed = 0;
  // A stack with a tilted entry loses the draws that leave below the surface or meet total internal
  // reflection in a tilted frame; its pdf integrates to what remains. Others lose none.
  bool tilted = false;
  long evaluations = 0;
  double seconds = 0.0;
};

bool is_microfacet_lobe(const std::string& name) {
  return name.rfind("interface", 0) == 0 || name.find("conductor") != std::string::npos;
}

// The uvs at which an example is sampled: for a textured one, from a 32 x 32 grid, the uv where the
// smallest lobe weight is largest (both sides of a mix drawn), then the uv whose lobe weights differ
// most from those (the other checker colour; bare copper or full patina).
std::vector<vec2> sampling_uvs(const Example& example) {
  if (!example.textured) return {vec2(0.5f)};
  std::vector<std::pair<vec2, std::vector<float>>> grid;
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) {
      vec2 uv((float(i) + 0.5f) / 32.0f, (float(j) + 0.5f) / 32.0f);
      grid.push_back({uv, example.evaluator.lobe_weights(at_uv(uv), vec3(0.0f, 0.0f, 1.0f))});
    }
  auto smallest = [](const auto& entry) { return *std::min_element(entry.second.begin(), entry.second.end()); };
  auto first = std::max_element(grid.begin(), grid.end(),
                                [&](const auto& a, const auto& b) { return smallest(a) < smallest(b); });
  auto distance = [&](const auto& entry) {
    float sum = 0.0f;
    for (size_t k = 0; k < entry.second.size(); ++k) sum += std::abs(entry.second[k] - first->second[k]);
    return sum;
  };
  auto second = std::max_element(grid.begin(), grid.end(),
                                 [&](const auto& a, const auto& b) { return distance(a) < distance(b); });
  return {first->first, second->first};
}

// The hemisphere integral of pdf in the coordinates of the microfacet lobes: substituting
// wi = reflect(wo, h), d omega_i = 4 (wo.h) d omega_h (Walter et al. 2007, eq. 14), over h above
// the horizon with wo.h > 0 and wi above the horizon (which covers the upper hemisphere of wi once),
// by the adaptive quadrature on cells of h (20 rows in theta_h). Seeds: the normal (the mirror direction, where
// every microfacet lobe peaks) and the half vector of the zenith (where directions that cannot
// leave the stack are spread around).
double halfvector_integral(const cpu::ShadingPoint& point, vec3 wo_f, double sample_count, long& evaluations) {
  const dvec3 wo = test::to_double(wo_f);
  auto density = [&](const dvec3& h) -> double {
    double wo_h = glm::dot(wo, h);
    if (wo_h <= 0.0) return 0.0;
    dvec3 wi = 2.0 * wo_h * h - wo;
    if (wi.z <= 0.0) return 0.0;
    return double(point.pdf(test::to_float(wi), wo_f)) * 4.0 * wo_h;
  };
  test::SphericalQuadrature q(density, test::Frame(), {dvec3(0.0, 0.0, 1.0), glm::normalize(wo + dvec3(0.0, 0.0, 1.0))},
                              sample_count);
  double sum = 0.0;
  const int rows = 20;
  for (int i = 0; i < rows; ++i) {
    // Fewer cells around the pole, where the lobes peak: each cell there refines on its own.
    const int columns = std::min(4 * (i + 1), 40);
    for (int j = 0; j < columns; ++j)
      sum += q.integrate(0.5 * test::kPi * i / rows, 0.5 * test::kPi * (i + 1) / rows, 2.0 * test::kPi * j / columns,
                         2.0 * test::kPi * (j + 1) / columns);
  }
  evaluations += q.evaluations();
  return sum;
}

SamplingResult run_sampling_case(const SamplingCase& c, uint64_t seed) {
  auto start = std::chrono::steady_clock::now();
  // Every draw at one point: its stack resolved once (a textured example's would be per query).
  const cpu::ShadingPoint point = c.example->evaluator.bind(at_uv(c.uv));
  const vec3 wo_f =
      glm::normalize(test::to_float(test::spherical(test::radians(c.theta_deg), test::radians(c.phi_deg))));
  const dvec3 wo = test::to_double(wo_f);
  const dvec3 peak = test::mirror(wo);
  const long n = c.samples;
  const double n_d = double(n);
  SamplingResult r;
  r.samples = n;
  r.tilted = cpu::tilted_entry(point) >= 0;

  // Draw.
  std::mt19937_64 rng(seed);
  std::vector<dvec3> directions;
  std::vector<int> lobes;
  directions.reserve(size_t(n));
  lobes.reserve(size_t(n));
  for (long i = 0; i < n; ++i) {
    vec2 u(to_unit_float(test::uniform(rng)), to_unit_float(test::uniform(rng)));
    cpu::Sample s = point.sample(wo_f, u, to_unit_float(test::uniform(rng)));
    if (!(s.pdf > 0.0f)) {
      ++r.failed;
      continue;
    }
    directions.push_back(glm::normalize(test::to_double(s.wi)));
    lobes.push_back(s.lobe);
  }

  // Global grid: observed counts and expected counts by adaptive quadrature of pdf.
  auto density = [&](const dvec3& w) -> double {
    if (w.z <= 0.0) return 0.0;
    return double(point.pdf(test::to_float(w), wo_f));
  };
  const test::Frame up;
  std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(kThetaBins * kPhiBins, 0.0);
  const double dtheta = 0.5 * test::kPi / kThetaBins, dphi = 2.0 * test::kPi / kPhiBins;
  for (const dvec3& w : directions) {
    auto [theta, phi] = up.angles(w);
    int i = std::min(int(theta / dtheta), kThetaBins - 1), j = std::min(int(phi / dphi), kPhiBins - 1);
    observed[size_t(i * kPhiBins + j)] += 1.0;
  }
  test::SphericalQuadrature grid(density, up, {peak}, n_d);
  for (int i = 0; i < kThetaBins; ++i)
    for (int j = 0; j < kPhiBins; ++j) {
      double p = grid.integrate(dtheta * i, dtheta * (i + 1), dphi * j, dphi * (j + 1));
      expected[size_t(i * kPhiBins + j)] = n_d * p;
      r.integral_grid += p;
    }
  r.evaluations += grid.evaluations();
  // The quadrature refines where the pdf varies as its first points see it; a tilted lobe's pdf
  // ends sharply at its frame's horizon, and a sliver of it inside a bin can escape all of them. A
  // bin that holds draws but almost no expected count is integrated again, refined around the
  // draws it holds (where the pdf really is 0, that still finds 0).
  std::vector<std::vector<dvec3>> held(expected.size());
  for (const dvec3& w : directions) {
    auto [theta, phi] = up.angles(w);
    size_t b =
        size_t(std::min(int(theta / dtheta), kThetaBins - 1) * kPhiBins + std::min(int(phi / dphi), kPhiBins - 1));
    if (expected[b] < 1.0 && held[b].size() < 16) held[b].push_back(w);
  }
  for (size_t b = 0; b < expected.size(); ++b) {
    if (held[b].empty()) continue;
    test::SphericalQuadrature again(density, up, held[b], n_d);
    const int i = int(b) / kPhiBins, j = int(b) % kPhiBins;
    const double p = again.integrate(dtheta * i, dtheta * (i + 1), dphi * j, dphi * (j + 1));
    r.integral_grid += p - expected[b] / n_d;
    expected[b] = n_d * p;
    r.evaluations += again.evaluations();
  }
  auto global_name = [&](size_t index) {
    int i = int(index) / kPhiBins, j = int(index) % kPhiBins;
    char name[120];
    std::snprintf(name, sizeof name, "theta [%.2f, %.2f) phi [%.1f, %.1f) deg", test::degrees(dtheta * i),
                  test::degrees(dtheta * (i + 1)), test::degrees(dphi * j), test::degrees(dphi * (j + 1)));
    return std::string(name);
  };
  r.global = test::chi_square(observed, expected, n_d, global_name);

  // Narrow lobes fit in a few global bins (2.25 deg in theta), which then test little more than
  // their total weight. Zoom in: a polar grid around the mirror direction, of three times the
  // radius holding 90% of the narrowest microfacet lobe's samples (lobes of at least 1% of the
  // samples), when that radius is under 5 degrees, plus one bin for everything outside it.
  std::map<int, std::vector<double>> lobe_angles;
  for (size_t i = 0; i < directions.size(); ++i)
    if (is_microfacet_lobe(c.example->evaluator.lobe_name(size_t(lobes[i]))))
      lobe_angles[lobes[i]].push_back(test::angle_between(directions[i], peak));
  double narrowest = 1.0e30;
  for (auto& [lobe, angles] : lobe_angles) {
    if (double(angles.size()) < 0.01 * n_d) continue;
    auto q90 = angles.begin() + long(0.9 * double(angles.size()));
    std::nth_element(angles.begin(), q90, angles.end());
    narrowest = std::min(narrowest, *q90);
  }
  if (narrowest < test::radians(5.0)) {
    r.zoomed = true;
    const double radius = 3.0 * narrowest;
    r.zoom_radius_deg = test::degrees(radius);
    const test::Frame around(peak);
    // Ring i holds min(4 (i + 1), kZoomAzimuthal) azimuthal bins, so inner bins are not tiny.
    const double dalpha = radius / kZoomRadial;
    std::vector<int> ring_start(kZoomRadial + 1, 0);
    auto azimuths = [](int ring) { return std::min(4 * (ring + 1), kZoomAzimuthal); };
    for (int i = 0; i < kZoomRadial; ++i) ring_start[size_t(i + 1)] = ring_start[size_t(i)] + azimuths(i);
    const size_t outside = size_t(ring_start[kZoomRadial]);
    std::vector<double> zo(outside + 1, 0.0), ze(outside + 1, 0.0);
    for (const dvec3& w : directions) {
      auto [alpha, beta] = around.angles(w);
      if (alpha >= radius) {
        zo[outside] += 1.0;
        continue;
      }
      int i = std::min(int(alpha / dalpha), kZoomRadial - 1);
      int j = std::min(int(beta / (2.0 * test::kPi) * azimuths(i)), azimuths(i) - 1);
      zo[size_t(ring_start[size_t(i)] + j)] += 1.0;
    }
    test::SphericalQuadrature cap(density, around, {peak}, n_d);
    double inside = 0.0;
    for (int i = 0; i < kZoomRadial; ++i)
      for (int j = 0; j < azimuths(i); ++j) {
        double dbeta = 2.0 * test::kPi / azimuths(i);
        double p = cap.integrate(dalpha * i, dalpha * (i + 1), dbeta * j, dbeta * (j + 1));
        ze[size_t(ring_start[size_t(i)] + j)] = n_d * p;
        inside += p;
      }
    ze[outside] = n_d * std::max(r.integral_grid - inside, 0.0);
    r.evaluations += cap.evaluations();
    auto zoom_name = [&](size_t index) {
      if (index == outside) return std::string("outside the zoom");
      int i = 0;
      while (size_t(ring_start[size_t(i + 1)]) <= index) ++i;
      int j = int(index) - ring_start[size_t(i)];
      double dbeta = 360.0 / azimuths(i);
      char name[120];
      std::snprintf(name, sizeof name, "from mirror [%.4f, %.4f) deg, azimuth [%.1f, %.1f) deg",
                    test::degrees(dalpha * i), test::degrees(dalpha * (i + 1)), dbeta * j, dbeta * (j + 1));
      return std::string(name);
    };
    r.zoom = test::chi_square(zo, ze, n_d, zoom_name);
  }

  // pdf is isotropic: the second integral only at phi = 0 (and not under the sanitisers).
  if (c.phi_deg == 0.0 && !test::kSanitized)
    r.integral_halfvector = halfvector_integral(point, wo_f, n_d, r.evaluations);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

struct SamplingRun {
  std::vector<SamplingCase> cases;
  std::vector<SamplingResult> results;
  double seconds = 0.0;
};

// Shared by the chi-square and the normalisation tests, computed once.
const SamplingRun& sampling_run() {
  static const SamplingRun run = [] {
    SamplingRun r;
    const long n = 500000;
    for (const Example& example : examples()) {
      std::vector<vec2> uvs = sampling_uvs(example);
      // 5 10^5 samples at phi = 0 at 0, 45 and 85 degrees (10^6, and 30 and 60 degrees too, until
      // the suite outgrew CI's half hour: the draws are most of this test's cost, 250 s of one core
      // at 10^6); the model is isotropic, so a second azimuth only checks that
      // sampling handles one, with fewer samples to keep the run short. A textured example's
      // second uv at two angles. A draw costs in proportion to the stack's entries: a stack of more
      // than 16 draws 16 / entries of the samples (Lavender Lepidolite's 53: 1.5 10^5 a case).
      const size_t entries = example.evaluator.program().stack.size();
      const long m = entries > 16 ? long(double(n) * 16.0 / double(entries)) : n;
      for (double theta : {0.0, 45.0, 85.0}) r.cases.push_back({&example, theta, 0.0, uvs[0], m});
      r.cases.push_back({&example, 60.0, 131.0, uvs[0], m / 4});
      for (size_t k = 1; k < uvs.size(); ++k)
        for (double theta : {30.0, 85.0}) r.cases.push_back({&example, theta, 0.0, uvs[k], m});
    }
    r.results.resize(r.cases.size());
    auto start = std::chrono::steady_clock::now();
    test::parallel_for(r.cases.size(), [&](size_t i) { r.results[i] = run_sampling_case(r.cases[i], 0x5eed1000 + i); });
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }();
  return run;
}

std::string case_name(const SamplingCase& c) {
  char name[200];
  std::snprintf(name, sizeof name, "%s, wo theta %.0f phi %.0f deg, uv (%.4f, %.4f)", c.example->name.c_str(),
                c.theta_deg, c.phi_deg, double(c.uv.x), double(c.uv.y));
  return name;
}

}  // namespace

// One test case, so that a ctest run (one process per test case) draws the samples once.
TEST_CASE("every example samples its pdf, and its pdf integrates to 1") {
  // The sanitised build looks for memory errors, not for statistics: sample() and pdf() run under it
  // in "sample() returns eval() and pdf()" for every example, while this run's quadratures of the
  // expected counts took 4 minutes there even at one case per material (tilted facets refine them
  // most). The optimised build runs it in full.
  if (test::kSanitized) return;
  SUBCASE("sample() follows pdf() (chi-square goodness of fit)") {
    const SamplingRun& run = sampling_run();
    int tests = 0;
    for (const SamplingResult& r : run.results) tests += 1 + (r.zoomed ? 1 : 0);
    const double significance = test::sidak(0.01, tests);
    std::map<std::string, std::string> worst;  // per example: the smallest p-value and where
    std::map<std::string, double> worst_p;
    for (size_t i = 0; i < run.cases.size(); ++i) {
      const SamplingCase& c = run.cases[i];
      const SamplingResult& r = run.results[i];
      std::string name = case_name(c);
      CAPTURE(name);
      // A sampler draws a direction for (almost) every u; a tilted stack loses the share its pdf
      // does not cover (within the quadrature's 1%), all of it where wo is below every tilted lobe.
      const double lost = double(r.failed) / double(r.samples);
      if (!r.tilted) CHECK(lost <= 1.0e-4);
      if (r.tilted) CHECK(std::abs(lost - (1.0 - r.integral_grid)) <= 0.01);
      if (r.failed == r.samples) continue;  // nothing drawn and nothing expected: no distribution to test
      CHECK_MESSAGE(r.global.p_value >= significance, "global grid chi2 " << r.global.statistic << " dof "
                                                                          << r.global.dof << " p " << r.global.p_value
                                                                          << "\nworst bins:\n"
                                                                          << r.global.worst_bins);
      if (r.zoomed)
        CHECK_MESSAGE(r.zoom.p_value >= significance, "zoom (radius " << r.zoom_radius_deg << " deg) chi2 "
                                                                      << r.zoom.statistic << " dof " << r.zoom.dof
                                                                      << " p " << r.zoom.p_value << "\nworst bins:\n"
                                                                      << r.zoom.worst_bins);
      const std::string& ex = c.example->name;
      for (auto [p, label] : {std::pair{r.global.p_value, "grid"}, std::pair{r.zoom.p_value, "zoom"}}) {
        if (std::string(label) == "zoom" && !r.zoomed) continue;
        if (!worst_p.count(ex) || p < worst_p[ex]) {
          worst_p[ex] = p;
          char text[200];
          std::snprintf(text, sizeof text, "%.3g (%s, theta %.0f phi %.0f)", p, label, c.theta_deg, c.phi_deg);
          worst[ex] = text;
        }
      }
    }
    std::string summary = "chi-square: " + std::to_string(tests) + " tests, Sidak per-test significance " +
                          std::to_string(significance) + ", sampling run " + std::to_string(run.seconds) +
                          " s; per example the smallest p-value:\n";
    for (const auto& [ex, text] : worst) summary += "  " + ex + ": " + text + "\n";
    summary += "zoomed cases (radius deg):";
    for (size_t i = 0; i < run.cases.size(); ++i)
      if (run.results[i].zoomed) {
        char text[120];
        std::snprintf(text, sizeof text, " %s/%.0f/%.0f:%.3g", run.cases[i].example->name.c_str(),
                      run.cases[i].theta_deg, run.cases[i].phi_deg, run.results[i].zoom_radius_deg);
        summary += text;
      }
    MESSAGE(summary);
  }
  SUBCASE("pdf() integrates to 1 over the hemisphere, less the draws a tilted stack loses") {
    // Two quadratures: the adaptive one of the chi-square bins (theta x phi of wi, refined where pdf
    // varies and around the mirror direction), and the same adaptive quadrature over half vectors
    // (halfvector_integral), at phi = 0.
    const SamplingRun& run = sampling_run();
    std::map<std::string, std::pair<double, double>> range_grid, range_half;
    for (size_t i = 0; i < run.cases.size(); ++i) {
      const SamplingCase& c = run.cases[i];
      const SamplingResult& r = run.results[i];
      std::string name = case_name(c);
      CAPTURE(name);
      // A tilted stack's pdf covers what its draws do not lose (checked with the chi-square).
      const double whole = r.tilted ? 1.0 - double(r.failed) / double(r.samples) : 1.0;
      CHECK(std::abs(r.integral_grid - whole) <= 0.01);
      if (r.integral_halfvector >= 0.0) CHECK(std::abs(r.integral_halfvector - whole) <= 0.01);
      auto widen = [](std::map<std::string, std::pair<double, double>>& m, const std::string& k, double v) {
        auto it = m.find(k);
        if (it == m.end()) {
          m[k] = {v, v};
        } else {
          it->second.first = std::min(it->second.first, v);
          it->second.second = std::max(it->second.second, v);
        }
      };
      widen(range_grid, c.example->name, r.integral_grid);
      if (r.integral_halfvector >= 0.0) widen(range_half, c.example->name, r.integral_halfvector);
    }
    std::string summary =
        "integral of pdf over the hemisphere, min..max over wo: grid quadrature | half-vector quadrature\n";
    for (const auto& [ex, g] : range_grid) {
      char line[200];
      std::snprintf(line, sizeof line, "  %-22s %.5f..%.5f | %.5f..%.5f\n", ex.c_str(), g.first, g.second,
                    range_half[ex].first, range_half[ex].second);
      summary += line;
    }
    MESSAGE(summary);
  }
}

// --- 7: sample() agrees with eval() and pdf() ----------------------------------------------------

TEST_CASE("sample() returns eval() and pdf() of the direction it drew") {
  const int count = 10000 / test::kSanitizerDivisor;
  for (const Example& example : examples()) {
    CAPTURE(example.name);
    std::mt19937_64 rng(0x5eed0007);
    long failed = 0, f_differs = 0, pdf_differs = 0, bad_direction = 0;
    std::string first;
    for (int i = 0; i < count; ++i) {
      vec3 wo = test::to_float(upper_direction(rng, nullptr, 0.0, 0.0, 0.0));
      ShadingContext ctx = at_uv(random_uv(rng));
      vec2 u(to_unit_float(test::uniform(rng)), to_unit_float(test::uniform(rng)));
      cpu::Sample s = example.evaluator.sample(ctx, wo, u, to_unit_float(test::uniform(rng)));
      if (!(s.pdf > 0.0f)) {
        // A tilted stack loses draws by design (the chi-square test checks that its pdf says so).
        if (cpu::tilted_entry(example.evaluator.bind(ctx)) < 0) ++failed;
        continue;
      }
      if (!(s.wi.z > 0.0f) || std::abs(glm::length(s.wi) - 1.0f) > 1.0e-6f || s.lobe < 0 ||
          size_t(s.lobe) >= example.evaluator.lobe_count())
        ++bad_direction;
      vec3 f = example.evaluator.eval(ctx, s.wi, wo);
      float pdf = example.evaluator.pdf(ctx, s.wi, wo);
      if (glm::any(glm::greaterThan(glm::abs(f - s.f), 1.0e-7f * glm::abs(f)))) {
        if (f_differs++ == 0) first = "f " + describe(s.f) + " vs eval " + describe(f);
      }
      if (std::abs(pdf - s.pdf) > 1.0e-7f * pdf) {
        if (pdf_differs++ == 0) first += " pdf " + std::to_string(s.pdf) + " vs " + std::to_string(pdf);
      }
    }
    CHECK_MESSAGE(f_differs == 0, first);
    CHECK_MESSAGE(pdf_differs == 0, first);
    CHECK(bad_direction == 0);
    CHECK(double(failed) <= 1.0e-3 * double(count));
  }
}

TEST_CASE("sampling alone estimates the albedo: the mean of f cos / pdf over sample() is Evaluator::albedo") {
  // A path tracer sees only what sample() draws: a part of f where pdf is 0 is light it never finds
  // (the energy-conserving model's forward part over a smooth metal, before its conductor lobes drew
  // a cosine share for it: christmas_orb read 0.68 in red at 80 degrees for 0.86). Stratified
  // samples, the standard error from their spread; Evaluator::albedo mixes in a cosine sampler of
  // its own and agrees with an adaptive quadrature (above).
  const int count = 16384 / test::kSanitizerDivisor;
  std::string summary = "sampled albedo against Evaluator::albedo, worst |difference| / (4 stderr + 0.005):\n";
  for (const Example* each : examples_in_both_models()) {
    const Example& example = *each;
    CAPTURE(label(example));
    double worst = 0.0;
    std::string worst_where;
    for (double theta : {0.0, 40.0, 70.0, 85.0}) {
      const vec3 wo = test::to_float(test::spherical(test::radians(theta), 0.0));
      const cpu::ShadingPoint point = example.evaluator.bind(at_uv(vec2(0.5f)));
      std::mt19937_64 rng(0x5eed0009);
      dvec3 sum(0.0), sum2(0.0);
      const int side = int(std::sqrt(double(count)));
      for (int a = 0; a < side; ++a)
        for (int b = 0; b < side; ++b) {
          vec2 u(to_unit_float((a + test::uniform(rng)) / side), to_unit_float((b + test::uniform(rng)) / side));
          cpu::Sample smp = point.sample(wo, u, to_unit_float(test::uniform(rng)));
          dvec3 weight = smp.pdf > 0.0f ? test::to_double(smp.f) * double(smp.wi.z) / double(smp.pdf) : dvec3(0.0);
          sum += weight;
          sum2 += weight * weight;
        }
      const double n = double(side) * side;
      const vec3 albedo = point.albedo(wo);
      for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n;
        const double stderr_c = std::sqrt(std::max(sum2[c] / n - mean * mean, 0.0) / n);
        const double ratio = std::abs(mean - double(albedo[c])) / (4.0 * stderr_c + 0.005);
        if (ratio > worst) {
          worst = ratio;
          char where[200];
          std::snprintf(where, sizeof where, "%g deg, channel %c: sampled %.4f +- %.4f, albedo %.4f", theta, "RGB"[c],
                        mean, stderr_c, double(albedo[c]));
          worst_where = where;
        }
      }
    }
    CHECK_MESSAGE(worst <= 1.0, worst_where);
    char line[300];
    std::snprintf(line, sizeof line, "  %-40s %.3f  %s\n", label(example).c_str(), worst, worst_where.c_str());
    summary += line;
  }
  MESSAGE(summary);
}

// --- 8: an independent transcription of Elek's Algorithm 1 ---------------------------------------

namespace {

// The stack of an example, read from its JSON file directly (not through the library).
struct Facet {
  std::string distribution = "beckmann";  // beckmann, blinn, ggx
  std::string fresnel = "exact";          // exact, schlick, lazanyi
  double m = 0.0;                         // RMS slope: tan(roughness_deg), or alpha
};
struct Coat {
  double ior = 1.0;  // absolute index below the interface
  Facet facet;
  dvec3 sigma{0.0};  // absorption per unit length
  double d = 0.0;    // thickness
};
struct Base {
  std::string kind;  // lambert, oren_nayar, conductor
  dvec3 albedo{0.0};
  double sigma = 0.0;
  dvec3 n{1.0}, k{0.0};
  Facet facet;
};
struct Stack {
  std::vector<Coat> coats;  // top first
  Base base;
  bool clamp = true;  // Elek sec. 3: a lower slope is raised to the one above it
};

// A parameter as the evaluator receives it: rounded to float. (An absorption exponent of 100
// turns the rounding of sigma and d alone into 1e-5 of the result.)
double read_number(const nlohmann::json& j) { return double(j.get<float>()); }

dvec3 read_color(const nlohmann::json& j) { return {read_number(j.at(0)), read_number(j.at(1)), read_number(j.at(2))}; }

// The smooth limit: slopes below 1e-4 are raised to it (README, "The layered model").
constexpr double kMinSlope = 1.0e-4;

Facet read_facet(const nlohmann::json& node) {
  Facet f;
  if (node.contains("distribution")) f.distribution = node.at("distribution").get<std::string>();
  if (node.contains("fresnel")) f.fresnel = node.at("fresnel").get<std::string>();
  if (node.contains("alpha"))
    f.m = read_number(node.at("alpha"));
  else if (node.contains("roughness_deg"))
    f.m = std::tan(test::radians(read_number(node.at("roughness_deg"))));
  return f;
}

// A stack without mixes and textures; nothing for other materials.
std::optional<Stack> read_stack(const std::string& text) {
  nlohmann::json doc = nlohmann::json::parse(text);
  const nlohmann::json& material = doc.at("materials").at(0);
  std::map<std::string, nlohmann::json> nodes;
  for (const auto& node : material.at("nodes")) nodes[node.at("id").get<std::string>()] = node;
  auto deref = [&](const nlohmann::json& link) -> const nlohmann::json& {
    std::string s = link.get<std::string>();
    REQUIRE(s.size() > 1);
    REQUIRE(s[0] == '@');
    REQUIRE(s.find('.') == std::string::npos);
    return nodes.at(s.substr(1));
  };
  for (const auto& [id, node] : nodes) {
    std::string type = node.at("type").get<std::string>();
    if (type == "mix" || type.rfind("texture/", 0) == 0 || type.rfind("math/", 0) == 0) return std::nullopt;
    // Elek's algorithm has no fluorescent base: its light through a stack is checked against
    // Beer-Lambert's law and the reference solver (tests/nodes/substrate_fluorescent_test.cpp).
    if (type == "substrate/fluorescent") return std::nullopt;
    // Nor flakes: a flake paint is checked against the fast model's equations and the full model
    // (tests/nodes/substrate_flake_paint_test.cpp).
    if (type == "substrate/flake_paint") return std::nullopt;
  }
  Stack stack;
  if (material.contains("clamp_lower_roughness")) stack.clamp = material.at("clamp_lower_roughness").get<bool>();
  const nlohmann::json* node = &deref(material.at("surface"));
  while (node->at("type") == "layer") {
    const nlohmann::json& interface = deref(node->at("interface"));
    REQUIRE(interface.at("type") == "interface/dielectric");
    Coat coat;
    coat.ior = read_number(interface.at("ior"));
    coat.facet = read_facet(interface);
    if (node->contains("medium")) {
      const nlohmann::json& medium = deref(node->at("medium"));
      if (medium.at("type") == "medium/absorbing") {
        coat.d = read_number(medium.at("thickness"));
        coat.sigma = read_color(medium.at("absorption"));
      } else {
        REQUIRE(medium.at("type") == "medium/clear");
      }
    }
    stack.coats.push_back(coat);
    node = &deref(node->at("base"));
  }
  const std::string type = node->at("type").get<std::string>();
  if (type == "substrate/lambert") {
    stack.base.kind = "lambert";
    stack.base.albedo = read_color(node->at("albedo"));
  } else if (type == "substrate/oren_nayar") {
    stack.base.kind = "oren_nayar";
    stack.base.albedo = read_color(node->at("albedo"));
    stack.base.sigma = read_number(node->at("sigma"));
  } else {
    REQUIRE(type == "substrate/conductor");
    stack.base.kind = "conductor";
    stack.base.facet = read_facet(*node);
    if (node->contains("metal")) {
      // The course's metal constants (SEEDS.md sec. 1, from the 'Type d) - Metal Foil' slide), and
      // copper at 645, 525 and 445 nm from Hagemann, Gudat and Kunz 1974 (as nodes/metals.cpp).
      const std::map<std::string, std::pair<dvec3, dvec3>> metals = {
          {"gold", {{0.1, 0.42, 1.56}, {3.8, 2.5, 1.9}}},
          {"silver", {{0.14, 0.13, 0.157}, {4.44, 3.25, 2.40}}},
          {"aluminium", {{1.94, 1.0, 0.6}, {8.21, 6.69, 4.86}}},
          {"copper", {{0.214, 1.037, 1.169}, {3.67, 2.59, 2.36}}}};
      auto it = metals.find(node->at("metal").get<std::string>());
      REQUIRE(it != metals.end());
      stack.base.n = it->second.first;
      stack.base.k = it->second.second;
    } else {
      stack.base.n = read_color(node->at("n"));
      stack.base.k = read_color(node->at("k"));
    }
  }
  return stack;
}

double fifth(double x) { return x * x * x * x * x; }

// A dielectric boundary of relative index eta under the node's `fresnel`: exact; Schlick 1994
// (eq. 24) with F0 = ((eta-1)/(eta+1))^2; Lazanyi and Szirmay-Kalos as Elek App. B codes it,
// ((n-1)^2 + 4 n (1-cos)^5 + k^2) / ((n+1)^2 + k^2) with k = 0. The approximations take the cosine
// on the rarer side: from the denser side (eta < 1) the refracted one, and total internal
// reflection gives 1 (de Greve 2006); no boundary (eta = 1) reflects nothing.
double fresnel_dielectric(double cos_i, double eta, const std::string& mode) {
  if (mode == "exact") return test::fresnel_reference(cos_i, eta);
  if (eta == 1.0) return 0.0;
  double c = cos_i;
  if (eta < 1.0) {
    double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return 1.0;
    c = std::sqrt(1.0 - sin2_t);
  }
  if (mode == "schlick") {
    double f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
    return f0 + (1.0 - f0) * fifth(1.0 - c);
  }
  REQUIRE(mode == "lazanyi");
  return ((eta - 1.0) * (eta - 1.0) + 4.0 * eta * fifth(1.0 - c)) / ((eta + 1.0) * (eta + 1.0));
}

// A conductor of relative index n + ik: exact; Schlick from the exact reflectance at normal
// incidence; Lazanyi and Szirmay-Kalos as Elek App. B codes it.
double fresnel_conductor(double cos_i, double n, double k, const std::string& mode) {
  if (mode == "exact") return test::fresnel_reference(cos_i, std::complex<double>(n, k));
  if (mode == "schlick") {
    double f0 = test::fresnel_reference(1.0, std::complex<double>(n, k));
    return f0 + (1.0 - f0) * fifth(1.0 - cos_i);
  }
  REQUIRE(mode == "lazanyi");
  return ((n - 1.0) * (n - 1.0) + 4.0 * n * fifth(1.0 - cos_i) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
}

// The normalised distributions, with tan^2 = sin^2 / cos^2 of the half vector:
// Beckmann exp(-tan^2/m^2) / (pi m^2 cos^4) (Walter et al. 2007, eq. 25); normalised Blinn
// (e + 2)/(2 pi) cos^e with e = 2/m^2 - 2 (course eq. 3.7); GGX a^2 / (pi cos^4 (a^2 + tan^2)^2)
// with a = m (Walter et al. 2007, eq. 33).
double distribution(const std::string& name, double cos_h, double tan2, double m) {
  double c4 = cos_h * cos_h * cos_h * cos_h;
  if (name == "beckmann") return std::exp(-tan2 / (m * m)) / (test::kPi * m * m * c4);
  if (name == "blinn") {
    double e = 2.0 / (m * m) - 2.0;
    return (e + 2.0) / (2.0 * test::kPi) * std::pow(cos_h, e);
  }
  REQUIRE(name == "ggx");
  return m * m / (test::kPi * c4 * (m * m + tan2) * (m * m + tan2));
}

// d ln D / d ln tan^2 of each distribution, for the float-noise estimate of NoisyValue.
double log_sensitivity(const std::string& name, double tan2, double m) {
  if (name == "beckmann") return tan2 / (m * m);
  if (name == "blinn") return 0.5 * (2.0 / (m * m) - 2.0) * tan2 / (1.0 + tan2);
  return 2.0 * tan2 / (m * m + tan2);
}

// The geometry term: the course's V-cavity min(1, 2 NH NV / VH, 2 NH NL / VH) for Beckmann and
// Blinn; for GGX Smith's G1(l) G1(v), G1 = 2 / (1 + sqrt(1 + a^2 tan^2)) (Walter et al. 2007, eq. 34).
double geometry(const std::string& name, const dvec3& l, const dvec3& v, const dvec3& h, double m) {
  double nh = h.z, vh = glm::dot(v, h);
  if (name != "ggx") return std::min(1.0, std::min(2.0 * nh * v.z / vh, 2.0 * nh * l.z / vh));
  auto g1 = [&](double c) { return 2.0 / (1.0 + std::sqrt(1.0 + m * m * (1.0 - c * c) / (c * c))); };
  return g1(l.z) * g1(v.z);
}

// The value plus an estimate of the error float evaluation cannot avoid: the evaluator computes
// tan^2 = (h.x^2 + h.y^2) / h.z^2 from the half vector's components (d_microfacet_h), so relative
// roundings e of those components change D by a factor of about (2 |d ln D / d ln tan^2| + 4) e
// (for Beckmann, (2 tan^2 / m^2 + 4) e); e = 2.4e-7 (four float ulps) covers computing the half
// vector in float. (From cos_h alone, 1 - cos^2 would cancel: 2e-3 for m = tan 1 deg near the peak.)
struct NoisyValue {
  dvec3 f{0.0};
  dvec3 float_noise{0.0};
};

// How the transcription forms the half vector: exactly, in double, from the float directions it is
// given (the default), or as the float evaluator does, normalize(l + v) in float arithmetic from
// the directions rounded to float (then made unit length in double). The second feeds D, G and F
// the direction the evaluator sees, so what remains is the error of evaluating them.
enum class HalfVector { Exact, FloatRounded };

dvec3 half_vector(const dvec3& l, const dvec3& v, HalfVector how) {
  if (how == HalfVector::Exact) return glm::normalize(l + v);
  return glm::normalize(test::to_double(glm::normalize(test::to_float(l) + test::to_float(v))));
}

// Torrance-Sparrow: F D G / (4 cos_l cos_v).
NoisyValue torrance_sparrow(const dvec3& l, const dvec3& v, const Facet& facet, double m, HalfVector how,
                            const std::function<dvec3(double)>& fresnel_at) {
  dvec3 h = half_vector(l, v, how);
  double nh = h.z, vh = glm::dot(v, h);
  if (nh <= 0.0 || vh <= 0.0) return {};
  double tan2 = (h.x * h.x + h.y * h.y) / (nh * nh);
  NoisyValue out;
  out.f = fresnel_at(vh) * distribution(facet.distribution, nh, tan2, m) * geometry(facet.distribution, l, v, h, m) /
          (4.0 * l.z * v.z);
  out.float_noise = out.f * ((2.0 * log_sensitivity(facet.distribution, tan2, m) + 4.0) * 2.4e-7);
  return out;
}

// The course's Oren-Nayar shader (COURSE_EXAMPLES.md sec. 5, after L. Gritz) for light L, eye V,
// normal z, turned into a BRDF: (L1 + L2) / cos_i / pi.
dvec3 oren_nayar(const dvec3& l, const dvec3& v, const dvec3& cs, double sigma) {
  double theta_r = std::acos(v.z);
  double sigma2 = sigma * sigma;
  double cos_theta_i = l.z;
  dvec3 eye_t(v.x, v.y, 0.0), l_t(l.x, l.y, 0.0);
  double cos_phi_diff =
      (glm::length(eye_t) > 0.0 && glm::length(l_t) > 0.0) ? glm::dot(glm::normalize(eye_t), glm::normalize(l_t)) : 0.0;
  double theta_i = std::acos(cos_theta_i);
  double alpha = std::max(theta_i, theta_r), beta = std::min(theta_i, theta_r);
  double c1 = 1.0 - 0.5 * sigma2 / (sigma2 + 0.33);
  double c2 = 0.45 * sigma2 / (sigma2 + 0.09);
  if (cos_phi_diff >= 0.0)
    c2 *= std::sin(alpha);
  else
    c2 *= std::sin(alpha) - std::pow(2.0 * beta / test::kPi, 3.0);
  double c3 = 0.125 * sigma2 / (sigma2 + 0.09) * std::pow(4.0 * alpha * beta / (test::kPi * test::kPi), 2.0);
  dvec3 l1 = cs * (cos_theta_i * (c1 + cos_phi_diff * c2 * std::tan(beta) +
                                  (1.0 - std::abs(cos_phi_diff)) * c3 * std::tan((alpha + beta) / 2.0)));
  dvec3 l2 = (cs * cs) * (0.17 * cos_theta_i * sigma2 / (sigma2 + 0.13) *
                          (1.0 - cos_phi_diff * (4.0 * beta * beta) / (test::kPi * test::kPi)));
  return (l1 + l2) / cos_theta_i / test::kPi;
}

// GLSL refract(I, N, eta) (GLSL spec, sec. 8.5).
dvec3 refract(const dvec3& i, const dvec3& n, double eta) {
  double k = 1.0 - eta * eta * (1.0 - glm::dot(n, i) * glm::dot(n, i));
  if (k < 0.0) return dvec3(0.0);
  return eta * i - (eta * glm::dot(n, i) + std::sqrt(k)) * n;
}

// The slope a lobe uses below an interface of (already clamped) slope m_above.
double effective_slope(const Stack& stack, double own, double m_above) {
  return std::max(stack.clamp ? std::max(own, m_above) : own, kMinSlope);
}

// Everything below coat `index` seen from the medium of index n_above, whose interface had the
// (already clamped) slope m_above.
NoisyValue layered(const Stack& stack, size_t index, const dvec3& l, const dvec3& v, double n_above, double m_above,
                   HalfVector how);

// Elek, Algorithm 1, for coat `index` over whatever lies below it:
//   f = f1 + T12 f2(L', V') a t, f1 = TorranceSparrow at V.H with eta = n1 / n_above,
//   L' = -refract(-L, N, 1/eta), T12 = T21 = 1 - F1, a = exp(-sigma d (1/N.L' + 1/N.V')),
//   t = (1 - G1) + T21 G1; the slope below is clamped to max(m2, m1).
NoisyValue elek_layer(const Stack& stack, size_t index, const dvec3& l, const dvec3& v, double n_above, double m_above,
                      HalfVector how) {
  const Coat& coat = stack.coats[index];
  const double eta = coat.ior / n_above;
  const double m1 = effective_slope(stack, coat.facet.m, m_above);
  const dvec3 n(0.0, 0.0, 1.0);
  auto fresnel_at = [&](double vh) { return fresnel_dielectric(vh, eta, coat.facet.fresnel); };
  NoisyValue top = torrance_sparrow(l, v, coat.facet, m1, how, [&](double vh) { return dvec3(fresnel_at(vh)); });
  dvec3 h = half_vector(l, v, how);
  double f1 = fresnel_at(glm::dot(v, h));
  double g1 = geometry(coat.facet.distribution, l, v, h, m1);
  dvec3 l_below = -refract(-l, n, 1.0 / eta), v_below = -refract(-v, n, 1.0 / eta);
  if (l_below.z <= 0.0 || v_below.z <= 0.0) return top;  // no light below (total internal reflection)
  double t12 = 1.0 - f1, t21 = t12;
  double t = (1.0 - g1) + t21 * g1;
  dvec3 a = glm::exp(-coat.sigma * coat.d * (1.0 / l_below.z + 1.0 / v_below.z));
  NoisyValue below = layered(stack, index + 1, l_below, v_below, coat.ior, m1, how);
  NoisyValue out;
  out.f = top.f + t12 * below.f * a * t;
  out.float_noise = top.float_noise + t12 * below.float_noise * a * t;
  return out;
}

NoisyValue layered(const Stack& stack, size_t index, const dvec3& l, const dvec3& v, double n_above, double m_above,
                   HalfVector how) {
  if (index < stack.coats.size()) return elek_layer(stack, index, l, v, n_above, m_above, how);
  const Base& base = stack.base;
  if (base.kind == "lambert") return {base.albedo / test::kPi, dvec3(0.0)};
  if (base.kind == "oren_nayar") return {oren_nayar(l, v, base.albedo, base.sigma), dvec3(0.0)};
  // Conductor: n + ik relative to the medium above it.
  double m2 = effective_slope(stack, base.facet.m, m_above);
  return torrance_sparrow(l, v, base.facet, m2, how, [&](double vh) {
    dvec3 f;
    for (int c = 0; c < 3; ++c)
      f[c] = fresnel_conductor(vh, base.n[c] / n_above, base.k[c] / n_above, base.facet.fresnel);
    return f;
  });
}

// Cosines at and above this are "steep": away from grazing, where V.H, the refraction and
// t = (1 - G) + T G are ill-conditioned.
constexpr float kSteep = 0.05f;

struct TranscriptionStats {
  long pairs = 0;
  double max_relative = 0.0;        // max |got - ref| / |ref| over channels float can evaluate to 1e-5
  double max_relative_all = 0.0;    // the same over all channels: the worst strict error
  double max_over_tolerance = 0.0;  // max |got - ref| / tolerance
  long limited = 0;                 // pairs where float conditioning allows more than 1e-5
  long strict = 0;                  // pairs within the strict 1e-5 (and its floors) in every channel
  long strict_float_h = 0;          // the same against the transcription at the float half vector
  double max_relative_float_h = 0.0;
  long steep = 0;  // pairs with both cosines >= kSteep
  long strict_steep = 0, strict_float_h_steep = 0;
  double max_relative_steep = 0.0, max_relative_float_h_steep = 0.0;
  std::string worst, worst_strict_float_h;
};

// One or two float ulps up or down per component, at random.
vec3 nudge(vec3 w, std::mt19937_64& rng) {
  for (int c = 0; c < 3; ++c) {
    uint64_t bits = rng();
    w[c] = std::nextafter(w[c], (bits & 1) ? 2.0f : -2.0f);
    if (bits & 2) w[c] = std::nextafter(w[c], (bits & 1) ? 2.0f : -2.0f);
  }
  return w;
}

// Compares the evaluator with the transcription over random pairs: 60% spread over the hemisphere
// (cosines down to 1e-4), 40% near the mirror direction (0.1 to 30 times the top slope, at most
// 0.5 rad) to exercise the lobes. The issue's bound is 1e-5 relative (floor 1e-7 of the pair's
// largest channel, and 1e-20): the strict counts. The test's tolerance adds what float evaluation
// cannot avoid: the distribution's sensitivity to the rounding of the half vector
// (NoisyValue::float_noise), and the spread of the transcription itself when its inputs move by one or
// two float ulps, doubled (near-grazing pairs around the mirror direction are ill-conditioned: V.H
// is a small difference there, and t = (1 - G) + T G cancels when G -> 1 and T -> 0; one ulp of
// input can change f tenfold).
TranscriptionStats compare_with_transcription(const Example& example, const Stack& stack, int pairs) {
  std::mt19937_64 rng(0x5eed0008);
  TranscriptionStats stats;
  stats.pairs = pairs;
  // The slope of the top lobe: the first coat's, or a bare substrate's own (0 for a diffuse one).
  const Facet& top = stack.coats.empty() ? stack.base.facet : stack.coats.front().facet;
  double m_top = std::max(top.m, 1.0e-3);
  for (int i = 0; i < pairs; ++i) {
    dvec3 wo_d = upper_direction(rng, nullptr, 0.0, 0.0, 0.0);
    dvec3 wi_d = upper_direction(rng, &wo_d, 0.4, 0.1 * m_top, std::min(30.0 * m_top, 0.5));
    vec3 wo = test::to_float(wo_d), wi = test::to_float(wi_d);
    // The transcription sees exactly the float directions the evaluator gets.
    const dvec3 l = test::to_double(wi), v = test::to_double(wo);
    NoisyValue ref = layered(stack, 0, l, v, 1.0, 0.0, HalfVector::Exact);
    NoisyValue ref_float_h = layered(stack, 0, l, v, 1.0, 0.0, HalfVector::FloatRounded);
    dvec3 spread(0.0);
    for (int k = 0; k < 8; ++k) {
      NoisyValue moved = layered(stack, 0, test::to_double(nudge(wi, rng)), test::to_double(nudge(wo, rng)), 1.0, 0.0,
                                 HalfVector::Exact);
      spread = glm::max(spread, glm::abs(moved.f - ref.f));
    }
    vec3 got = example.evaluator.eval(ShadingContext{}, wi, wo);
    double pair_max = std::max({ref.f.x, ref.f.y, ref.f.z});
    bool limited = false, strict = true, strict_float_h = true;
    double pair_relative = 0.0, pair_relative_float_h = 0.0;
    for (int c = 0; c < 3; ++c) {
      double error = std::abs(double(got[c]) - ref.f[c]);
      double floors = 1.0e-7 * pair_max + 1.0e-20;
      double conditioning = ref.float_noise[c] + 2.0 * spread[c];
      strict = strict && error <= 1.0e-5 * std::abs(ref.f[c]) + floors;
      double error_float_h = std::abs(double(got[c]) - ref_float_h.f[c]);
      strict_float_h = strict_float_h && error_float_h <= 1.0e-5 * std::abs(ref_float_h.f[c]) + floors;
      // Relative errors of values that matter (above the floors).
      if (std::abs(ref.f[c]) > std::max(1.0e-7 * pair_max, 1.0e-20)) {
        double relative = error / std::abs(ref.f[c]);
        stats.max_relative_all = std::max(stats.max_relative_all, relative);
        pair_relative = std::max(pair_relative, relative);
        pair_relative_float_h = std::max(pair_relative_float_h, error_float_h / std::abs(ref_float_h.f[c]));
        if (conditioning > 1.0e-5 * std::abs(ref.f[c]))
          limited = true;
        else
          stats.max_relative = std::max(stats.max_relative, relative);
        double relative_float_h = error_float_h / std::abs(ref_float_h.f[c]);
        if (relative_float_h > stats.max_relative_float_h) {
          stats.max_relative_float_h = relative_float_h;
          std::ostringstream s;
          s.precision(10);
          s << "wi " << describe(wi) << " wo " << describe(wo) << " channel " << c << ": evaluator " << got[c]
            << ", transcription at the float half vector " << ref_float_h.f[c];
          stats.worst_strict_float_h = s.str();
        }
      }
      double tolerance = 1.0e-5 * std::abs(ref.f[c]) + floors + conditioning;
      if (error / tolerance > stats.max_over_tolerance) {
        stats.max_over_tolerance = error / tolerance;
        std::ostringstream s;
        s.precision(10);
        s << "wi " << describe(wi) << " wo " << describe(wo) << " channel " << c << ": evaluator " << got[c]
          << ", transcription " << ref.f[c] << ", float noise of D " << ref.float_noise[c] << ", spread " << spread[c];
        stats.worst = s.str();
      }
    }
    if (limited) ++stats.limited;
    if (strict) ++stats.strict;
    if (strict_float_h) ++stats.strict_float_h;
    if (std::min(wi.z, wo.z) >= kSteep) {
      ++stats.steep;
      if (strict) ++stats.strict_steep;
      if (strict_float_h) ++stats.strict_float_h_steep;
      stats.max_relative_steep = std::max(stats.max_relative_steep, pair_relative);
      stats.max_relative_float_h_steep = std::max(stats.max_relative_float_h_steep, pair_relative_float_h);
    }
  }
  return stats;
}

}  // namespace

TEST_CASE("every stack without mixes matches an independent transcription of Elek's Algorithm 1") {
  // Every example and test material that is a plain stack: the 2-layer examples, house paint's
  // two coats, the three distinct interfaces of three_interfaces, and every distribution and
  // Fresnel term.
  const int pairs = 10000 / test::kSanitizerDivisor;
  std::string summary =
      "Elek transcription vs evaluator (" + std::to_string(pairs) +
      " pairs each): pairs within the strict 1e-5 against the exact transcription | worst strict relative error | "
      "the same against the transcription at the float-rounded half vector | max relative error where float "
      "conditioning allows 1e-5 | max error / (1e-5 + conditioning) | pairs where conditioning allows more than 1e-5\n";
  int compared = 0, layers_three = 0;
  long strict_total = 0, strict_float_h_total = 0, pairs_total = 0;
  for (const Example* each : examples_in_both_models()) {
    const Example& example = *each;
    std::optional<Stack> stack = read_stack(example.text);
    // Elek's algorithm is the Weidlich-Wilkie model; the energy-conserving one is not it.
    if (!stack || example.evaluator.program().model != lamina::kernels::LAMINA_MODEL_WEIDLICH_WILKIE) continue;
    CAPTURE(label(example));
    ++compared;
    if (stack->coats.size() >= 3) ++layers_three;
    TranscriptionStats stats = compare_with_transcription(example, *stack, pairs);
    CHECK_MESSAGE(stats.max_over_tolerance <= 1.0, stats.worst);
    // Where the distribution's sensitivity and the spread under one-ulp moves allow 1e-5, it holds.
    CHECK(stats.max_relative <= 1.0e-5);
    // Away from grazing, given the half vector the evaluator computes, what remains is the error of
    // evaluating in float: D's exponent tan^2 / m^2 reaches 80 inside a lobe, where a few roundings
    // of it (2.4e-7) move D by up to 2e-5.
    CHECK(stats.max_relative_float_h_steep <= 4.0e-5);
    strict_total += stats.strict;
    strict_float_h_total += stats.strict_float_h;
    pairs_total += stats.pairs;
    char line[300];
    std::snprintf(line, sizeof line, "  %-40s %zu coat(s): %5ld/%ld | %.3g | %5ld | %.3g | %.3g | %.3g | %ld\n",
                  label(example).c_str(), stack->coats.size(), stats.strict, stats.pairs, stats.max_relative_all,
                  stats.strict_float_h, stats.max_relative_float_h, stats.max_relative, stats.max_over_tolerance,
                  stats.limited);
    summary += line;
    std::snprintf(line, sizeof line,
                  "    steep pairs (cosines >= %.2f): %ld/%ld strict, worst %.3g | %ld at the float half vector, worst "
                  "%.3g\n",
                  double(kSteep), stats.strict_steep, stats.steep, stats.max_relative_steep, stats.strict_float_h_steep,
                  stats.max_relative_float_h_steep);
    summary += line;
  }
  CHECK(compared >= 20);
  CHECK(layers_three >= 1);
  char total[200];
  std::snprintf(total, sizeof total, "  all: %ld of %ld pairs strict (%.1f%%); at the float half vector %ld (%.1f%%)\n",
                strict_total, pairs_total, 100.0 * double(strict_total) / double(pairs_total), strict_float_h_total,
                100.0 * double(strict_float_h_total) / double(pairs_total));
  summary += total;
  MESSAGE(summary);
}

// --- 9: the mix ----------------------------------------------------------------------------------

TEST_CASE("checker tiles evaluate as the red stack on red squares and as the gold stack on gold squares") {
  const Example& example = example_named("checker_tiles");
  // The two stacks of examples/materials/checker_tiles.json, each on its own.
  cpu::Evaluator red = test::evaluator_from_text(R"({"format": 1, "materials": [{"name": "red", "surface": "@coat",
    "nodes": [
      {"id": "coat", "type": "layer", "interface": "@varnish", "medium": "@tint", "base": "@paint"},
      {"id": "varnish", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 1.5},
      {"id": "tint", "type": "medium/absorbing", "thickness": 1.2, "absorption": [0.01, 0.99, 0.99]},
      {"id": "paint", "type": "substrate/oren_nayar", "albedo": [1.0, 0.03, 0.05], "sigma": 0.0}]}]})");
  cpu::Evaluator gold = test::evaluator_from_text(R"({"format": 1, "materials": [{"name": "gold", "surface": "@coat",
    "nodes": [
      {"id": "coat", "type": "layer", "interface": "@varnish", "base": "@metal"},
      {"id": "varnish", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 1.0},
      {"id": "metal", "type": "substrate/conductor", "metal": "gold", "roughness_deg": 2.0}]}]})");
  std::mt19937_64 rng(0x5eed0009);
  long compared = 0, differs = 0;
  std::string first;
  for (int i = 0; i < 20000 / test::kSanitizerDivisor; ++i) {
    dvec3 wo_d = upper_direction(rng, nullptr, 0.0, 0.0, 0.0);
    dvec3 wi_d = upper_direction(rng, &wo_d, 0.4, 1.0e-3, 0.3);
    vec3 wo = test::to_float(wo_d), wi = test::to_float(wi_d);
    // A point inside a random square (8 x 8 per unit); squares with an even index sum are colour a.
    int su = int(test::uniform(rng) * 8.0), sv = int(test::uniform(rng) * 8.0);
    vec2 uv((float(su) + 0.1f + 0.8f * float(test::uniform(rng))) / 8.0f,
            (float(sv) + 0.1f + 0.8f * float(test::uniform(rng))) / 8.0f);
    const cpu::Evaluator& alone = (su + sv) % 2 == 0 ? red : gold;
    vec3 mixed = example.evaluator.eval(at_uv(uv), wi, wo), expected = alone.eval(ShadingContext{}, wi, wo);
    ++compared;
    if (mixed != expected && differs++ == 0)
      first = "uv " + describe(vec3(uv, 0.0f)) + ": mix " + describe(mixed) + " vs stack alone " + describe(expected);
  }
  CHECK(compared > 0);
  CHECK_MESSAGE(differs == 0, first);
}

TEST_CASE("house paint's middle interface is inert under the relative index: it evaluates as its top coat alone") {
  // Both of its coats have index 1.3, so the middle one has eta = 1: F = 0, T = 1, t = 1 (README,
  // "Energy"; the example's notes). Only float rounding of the refraction through it remains.
  const Example& example = example_named("house_paint");
  cpu::Evaluator top_only = test::evaluator_from_text(R"({"format": 1, "materials": [{"name": "top", "surface": "@top",
    "nodes": [
      {"id": "top", "type": "layer", "interface": "@top_iface", "base": "@paint"},
      {"id": "top_iface", "type": "interface/dielectric", "ior": 1.3, "roughness_deg": 30.0},
      {"id": "paint", "type": "substrate/oren_nayar", "albedo": [0.5, 0.9, 1.0], "sigma": 0.34}]}]})");
  std::mt19937_64 rng(0x5eed000a);
  double worst = 0.0;
  for (int i = 0; i < 20000 / test::kSanitizerDivisor; ++i) {
    vec3 wo = test::to_float(upper_direction(rng, nullptr, 0.0, 0.0, 0.0));
    dvec3 wo_d = test::to_double(wo);
    vec3 wi = test::to_float(upper_direction(rng, &wo_d, 0.3, 1.0e-3, 0.5));
    vec3 a = example.evaluator.eval(ShadingContext{}, wi, wo), b = top_only.eval(ShadingContext{}, wi, wo);
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(double(a[c]) - double(b[c])) / std::max(double(b[c]), 1.0e-12));
  }
  CHECK(worst <= 1.0e-5);
  MESSAGE("house_paint vs its top coat alone: largest relative difference " << worst);
  // Its lobe selection, too, gives the middle interface only the floor share (F = 0).
  std::vector<float> w = example.evaluator.lobe_weights(ShadingContext{}, glm::normalize(vec3(0.3f, 0.0f, 1.0f)));
  REQUIRE(w.size() == 3);
  CHECK(w[1] < 0.01f);
}
