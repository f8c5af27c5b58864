// lamina reference FILE --wi X,Y,Z --wo X,Y,Z | --albedo --theta DEG: the reference solver's
// Monte Carlo estimate (graph/cpu/reference.h) of f or of the directional albedo, with its
// standard error; with --flakes, a flake paint's full model (graph/cpu/flake_reference.h) beside
// lamina's evaluation of it.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "graph/cpu/flake_reference.h"
#include "graph/cpu/reference.h"
#include "tools/commands.h"
#include "tools/json_rgb.h"
#include "tools/material_arg.h"

namespace lamina::cli {

namespace {

constexpr int64_t kMaxReferenceWalks = int64_t(1) << 32;
constexpr int kMaxDepth = 1 << 20;

struct ReferenceCliOptions {
  MaterialArg material;
  std::string wi, wo;
  bool albedo = false;
  double theta_deg = 0.0;
  bool theta_given = false;
  int64_t walks = int64_t(1) << 16;
  int max_depth = 1000;
  uint64_t seed = 0;
  ContextArg context;
  bool json = false;
  bool flakes = false;
  bool coarse = false;
};

// --flakes: the paint's full model per channel (doubling and adding, its boundary smooth) and the
// material's own evaluation at the same directions. f leaves out the boundary's mirror reflection
// (a delta); the albedo includes it.
int run_flakes(const ReferenceCliOptions& o, const cpu::ShadingPoint& point, const cpu::Evaluator& evaluator,
               std::optional<glm::vec3> wi, glm::vec3 wo) {
  cpu::FlakePaintSlabs slabs;
  try {
    slabs = cpu::flake_paint_slabs(point);
  } catch (const std::invalid_argument& e) {
    std::cerr << "lamina: " << o.material.file << ": material \"" << evaluator.program().name << "\": " << e.what()
              << " (README, Flake paint)\n";
    return kExitInvalid;
  }
  if (wo.z <= 0.0f || (wi && wi->z <= 0.0f)) {
    std::cerr << "lamina: --flakes takes directions above the horizon (z > 0)\n";
    return kExitInvalid;
  }
  const cpu::FlakeSlabOptions options = o.coarse ? cpu::FlakeSlabOptions::coarse() : cpu::FlakeSlabOptions{};
  glm::vec3 full(0.0f);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> views{double(wo.z)};
    if (wi) views.push_back(double(wi->z));
    try {
      const cpu::FlakeSlabSolution solution(slabs.channels[size_t(c)], views, options);
      if (wi) {
        // The azimuth of wo from the mirror side of the plane of incidence.
        const double phi = std::atan2(double(-wi->x * wo.y + wi->y * wo.x), double(-wi->x * wo.x - wi->y * wo.y));
        full[c] = float(solution.brdf(1, 0, phi));
      } else {
        full[c] = float(solution.albedo(0) + solution.mirror(0));
      }
    } catch (const std::invalid_argument& e) {
      std::cerr << "lamina: " << o.material.file << ": material \"" << evaluator.program().name << "\": " << e.what()
                << "\n";
      return kExitInvalid;
    }
  }
  const glm::vec3 model = wi ? point.eval(*wi, wo) : point.albedo(wo);
  const char* what = o.albedo ? "albedo" : "f";
  if (o.json) {
    nlohmann::json report{{what, json_rgb(full)},
                          {"model", json_rgb(model)},
                          {"boundary_slope", slabs.boundary_slope},
                          {"spectral_fold", slabs.spectral_fold}};
    if (o.albedo) report["theta_deg"] = o.theta_deg;
    std::cout << report.dump() << "\n";
    return kExitOk;
  }
  std::printf("%s = %.6g %.6g %.6g  (the paint's full model: doubling and adding)\n", what, full.r, full.g, full.b);
  std::printf("model %s = %.6g %.6g %.6g  (lamina's evaluation of the material)\n", what, model.r, model.g, model.b);
  if (slabs.boundary_slope > 0.0f)
    std::printf("the full model takes the boundary smooth; the material's interface has the slope %.3g\n",
                double(slabs.boundary_slope));
  if (wi)
    std::printf(
        "f: the full model leaves out its boundary's mirror reflection; the model's has its interface's lobe\n");
  if (slabs.spectral_fold)
    std::printf("the full model takes the flakes' film at 645, 525 and 445 nm; the material folds its spectrum\n");
  return kExitOk;
}

int run_reference(const ReferenceCliOptions& o) {
  if (o.walks < 1 || o.walks > kMaxReferenceWalks) {
    std::cerr << "lamina: --walks: " << o.walks << " is outside [1, " << kMaxReferenceWalks << "]\n";
    return kExitInvalid;
  }
  if (o.max_depth < 1 || o.max_depth > kMaxDepth) {
    std::cerr << "lamina: --max-depth: " << o.max_depth << " is outside [1, " << kMaxDepth << "]\n";
    return kExitInvalid;
  }
  if (o.coarse && !o.flakes) {
    std::cerr << "lamina: --coarse takes --flakes (the full flake model's solve)\n";
    return kExitInvalid;
  }
  std::optional<glm::vec3> wi, wo;
  if (o.albedo) {
    if (!o.wi.empty() || !o.wo.empty()) {
      std::cerr << "lamina: --albedo takes --theta, not --wi or --wo\n";
      return kExitInvalid;
    }
    if (!o.theta_given) {
      std::cerr << "lamina: --albedo needs --theta, the view angle from the normal in degrees\n";
      return kExitInvalid;
    }
    wo = parse_view_angle(o.theta_deg);
    if (!wo) return kExitInvalid;
  } else {
    if (o.wi.empty() || o.wo.empty() || o.theta_given) {
      std::cerr << "lamina: give --wi and --wo for f, or --albedo and --theta for the directional albedo\n";
      return kExitInvalid;
    }
    wi = parse_direction("--wi", o.wi);
    wo = parse_direction("--wo", o.wo);
    if (!wi || !wo) return kExitInvalid;
  }
  const std::optional<ShadingContext> ctx = parse_context(o.context);
  if (!ctx) return kExitInvalid;
  std::optional<cpu::Evaluator> evaluator;
  if (int code = load_material(o.material, evaluator); code != kExitOk) return code;
  const cpu::ShadingPoint point = evaluator->bind(*ctx);
  if (int code = refuse_tilted(o.material, *evaluator, point); code != kExitOk) return code;
  if (o.flakes) return run_flakes(o, point, *evaluator, wi, *wo);
  const cpu::ReferenceOptions options{o.walks, o.max_depth, o.seed};
  const cpu::ReferenceEstimate r =
      o.albedo ? cpu::reference_albedo(point, *wo, options) : cpu::reference_eval(point, *wi, *wo, options);
  const char* what = o.albedo ? "albedo" : "f";
  if (o.json) {
    nlohmann::json report{{what, json_rgb(r.value)},
                          {"std_error", json_rgb(r.std_error)},
                          {"walks", r.walks},
                          {"truncated_walks", r.truncated_walks},
                          {"truncated_weight", json_rgb(r.truncated)},
                          {"seed", o.seed}};
    if (o.albedo) report["theta_deg"] = o.theta_deg;
    std::cout << report.dump() << "\n";
  } else {
    std::printf("%s = %.6g %.6g %.6g  +- %.2g %.2g %.2g (standard error, %lld walks)\n", what, r.value.r, r.value.g,
                r.value.b, r.std_error.r, r.std_error.g, r.std_error.b, static_cast<long long>(r.walks));
    if (r.truncated_walks > 0)
      std::printf("%lld walks cut off at depth %d, carrying %.2g %.2g %.2g per walk\n",
                  static_cast<long long>(r.truncated_walks), o.max_depth, r.truncated.r, r.truncated.g, r.truncated.b);
  }
  return kExitOk;
}

}  // namespace

