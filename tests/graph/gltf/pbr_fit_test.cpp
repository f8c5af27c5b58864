// glTF's reference BRDF on the CPU (values against an independent python transcription of the
// specification's formulas, physical properties, albedo quadrature) and the fit of its parameters
// (recovering known glTF parameters; every bundled example fitted within documented limits).
#include "graph/gltf/pbr_fit.h"

#include "graph/compile.h"
#include "graph/cpu/reference.h"
#include "graph/gltf/fallback.h"
#include "nodes/kernels/kernels.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <sstream>
#include <string>

#include "../cpu_test_support.h"
#include "test_support.h"

using namespace lamina;
using glm::vec3;
using gltf::PbrParams;

namespace {

PbrParams params(vec3 base, float metallic, float roughness) {
  PbrParams p;
  p.base_color = base;
  p.metallic = metallic;
  p.roughness = roughness;
  return p;
}

PbrParams plastic() { return params({0.8f, 0.2f, 0.1f}, 0.0f, 0.5f); }
PbrParams metal() { return params({0.95f, 0.64f, 0.54f}, 1.0f, 0.3f); }
PbrParams ior_specular() {
  PbrParams p = params({0.2f, 0.5f, 0.3f}, 0.3f, 0.7f);
  p.ior = 1.8f;
  p.specular = 0.7f;
  p.specular_color = {1.5f, 0.8f, 14.0f};  // blue: 0.0816 * 14 > 1, so the min(..., 1) clamp acts
  return p;
}
PbrParams coated() {
  PbrParams p = params({0.1f, 0.3f, 0.7f}, 0.0f, 0.6f);
  p.clearcoat = 0.8f;
  p.clearcoat_roughness = 0.2f;
  return p;
}

std::vector<PbrParams> parameter_sets() {
  std::vector<PbrParams> sets{plastic(), metal(), ior_specular(), coated()};
  PbrParams smooth = params({0.5f, 0.5f, 0.5f}, 0.5f, 0.0f);  // roughness 0: the alpha floor
  smooth.clearcoat = 1.0f;
  sets.push_back(smooth);
  return sets;
}

std::string describe(vec3 v) {
  std::ostringstream s;
  s.precision(4);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

void check_close(vec3 actual, vec3 expected, float relative) {
  for (int c = 0; c < 3; ++c) CHECK(actual[c] == doctest::Approx(expected[c]).epsilon(relative).scale(0.0));
}

vec3 random_direction(std::mt19937_64& rng) {
  double cos_theta = test::uniform(rng), phi = 2.0 * test::kPi * test::uniform(rng);
  return test::to_float(test::from_cosine(cos_theta, phi));
}

gltf::FitTarget target_of(const PbrParams& p) {
  return {[p](vec3 wi, vec3 wo) { return gltf::pbr_eval(p, wi, wo); },
          [p](vec3 wo) { return gltf::pbr_albedo(p, wo); }};
}

}  // namespace

TEST_CASE("pbr_eval matches an independent transcription of the glTF specification's formulas") {
  // Expected values: a python transcription of Appendix B sec. B.3.2-B.3.4 with the
  // KHR_materials_ior, _specular and _clearcoat "Implementation" sections, in double precision:
  //   brdf(base, metallic, rough, ior, spec, spec_col, cc, ccr, L, V) with L, V normalised,
  //   H = normalize(L + V), D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2), a = rough^2,
  //   Vis = 1/(N.L + sqrt(a^2 + (1 - a^2)(N.L)^2)) * 1/(N.V + sqrt(a^2 + (1 - a^2)(N.V)^2)),
  //   w = (1 - |V.H|)^5, f0 = ((ior - 1)/(ior + 1))^2, df0 = min(f0 spec_col, 1) spec,
  //   F = df0 + (spec - df0) w, diel = F Vis D + (1 - max(F)) base / pi,
  //   metal = Vis D (base + (1 - base) w), m = mix(diel, metal, metallic),
  //   coated = (1 - cc Fc) m + cc Fc Vis(ccr^2) D(ccr^2), Fc = 0.04 + 0.96 (1 - N.V)^5.
  auto n = [](vec3 v) { return glm::normalize(v); };
  // brdf(base=[0.8,0.2,0.1], metallic=0, rough=0.5, L=[0.3,0.2,0.9], V=[-0.5,0.1,0.7])
  check_close(gltf::pbr_eval(plastic(), n({0.3f, 0.2f, 0.9f}), n({-0.5f, 0.1f, 0.7f})),
              {0.264648673f, 0.0813047303f, 0.0507474065f}, 2e-5f);
  // brdf(base=[0.95,0.64,0.54], metallic=1, rough=0.3, L=[0.4,-0.1,0.6], V=[-0.35,0.05,0.8])
  check_close(gltf::pbr_eval(metal(), n({0.4f, -0.1f, 0.6f}), n({-0.35f, 0.05f, 0.8f})),
              {2.66965754f, 1.7985358f, 1.51752879f}, 2e-5f);
  // brdf(base=[0.2,0.5,0.3], metallic=0.3, rough=0.7, ior=1.8, spec=0.7, spec_col=[1.5,0.8,14],
  //      L=[0.7,0.3,0.3], V=[-0.2,-0.4,0.6])
  check_close(gltf::pbr_eval(ior_specular(), n({0.7f, 0.3f, 0.3f}), n({-0.2f, -0.4f, 0.6f})),
              {0.0500500033f, 0.0884970705f, 0.193202743f}, 2e-5f);
  // brdf(base=[0.1,0.3,0.7], metallic=0, rough=0.6, cc=0.8, ccr=0.2, L=[0.25,0.1,0.9], V=[-0.3,-0.1,0.85])
  check_close(gltf::pbr_eval(coated(), n({0.25f, 0.1f, 0.9f}), n({-0.3f, -0.1f, 0.85f})),
              {0.6489296f, 0.708089335f, 0.826408804f}, 2e-5f);
}

TEST_CASE("pbr_eval's specular lobe is Appendix B's Vis D with the separable Smith visibility, in double here") {
  // A white metal: F = baseColor + (1 - baseColor) fresnel_w = 1, so f = Vis D (sec. B.3.2, as
  // written before KhronosGroup/glTF#2541) with D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2), a = rough^2,
  // and Vis = 1 / ((N.L + sqrt(a^2 + (1 - a^2)(N.L)^2)) (N.V + sqrt(a^2 + (1 - a^2)(N.V)^2))).
  auto spec = [](double rough, glm::dvec3 l, glm::dvec3 v) {
    const double a2 = std::pow(rough, 4.0);
    const glm::dvec3 h = glm::normalize(l + v);
    const double d = a2 / (test::kPi * std::pow(h.z * h.z * (a2 - 1.0) + 1.0, 2.0));
    auto vis1 = [a2](double c) { return 1.0 / (c + std::sqrt(a2 + (1.0 - a2) * c * c)); };
    return vis1(l.z) * vis1(v.z) * d;
  };
  for (float rough : {0.1f, 0.3f, 0.6f, 1.0f}) {
    const PbrParams white_metal = params(vec3(1.0f), 1.0f, rough);
    for (double theta_l : {0.0, 20.0, 55.0, 85.0})
      for (double theta_v : {5.0, 40.0, 70.0, 89.0})
        for (double phi : {0.0, 90.0, 180.0}) {
          const glm::dvec3 l = test::spherical(test::radians(theta_l), test::radians(phi));
          const glm::dvec3 v = test::spherical(test::radians(theta_v), 0.0);
          const vec3 f = gltf::pbr_eval(white_metal, test::to_float(l), test::to_float(v));
          CAPTURE(rough);
          CAPTURE(theta_l);
          CAPTURE(theta_v);
          CAPTURE(phi);
          for (int c = 0; c < 3; ++c)
            CHECK(double(f[c]) == doctest::Approx(spec(rough, l, v)).epsilon(1e-4).scale(0.0));
        }
  }
  // Roughness 0 is floored at alpha = the kernels' smooth limit: at normal incidence D = 1 / (pi a^2)
  // and Vis = 1/4.
  const double m = double(kernels::LAMINA_MIN_SLOPE);
  const vec3 n(0.0f, 0.0f, 1.0f);
  CHECK(double(gltf::pbr_eval(params(vec3(1.0f), 1.0f, 0.0f), n, n).x) ==
        doctest::Approx(1.0 / (4.0 * test::kPi * m * m)).epsilon(1e-5).scale(0.0));
}

TEST_CASE("pbr_eval is finite, non-negative, zero below the horizon and reciprocal without a clearcoat") {
  std::mt19937_64 rng(20240611);
  for (const PbrParams& p : parameter_sets()) {
    int bad = 0, below = 0, not_reciprocal = 0, coat_asymmetric = 0;
    for (int i = 0; i < 4000; ++i) {
      vec3 wi = random_direction(rng), wo = random_direction(rng);
      vec3 f = gltf::pbr_eval(p, wi, wo), g = gltf::pbr_eval(p, wo, wi);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(f[c]) || f[c] < 0.0f) ++bad;
        bool equal = std::abs(f[c] - g[c]) <= 1e-5f * std::max(1.0f, std::abs(f[c]));
        if (p.clearcoat == 0.0f && !equal) ++not_reciprocal;
        if (p.clearcoat > 0.0f && !equal) ++coat_asymmetric;
      }
      vec3 wo_below(wo.x, wo.y, -wo.z);
      if (gltf::pbr_eval(p, wi, wo_below) != vec3(0.0f) || gltf::pbr_eval(p, wo_below, wi) != vec3(0.0f)) ++below;
      // With a clearcoat, f weights the layers by a Fresnel term of N.V alone
      // (KHR_materials_clearcoat): swapping directions of equal elevation leaves f unchanged.
      vec3 wi_same(-wo.y, wo.x, wo.z);
      vec3 h = gltf::pbr_eval(p, wi_same, wo), k = gltf::pbr_eval(p, wo, wi_same);
      for (int c = 0; c < 3; ++c)
        if (std::abs(h[c] - k[c]) > 1e-5f * std::max(1.0f, std::abs(h[c]))) ++not_reciprocal;
    }
    CHECK(bad == 0);
    CHECK(below == 0);
    CHECK(not_reciprocal == 0);
    // ... but not in general: the spec's N.V Fresnel is not reciprocal, and this implements it as written.
    if (p.clearcoat > 0.0f) CHECK(coat_asymmetric > 0);
  }
  CHECK(gltf::pbr_eval(plastic(), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f)) == vec3(0.0f));
}

