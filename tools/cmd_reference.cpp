// lamina reference FILE --wi X,Y,Z --wo X,Y,Z | --albedo --theta DEG: the reference solver's
// Monte Carlo estimate (graph/cpu/reference.h) of f or of the directional albedo, with its
// standard error.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

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
};

int run_reference(const ReferenceCliOptions& o) {
  if (o.walks < 1 || o.walks > kMaxReferenceWalks) {
    std::cerr << "lamina: --walks: " << o.walks << " is outside [1, " << kMaxReferenceWalks << "]\n";
    return kExitInvalid;
  }
  if (o.max_depth < 1 || o.max_depth > kMaxDepth) {
    std::cerr << "lamina: --max-depth: " << o.max_depth << " is outside [1, " << kMaxDepth << "]\n";
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