void add_reference(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<ReferenceCliOptions>();
  auto* cmd = app.add_subcommand(
      "reference", "Monte Carlo ground truth of a material's slab: f at --wi/--wo, or the albedo at --theta");
  add_material_options(*cmd, o->material);
  cmd->add_option("--wi", o->wi, "direction to the light, X,Y,Z in the local frame (z = normal); normalised");
  cmd->add_option("--wo", o->wo, "direction to the viewer, X,Y,Z in the local frame; normalised");
  cmd->add_flag("--albedo", o->albedo, "estimate the directional albedo seen from --theta instead of f");
  cmd->add_option("--theta", o->theta_deg, "with --albedo: view angle from the normal in degrees, in [0, 90)");
  cmd->add_option("--walks", o->walks, "random walks in the estimate")->capture_default_str();
  cmd->add_option("--max-depth", o->max_depth, "scattering events after which a walk is cut off")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "mixed into the seed hashed from the directions")->capture_default_str();
  add_context_options(*cmd, o->context);
  cmd->add_flag("--json", o->json, "print the estimate, its standard error and the truncation as JSON");
  cmd->add_flag("--flakes", o->flakes,
                "a layer over a substrate/flake_paint: solve the paint's full model (doubling and adding, 1 to 2 s a "
                "channel) instead of walking, and print lamina's evaluation beside it");
  cmd->add_flag("--coarse", o->coarse, "with --flakes: a coarse solve, about 0.05 s a channel (within 5e-3)");
  cmd->footer(
      "Follows light through the stack's boundaries (rough dielectric reflection and transmission both ways, "
      "total internal reflection), media (Beer-Lambert) and substrates without the layered model's approximations. "
      "The same arguments give the same digits; the standard error shrinks as 1/sqrt(walks).");
  cmd->callback([o, cmd, &runner] {
    o->theta_given = cmd->count("--theta") > 0;
    runner = [o] { return run_reference(*o); };
  });
}

}  // namespace lamina::cli