TEST_CASE("pbr_albedo integrates a white Lambert to one and a rough white metal to 1 - ln 2") {
  PbrParams lambert = params(vec3(1.0f), 0.0f, 0.5f);
  lambert.specular = 0.0f;  // dielectric_f0 = dielectric_f90 = 0: pure diffuse
  PbrParams rough_metal = params(vec3(1.0f), 1.0f, 1.0f);
  for (float degrees : {0.0f, 30.0f, 60.0f, 80.0f}) {
    float theta = degrees * float(test::kPi) / 180.0f;
    vec3 wo(std::sin(theta), 0.0f, std::cos(theta));
    vec3 a = gltf::pbr_albedo(lambert, wo);
    for (int c = 0; c < 3; ++c) CHECK(a[c] == doctest::Approx(1.0f).epsilon(1e-3).scale(0.0));
    vec3 m = gltf::pbr_albedo(rough_metal, wo);
    CHECK(m.x < 1.0f);  // single scattering loses energy
    CHECK(m.x > 0.0f);
  }
  // Alpha = 1 makes D = 1/pi, so at normal incidence (F = 1 for base colour 1) f cos integrates to
  // 2 pi int_0^1 (1/pi) / ((mu + 1) * 2) mu dmu = 1 - ln 2.
  vec3 normal(0.0f, 0.0f, 1.0f);
  CHECK(gltf::pbr_albedo(rough_metal, normal).x == doctest::Approx(1.0 - std::log(2.0)).epsilon(2e-3).scale(0.0));
  // Python midpoint rule in (cos theta_i, phi), 400 x 200 cells, of the transcription above:
  // metal base 1 roughness 1 at 60 degrees: 0.409137353; plastic base 0.5 roughness 0.7 at 60: 0.514908808.
  vec3 wo60(std::sin(float(test::kPi) / 3.0f), 0.0f, 0.5f);
  CHECK(gltf::pbr_albedo(rough_metal, wo60).x == doctest::Approx(0.409137353).epsilon(3e-3).scale(0.0));
  CHECK(gltf::pbr_albedo(params(vec3(0.5f), 0.0f, 0.7f), wo60).x ==
        doctest::Approx(0.514908808).epsilon(3e-3).scale(0.0));
}

