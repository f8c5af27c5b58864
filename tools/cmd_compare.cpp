// lamina compare FILE: the layered model against the reference solver (graph/cpu/compare.h):
// directional albedo at 0 to 89 degrees, in-plane BRDF slices, and the relative errors.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "graph/cpu/compare.h"
#include "tools/commands.h"
#include "tools/figure_file.h"
#include "tools/json_rgb.h"
#include "tools/material_arg.h"
#include "tools/output.h"
#include "tools/plot_compare.h"

namespace lamina::cli {

namespace {

constexpr int64_t kMaxCompareWalks = int64_t(1) << 28;

struct CompareCliOptions {
  MaterialArg material;
  int64_t albedo_walks = int64_t(1) << 16;
  int64_t slice_walks = int64_t(1) << 14;
  uint64_t seed = 0;
  ContextArg context;
  bool json = false;
  std::string plot;  // the figure's file, if any
  int size = kFigureDefaultSize;
};

nlohmann::json value_json(const cpu::CompareValue& v) {
  return {{"model", json_rgb(v.model)}, {"reference", json_rgb(v.reference)}, {"std_error", json_rgb(v.std_error)}};
}

void print_text(const cpu::Comparison& c, const CompareCliOptions& o) {
  std::printf("the layered model against the reference solver (%lld walks per albedo, %lld per BRDF point)\n",
              static_cast<long long>(o.albedo_walks), static_cast<long long>(o.slice_walks));
  std::printf(
      "directional albedo:\n  theta  model (R G B)            reference (R G B)        +- standard error"
      "          relative error\n");
  for (const cpu::AlbedoComparison& row : c.albedo) {
    const cpu::CompareValue& v = row.albedo;
    std::printf("  %5g  %7.4f %7.4f %7.4f  %7.4f %7.4f %7.4f  %7.1e %7.1e %7.1e  %6.1f%%\n", row.theta_deg, v.model.r,
                v.model.g, v.model.b, v.reference.r, v.reference.g, v.reference.b, v.std_error.r, v.std_error.g,
                v.std_error.b, 100.0 * row.relative_error);
  }
  std::printf("BRDF slices in the plane of incidence (light every %g degrees from -%g to %g):\n",
              cpu::kCompareLightStep, cpu::kCompareLightLimit, cpu::kCompareLightLimit);
  for (const cpu::SliceComparison& s : c.slices)
    std::printf("  theta_o %2g: RMS relative error %6.1f%%\n", s.theta_o_deg, 100.0 * s.rms_relative_error);
  std::printf("summary: albedo error at most %.1f%% (theta %g); slice RMS errors", 100.0 * c.max_albedo_error,
              c.max_albedo_error_theta_deg);
  for (const cpu::SliceComparison& s : c.slices) std::printf(" %.1f%%", 100.0 * s.rms_relative_error);
  std::printf(" (theta_o");
  for (const cpu::SliceComparison& s : c.slices) std::printf(" %g", s.theta_o_deg);
  std::printf(")\n");
}

void print_json(const cpu::Comparison& c, const CompareCliOptions& o) {
  nlohmann::json albedo = nlohmann::json::array(), slices = nlohmann::json::array();
  for (const cpu::AlbedoComparison& row : c.albedo) {
    nlohmann::json r = value_json(row.albedo);
    r["theta_deg"] = row.theta_deg;
    r["relative_error"] = row.relative_error;
    albedo.push_back(std::move(r));
  }
  for (const cpu::SliceComparison& s : c.slices) {
    nlohmann::json points = nlohmann::json::array();
    for (size_t k = 0; k < s.f.size(); ++k) {
      nlohmann::json p = value_json(s.f[k]);
      p["theta_i_deg"] = s.theta_i_deg[k];
      points.push_back(std::move(p));
    }
    slices.push_back({{"theta_o_deg", s.theta_o_deg}, {"rms_relative_error", s.rms_relative_error}, {"f", points}});
  }
  nlohmann::json report{{"albedo", albedo},
                        {"slices", slices},
                        {"max_albedo_error", c.max_albedo_error},
                        {"max_albedo_error_theta_deg", c.max_albedo_error_theta_deg},
                        {"albedo_walks", o.albedo_walks},
                        {"slice_walks", o.slice_walks},
                        {"seed", o.seed}};
  std::cout << report.dump() << "\n";
}

int run_compare(const CompareCliOptions& o) {
  for (auto [name, walks] : {std::pair{"--albedo-walks", o.albedo_walks}, std::pair{"--slice-walks", o.slice_walks}})
    if (walks < 1 || walks > kMaxCompareWalks) {
      std::cerr << "lamina: " << name << ": " << walks << " is outside [1, " << kMaxCompareWalks << "]\n";
      return kExitInvalid;
    }
  const std::optional<ShadingContext> ctx = parse_context(o.context);
  if (!ctx) return kExitInvalid;
  FigureFile figure;
  if (!o.plot.empty())
    if (int code = prepare_figure("--plot", o.plot, o.size, figure); code != kExitOk) return code;
  std::optional<cpu::Evaluator> evaluator;
  if (int code = load_material(o.material, evaluator); code != kExitOk) return code;
  if (!o.plot.empty())
    if (int code = check_outputs({figure.path}); code != kExitOk) return code;  // before the walks
  const cpu::ShadingPoint point = evaluator->bind(*ctx);
  if (int code = refuse_tilted(o.material, *evaluator, point); code != kExitOk) return code;
  const cpu::Comparison c = cpu::compare_to_reference(point, {o.albedo_walks, o.slice_walks, o.seed});
  if (!o.plot.empty()) {
    plot::Canvas canvas = figure_canvas(figure);
    const plot::ComparisonSource source{o.material.file, ctx->uv, o.albedo_walks, o.slice_walks};
    if (std::string why = plot::draw_comparison(canvas, *evaluator, c, source, figure.fonts); !why.empty()) {
      print_problem("cannot draw the labels with " + figure.fonts.regular + ": " + why);
      return kExitIo;
    }
    if (int code = write_figure(canvas, figure, "lamina compare of " + evaluator->program().name); code != kExitOk)
      return code;
  }
  if (o.json)
    print_json(c, o);
  else
    print_text(c, o);
  return kExitOk;
}

}  // namespace

void add_compare(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<CompareCliOptions>();
  auto* cmd = app.add_subcommand("compare", "The layered model against the reference solver: albedo and BRDF slices");
  add_material_options(*cmd, o->material);
  cmd->add_option("--albedo-walks", o->albedo_walks, "reference walks per albedo angle")->capture_default_str();
  cmd->add_option("--slice-walks", o->slice_walks, "reference walks per BRDF point")->capture_default_str();
  cmd->add_option("--seed", o->seed, "mixed into the reference's seeds")->capture_default_str();
  add_context_options(*cmd, o->context);
  cmd->add_flag("--json", o->json, "print every value, its reference and the errors as JSON");
  cmd->add_option("--plot", o->plot,
                  "also draw the comparison into this image (e.g. compare.png): the slices of lamina plot with the "
                  "reference's points, beside the directional albedo");
  cmd->add_option("--size", o->size, "the figure's width in pixels; the height is half of it")->capture_default_str();
  cmd->footer(
      "Albedo at 0 to 89 degrees, and f in the plane of incidence for views at 0, 30, 60 and 80 degrees with the "
      "light every 5 degrees (positive angles on the mirror side). A channel's relative error is "
      "|model - reference| / reference, counted against 0.01 where the reference is darker; a slice's error is the "
      "root mean square of its points' relative errors in luminance (against 0.001 / sr where darker).");
  cmd->callback([o, &runner] { runner = [o] { return run_compare(*o); }; });
}

}  // namespace lamina::cli
