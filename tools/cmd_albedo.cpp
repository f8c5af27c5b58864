// lamina albedo FILE --material NAME --theta DEG: the directional albedo (the integral of f cos
// over the hemisphere) seen from theta degrees off the normal, by the evaluator's quadrature.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "tools/commands.h"
#include "tools/material_arg.h"

namespace lamina::cli {

namespace {

constexpr int kMaxPoints = 1 << 20;

struct AlbedoOptions {
  MaterialArg material;
  double theta_deg = 0.0;
  int points = 1024;
  ContextArg context;
  bool json = false;
};

int run_albedo(const AlbedoOptions& o) {
  const std::optional<glm::vec3> wo = parse_view_angle(o.theta_deg);
  if (!wo) return kExitInvalid;
  if (o.points < 1 || o.points > kMaxPoints) {
    std::cerr << "lamina: --points: " << o.points << " is outside [1, " << kMaxPoints
              << "] (quadrature points per lobe)\n";
    return kExitInvalid;
  }
  const std::optional<ShadingContext> ctx = parse_context(o.context);
  if (!ctx) return kExitInvalid;
  std::optional<cpu::Evaluator> evaluator;
  if (int code = load_material(o.material, evaluator); code != kExitOk) return code;
  glm::vec3 albedo = evaluator->albedo(*ctx, *wo, o.points);
  if (o.json) {
    nlohmann::json report{{"albedo", {albedo.r, albedo.g, albedo.b}}, {"theta_deg", o.theta_deg}};
    std::cout << report.dump() << "\n";
  } else {
    std::printf("albedo = %.6g %.6g %.6g\n", double(albedo.r), double(albedo.g), double(albedo.b));
  }
  return kExitOk;
}

}  // namespace

void add_albedo(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<AlbedoOptions>();
  auto* cmd = app.add_subcommand("albedo", "Directional albedo of a material seen from theta degrees off the normal");
  add_material_options(*cmd, o->material);
  cmd->add_option("--theta", o->theta_deg, "view angle from the normal in degrees, in [0, 90)")->required();
  cmd->add_option("--points", o->points, "quadrature points per lobe")->capture_default_str();
  add_context_options(*cmd, o->context);
  cmd->add_flag("--json", o->json, "print {\"albedo\": [r, g, b], \"theta_deg\": t} at full float precision");
  cmd->footer(
      "The view direction is (sin theta, 0, cos theta) in the local frame. The albedo is the fraction of light "
      "from that direction reflected into the hemisphere, per channel (1 - albedo is absorbed).");
  cmd->callback([o, &runner] { runner = [o] { return run_albedo(*o); }; });
}

}  // namespace lamina::cli