TEST_CASE("fit_pbr recovers the parameters of glTF materials fitted to themselves") {
  struct Case {
    const char* name;
    PbrParams truth;
  };
  PbrParams self_plastic = params({0.7f, 0.3f, 0.15f}, 0.0f, 0.45f);
  PbrParams self_metal = params({0.9f, 0.7f, 0.35f}, 1.0f, 0.3f);
  PbrParams self_coated = params({0.1f, 0.35f, 0.6f}, 0.0f, 0.7f);
  self_coated.clearcoat = 1.0f;
  self_coated.clearcoat_roughness = 0.1f;
  for (const Case& c : {Case{"plastic", self_plastic}, Case{"metal", self_metal}, Case{"coated", self_coated}}) {
    gltf::FitResult fit = gltf::fit_pbr(target_of(c.truth));
    const PbrParams& p = fit.params;
    INFO(c.name, ": base ", describe(p.base_color), " metallic ", p.metallic, " roughness ", p.roughness, " clearcoat ",
         p.clearcoat, " / ", p.clearcoat_roughness, " rms ", fit.error.rms);
    for (int k = 0; k < 3; ++k) CHECK(std::abs(p.base_color[k] - c.truth.base_color[k]) < 0.02f);
    CHECK(std::abs(p.roughness - c.truth.roughness) < 0.05f);
    CHECK(std::abs(p.metallic - c.truth.metallic) < 0.1f);
    CHECK(fit.uses_clearcoat == (c.truth.clearcoat > 0.0f));
    CHECK_FALSE(fit.uses_ior);
    CHECK_FALSE(fit.uses_specular);
    if (fit.uses_clearcoat) {
      CHECK(std::abs(p.clearcoat - c.truth.clearcoat) < 0.1f);
      CHECK(std::abs(p.clearcoat_roughness - c.truth.clearcoat_roughness) < 0.05f);
    }
    CHECK(fit.error.albedo_normal < 0.01f);
    CHECK(fit.error.albedo_grazing < 0.01f);
    CHECK(fit.error.rms < 0.02f);
  }
}

