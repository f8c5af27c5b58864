// lamina eval FILE --material NAME --wi X,Y,Z --wo X,Y,Z: the BRDF f (no cosine) and the sampling
// density pdf of one pair of directions, in the local frame (z along the normal); with --light, what
// is reflected of light of that colour (a fluorescent base moves light between channels).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "tools/commands.h"
#include "tools/material_arg.h"

namespace lamina::cli {

namespace {

struct EvalOptions {
  MaterialArg material;
  std::string wi, wo;
  std::string light;
  ContextArg context;
  bool json = false;
};

int run_eval(const EvalOptions& o) {
  auto wi = parse_direction("--wi", o.wi);
  auto wo = parse_direction("--wo", o.wo);
  if (!wi || !wo) return kExitInvalid;
  glm::vec3 light(1.0f);
  if (!o.light.empty()) {
    auto numbers = parse_numbers("--light", o.light, 3, "R,G,B, e.g. 0,1,0");
    if (!numbers) return kExitInvalid;
    light = glm::vec3((*numbers)[0], (*numbers)[1], (*numbers)[2]);
    if (light.x < 0.0f || light.y < 0.0f || light.z < 0.0f || !std::isfinite(light.x + light.y + light.z)) {
      std::cerr << "lamina eval: --light " << o.light << ": expected three finite numbers >= 0 (R,G,B)\n";
      return kExitInvalid;
    }
  }
  const std::optional<ShadingContext> ctx = parse_context(o.context);
  if (!ctx) return kExitInvalid;
  std::optional<cpu::Evaluator> evaluator;
  if (int code = load_material(o.material, evaluator); code != kExitOk) return code;
  cpu::EvalPdf result = evaluator->eval_pdf(*ctx, *wi, *wo);
  if (!o.light.empty()) result.f = evaluator->eval(*ctx, *wi, *wo, light);
  if (o.json) {
    nlohmann::json report{{"f", {result.f.r, result.f.g, result.f.b}}, {"pdf", result.pdf}};
    std::cout << report.dump() << "\n";
  } else {
    std::printf("f = %.6g %.6g %.6g  pdf = %.6g\n", double(result.f.r), double(result.f.g), double(result.f.b),
                double(result.pdf));
  }
  return kExitOk;
}

}  // namespace

void add_eval(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<EvalOptions>();
  auto* cmd = app.add_subcommand("eval", "Evaluate a material's BRDF f (no cosine) and pdf for one pair of directions");
  add_material_options(*cmd, o->material);
  cmd->add_option("--wi", o->wi, "direction to the light, X,Y,Z in the local frame (z = normal); normalised")
      ->required();
  cmd->add_option("--wo", o->wo, "direction to the viewer, X,Y,Z in the local frame; normalised")->required();
  cmd->add_option("--light", o->light,
                  "the light's colour R,G,B (linear, >= 0): f becomes what is reflected of it per unit of "
                  "irradiance, which differs from f times the colour only under fluorescence (default 1,1,1)");
  add_context_options(*cmd, o->context);
  cmd->add_flag("--json", o->json, "print {\"f\": [r, g, b], \"pdf\": p} at full float precision");
  cmd->footer(
      "Directions point away from the surface; a direction below the horizon (z <= 0) gives f = 0 and pdf = 0.");
  cmd->callback([o, &runner] { runner = [o] { return run_eval(*o); }; });
}

}  // namespace lamina::cli