namespace {

// The share of the target's albedo no glTF fit can reach: the reference BRDF reflects at most all
// light, but lamina's model exceeds 1 for several examples (cpu_physics_test.cpp, white furnace).
float unreachable(vec3 albedo) {
  float worst = 0.0f;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::max(0.0f, albedo[c] - 1.0f) / albedo[c]);
  return worst;
}

// What a texture state of a material is made of, read from its compiled stack (never from a fit):
// whether a conductor is reachable through the mixes at that state's weights.
bool reaches_conductor(const Program& program, const std::vector<float>& registers, int index) {
  namespace k = kernels;
  const StackEntry& e = program.stack[static_cast<size_t>(index)];
  if (e.kind == k::LAMINA_SUBSTRATE) return e.model == k::LAMINA_SUBSTRATE_CONDUCTOR;
  if (e.kind == k::LAMINA_LAYER) return reaches_conductor(program, registers, e.first);
  // A mix: the evaluator clamps a linked weight to its range [0, 1]; a stack with no weight is not seen.
  const InputRef& weight = e.scalar_x;
  const float w =
      std::clamp(weight.linked() ? registers[static_cast<size_t>(weight.slot)] : weight.constant.x, 0.0f, 1.0f);
  return (w < 1.0f && reaches_conductor(program, registers, e.first)) ||
         (w > 0.0f && reaches_conductor(program, registers, e.second));
}

// Limits by structure on the errors beyond the unreachable share, each the worst measured over the
// fitted texture states of the bundled examples in their own model (the table this test prints)
// plus 0.02, rounded up to a whole percent: the margin covers compilers and libm implementations
// that round differently, while a change that makes any fit worse by more than two percentage
// points fails.
//  - Dielectric coats over a diffuse base: glTF's dielectric lobe over Lambert is the same
//    structure. Worst: A(0) 0.219, A(80) 0.172 and RMS 0.252, all frosted_acrylic_paint (a rough
//    coat, which glTF's single roughness shares with the base).
//  - A conductor reachable under a coat: one Schlick-Fresnel GGX lobe per glTF layer cannot follow
//    a metal lobe squeezed into the coat's refraction cone, nor a coloured metal that stays coloured
//    at grazing views, where glTF's Schlick term turns every metal white. Worst: A(0) 0.234
//    (car_paint), A(80) 0.456 and RMS 0.414 (christmas_orb: its green at 80 degrees, 0.39, is read
//    as 0.57).
struct Limits {
  float normal, grazing, rms;
};
constexpr Limits kDiffuseBase{0.24f, 0.20f, 0.28f};
constexpr Limits kConductorBase{0.26f, 0.48f, 0.44f};

// What a person sees: the fallback's mean colour on the preview sphere against the material's own
// (graph/gltf/appearance.h), CIE 1976 |Delta L*| and the distance of (a*, b*), for every structure:
// the worst measured plus 2, rounded up (|Delta L*| 4.3, checker_tiles' gold square; (a*, b*) 4.8,
// a copper state of patina_map_copper). A fallback that turns a coloured material grey differs by
// its whole chroma (gold_metallic_paint's grey-white fallback: 12.5, appearance_test.cpp).
constexpr float kLightnessLimit = 7.0f;
constexpr float kColourLimit = 7.0f;
// A thin-film surface's fit (KHR_materials_iridescence) is held to what a person sees and to its
// RMS: the extension's film (Schlick's terms without polarisation, phases of 0 or pi) is a coarse
// copy of lamina's exact one, and a dark film's albedo, off by a few hundredths, is off by
// hundreds of percent at 80 degrees (a soap film: 0.2 where lamina's reflects 0.009 in blue).
constexpr float kFilmRms = 0.8f;
constexpr float kFilmColourLimit = 10.0f;

}  // namespace

TEST_CASE("fit_pbr fits every texture state of every bundled example within its structure's limits") {
  // The fallback fits exactly what the export fits: every distinct texture state of the bake grid
  // (or the representative states when there are more than max_states), with the CLI's options;
  // under the sanitisers, which look for memory errors, on a 64-texel grid, at most three states a
  // material (more repeat the same code; they took 166 s of a clean-clone CI run's ASan phase) and
  // for every second example (the round trip's sweep covers the others).
  gltf::FallbackOptions options;
  if (test::kSanitized) {
    options.bake_size = 64;
    options.max_states = 3;
  }
  std::string table =
      "\nname                   state uv            base  base colour           metal rough  ior   spec"
      "  coat  c.rough ext | A(0) err unreach A(80) err unreach rms    dL*  dab\n";
  for (const auto& file : test::swept_example_files(0)) {
    const std::string name = file.stem().string();
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    const Program program = compile(*checked.graphs[0], file.string());
    const cpu::Evaluator material(program);
    const gltf::Fallback fallback = gltf::fit_fallback(program, options);
    REQUIRE_FALSE(fallback.states.empty());
    for (const auto& state : fallback.states) {
      ShadingContext ctx;  // the state's texel, filtered over it as the bake is
      ctx.uv = state.uv;
      if (fallback.bake_size > 0) ctx.footprint = 1.0f / float(fallback.bake_size);
      const bool conductor = reaches_conductor(program, material.texture_registers(ctx), 0);
      const gltf::FitResult& fit = state.fit;
      const PbrParams& p = fit.params;
      const vec3 normal(0.0f, 0.0f, 1.0f), grazing(std::sin(1.3962634f), 0.0f, std::cos(1.3962634f));
      const cpu::ShadingPoint flat = material.bind_untilted(ctx);  // what the fit fits
      const float unreachable_normal = unreachable(flat.albedo(normal));
      const float unreachable_grazing = unreachable(flat.albedo(grazing));
      char line[400];
      std::snprintf(line, sizeof line,
                    "%-22s (%.3f, %.3f)  %-5s (%.3f,%.3f,%.3f)  %.3f %.3f  %.3f %.3f  %.3f %.3f   %c%c%c | %.4f   "
                    "%.4f  %.4f   %.4f  %.4f  %4.1f %4.1f\n",
                    name.c_str(), state.uv.x, state.uv.y, conductor ? "metal" : "diff", p.base_color.x, p.base_color.y,
                    p.base_color.z, p.metallic, p.roughness, p.ior, p.specular, p.clearcoat, p.clearcoat_roughness,
                    fit.uses_clearcoat ? 'c' : '-',
                    fit.uses_ior           ? 'i'
                    : fit.uses_iridescence ? 'f'
                                           : '-',
                    fit.uses_specular ? 's' : '-', fit.error.albedo_normal, unreachable_normal,
                    fit.error.albedo_grazing, unreachable_grazing, fit.error.rms, fit.error.lightness,
                    fit.error.colour);
      table += line;
      INFO(line);
      const Limits& limits = conductor ? kConductorBase : kDiffuseBase;
      // A state whose stack a normal input tilts (a flake, a glitter facet) is fitted as its flat
      // equivalent (the fallback's normal texture puts the tilt back: the test below), and its
      // errors are the fit's against that, held to the same limits as every other state.
      if (fit.uses_iridescence) {
        CHECK(fit.error.rms <= kFilmRms);
        CHECK(fit.error.lightness <= kLightnessLimit);
        CHECK(fit.error.colour <= kFilmColourLimit);
      } else {
        CHECK(fit.error.albedo_normal <= unreachable_normal + limits.normal);
        CHECK(fit.error.albedo_grazing <= unreachable_grazing + limits.grazing);
        CHECK(fit.error.rms <= limits.rms);
        CHECK(fit.error.lightness <= kLightnessLimit);
        CHECK(fit.error.colour <= kColourLimit);
      }
      // The reported unreachable share is (A - 1) / A of the material's own albedo at normal incidence.
      CHECK(fit.error.unreachable_normal == doctest::Approx(unreachable_normal).epsilon(1e-4));  // 0 for most
    }
  }
  MESSAGE(table);
}

TEST_CASE("fit_pbr is deterministic: the same material and state give bit-identical parameters") {
  for (const char* example : {"car_paint", "house_paint", "checker_tiles"}) {
    CAPTURE(example);
    cpu::Evaluator material =
        test::load_evaluator(test::source_dir() / "examples/materials" / (std::string(example) + ".json"));
    ShadingContext ctx;
    ctx.uv = glm::vec2(0.3f, 0.6f);
    const gltf::FitResult fit = gltf::fit_pbr(material, ctx), again = gltf::fit_pbr(material, ctx);
    CHECK(std::memcmp(&fit.params, &again.params, sizeof(PbrParams)) == 0);
    CHECK(fit.error.rms == again.error.rms);
    CHECK(fit.error.albedo_normal == again.error.albedo_normal);
    CHECK(fit.uses_ior == again.uses_ior);
    CHECK(fit.uses_clearcoat == again.uses_clearcoat);
    CHECK(fit.uses_specular == again.uses_specular);
  }
}

TEST_CASE("the fallback's normal texture puts back glitter facets' tilt, and only tilted substrates get one") {
  // Normals need no fits: two representative states keep the fitting cheap.
  gltf::FallbackOptions options;
  options.max_states = 2;
  bool aventurine = false;
  int sanitised_bakes = 0;
  for (const auto& file : test::example_files()) {
    CAPTURE(file.filename().string());
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    const Program program = compile(*checked.graphs[0], file.string());
    bool tilts = false;
    for (const StackEntry& e : program.stack)
      tilts = tilts || (e.kind == kernels::LAMINA_SUBSTRATE && e.normal.linked());
    // Whether a normal texture is made is decided by the stack alone when nothing tilts: the
    // smallest bake shows it. The sanitisers look for memory errors, in the bake of normals: they
    // visit the first stack that tilts, on the smallest bake (the bake is the same code for every
    // texture that tilts); the statistics below are the optimised build's.
    if (test::kSanitized && (!tilts || sanitised_bakes++ > 0)) continue;
    options.bake_size = tilts && !test::kSanitized ? 256 : 64;
    const gltf::Fallback fallback = gltf::fit_fallback(program, options);
    if (!tilts) CHECK_FALSE(fallback.normal);
    // No bundled example tilts an interface ("a tilted coat ..." below has one that does).
    bool coat_tilts = false;
    for (const StackEntry& e : program.stack)
      coat_tilts = coat_tilts || (e.kind == kernels::LAMINA_LAYER && e.normal.linked());
    if (!coat_tilts) CHECK_FALSE(fallback.clearcoat_normal);
    if (!fallback.normal) continue;
    // Unit normals, within a byte's step, and never below the surface.
    const gltf::BakedImage& image = *fallback.normal;
    REQUIRE(image.channels == 3);
    REQUIRE(image.pixels.size() == size_t(image.size) * size_t(image.size) * 3);
    double tilted = 0.0, tilt_sum = 0.0;
    for (size_t t = 0; t < image.pixels.size(); t += 3) {
      const vec3 n = vec3(image.pixels[t], image.pixels[t + 1], image.pixels[t + 2]) / 127.5f - vec3(1.0f);
      CHECK(std::abs(glm::length(n) - 1.0f) < 0.02f);
      CHECK(n.z > 0.0f);
      const double degrees = std::acos(std::clamp(double(n.z) / double(glm::length(n)), -1.0, 1.0)) * 180.0 / M_PI;
      if (degrees > 1.0) {
        tilted += 1.0;
        tilt_sum += degrees;
      }
    }
    const double texels = double(image.size) * double(image.size), share = tilted / texels;
    const double mean_tilt = tilt_sum / std::max(tilted, 1.0);
    MESSAGE(file.filename().string() << ": " << 100.0 * share << "% of texels tilted over 1 degree, by " << mean_tilt
                                     << " degrees on average");
    if (file.filename() == "aventurine_glass.json" && !test::kSanitized) {
      aventurine = true;
      // One glitter entry in 4 is a facet, its cell's normal drawn from Beckmann slopes of m = tan 3
      // degrees (tan^2 = -m^2 ln(1 - u), Walter et al. 2007 eq. 28): 10.5% of facets tilt under 1
      // degree (1 - e^(-1/9)), so 22.4% of texels should tilt over it, by 2.9 degrees on average
      // (E[theta | theta > 1 degree]), a little less at cell edges. Measured: 23.0%, 2.59 degrees.
      CHECK(share == doctest::Approx(0.224).epsilon(0.2));
      CHECK(mean_tilt > 2.0);
      CHECK(mean_tilt < 3.5);
    }
  }
  // The glitter's 4.3 texels per cell at this size resolve its facets: it gets one.
  if (!test::kSanitized) CHECK(aventurine);
}

TEST_CASE("a tilted coat gets a clearcoat normal texture that puts back its facets' tilt, and its flat base none") {
  const std::filesystem::path file = test::source_dir() / "tests/data/gltf/tilted_coat.json";
  CheckedFile checked = check_file(file);
  REQUIRE(checked.ok());
  const Program program = compile(*checked.graphs[0], file.string());
  gltf::FallbackOptions options;
  options.max_states = 2;
  options.bake_size = 64;
  const gltf::Fallback fallback = gltf::fit_fallback(program, options);
  // A smooth varnish over a rough metal: two lobes, the sharp one the clearcoat.
  REQUIRE(fallback.uses_clearcoat);
  CHECK_FALSE(fallback.normal);
  REQUIRE(fallback.clearcoat_normal);
  const gltf::BakedImage& image = *fallback.clearcoat_normal;
  REQUIRE(image.channels == 3);
  REQUIRE(image.size == 64);
  // Each texel inside one cell (its corners' coat normals agree) holds that cell's normal within a
  // byte's step. The cells' normals have Beckmann slopes of m = tan 6 degrees: tan theta = m sqrt(E),
  // E exponential (Walter et al. 2007 eq. 28), so the mean tilt is about atan(m sqrt(pi) / 2) = 5.3
  // degrees; over the 64 cells of the uv square, within 30%.
  const cpu::Evaluator evaluator(program);
  const auto coat_normal = [&](glm::vec2 uv) {
    ShadingContext ctx;
    ctx.uv = uv;
    ctx.footprint = 1.0f / 128.0f;
    return evaluator.entry_covers(ctx)[0].normal;
  };
  int inside = 0, off = 0;
  double tilt_sum = 0.0;
  for (int row = 0; row < image.size; ++row)
    for (int column = 0; column < image.size; ++column) {
      const float step = 1.0f / float(image.size);
      const vec3 a = coat_normal(glm::vec2(float(column) + 0.25f, float(row) + 0.25f) * step);
      const vec3 b = coat_normal(glm::vec2(float(column) + 0.75f, float(row) + 0.75f) * step);
      const vec3 c = coat_normal(glm::vec2(float(column) + 0.25f, float(row) + 0.75f) * step);
      const vec3 d = coat_normal(glm::vec2(float(column) + 0.75f, float(row) + 0.25f) * step);
      if (!(a == b && a == c && a == d)) continue;
      ++inside;
      const size_t t = (size_t(row) * size_t(image.size) + size_t(column)) * 3;
      const vec3 n = vec3(image.pixels[t], image.pixels[t + 1], image.pixels[t + 2]) / 127.5f - vec3(1.0f);
      off += glm::all(glm::lessThanEqual(glm::abs(n - a), vec3(1.5f / 127.5f))) ? 0 : 1;
      tilt_sum += std::acos(std::clamp(double(a.z), -1.0, 1.0)) * 180.0 / M_PI;
    }
  CHECK(inside > image.size * image.size / 2);
  CHECK(off == 0);
  const double mean_tilt = tilt_sum / std::max(inside, 1);
  MESSAGE("tilted coat: " << inside << " texels inside one cell, mean tilt " << mean_tilt << " degrees");
  CHECK(mean_tilt == doctest::Approx(5.3).epsilon(0.3));
}
