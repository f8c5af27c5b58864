// lamina plot FILE --material NAME -o OUT.png: a picture of a material for people. Four in-plane
// BRDF slices (log10 f per channel against the light's angle, for views at 0, 30, 60 and 80
// degrees, at one uv) beside a sphere lit by one directional light and a dim uniform sky
// (tools/plot_figure.h). Deterministic for the same input.
#include <iostream>

#include "nodes/kernels/kernels.h"
#include "tools/commands.h"
#include "tools/figure_file.h"
#include "tools/material_arg.h"
#include "tools/output.h"
#include "tools/plot_figure.h"

namespace lamina::cli {

namespace {

// The radiance of the uniform sky around the sphere: by default the preview's own, which the GLSL
// sphere shader uses too.
const float kDefaultAmbient = kernels::LAMINA_PREVIEW_AMBIENT;
constexpr float kMaxAmbient = 10.0f;

struct PlotOptions {
  MaterialArg material;
  std::string output;
  int size = kFigureDefaultSize;
  std::string uv = "0,0";
  float ambient = kDefaultAmbient;
};

int run_plot(const PlotOptions& o) {
  if (!(o.ambient >= 0.0f && o.ambient <= kMaxAmbient)) {
    std::cerr << "lamina: --ambient: " << o.ambient << " is outside [0, " << kMaxAmbient
              << "] (the radiance of the uniform sky; 0 for the light alone)\n";
    return kExitInvalid;
  }
  auto uv = parse_numbers("--uv", o.uv, 2);
  if (!uv) return kExitInvalid;
  FigureFile figure;
  if (int code = prepare_figure("-o", o.output, o.size, figure); code != kExitOk) return code;

  std::optional<cpu::Evaluator> evaluator;
  if (int code = load_material(o.material, evaluator); code != kExitOk) return code;
  if (int code = check_outputs({figure.path}); code != kExitOk) return code;  // before the drawing

  plot::Canvas canvas = figure_canvas(figure);
  if (std::string why = plot::draw_figure(canvas, *evaluator, o.material.file, figure.fonts,
                                          glm::vec2((*uv)[0], (*uv)[1]), o.ambient);
      !why.empty()) {
    print_problem("cannot draw the labels with " + figure.fonts.regular + ": " + why);
    return kExitIo;
  }
  return write_figure(canvas, figure, "lamina plot of " + evaluator->program().name);
}

}  // namespace

void add_plot(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<PlotOptions>();
  auto* cmd = app.add_subcommand("plot", "Draw a material: four in-plane BRDF slices beside a lit sphere");
  add_material_options(*cmd, o->material);
  cmd->add_option("-o,--output", o->output, "the image to write, e.g. plot.png (any format OpenImageIO writes)")
      ->required();
  cmd->add_option("--size", o->size, "image width in pixels; the height is half of it")->capture_default_str();
  cmd->add_option("--uv", o->uv, "texture coordinates U,V of the slices (textured materials)")->capture_default_str();
  cmd->add_option("--ambient", o->ambient,
                  "radiance of the uniform sky around the sphere, in [0, 10]; 0 for the directional light alone")
      ->capture_default_str();
  cmd->footer(
      "The slices show log10 f per channel in the plane of incidence, against the light's angle theta_i from the "
      "normal (positive on the mirror side), for views at 0, 30, 60 and 80 degrees, at one uv. The sphere is lit by "
      "one directional light from the upper left (irradiance pi: a white Lambertian surface facing it shows 1) and a "
      "dim uniform sky (--ambient; a surface reflects it as ambient times its directional albedo, so smooth metals "
      "show their colour away from the highlight), seen orthographically; uv follows longitude and latitude. Nothing "
      "is written for an invalid file.");
  cmd->callback([o, &runner] { runner = [o] { return run_plot(*o); }; });
}

}  // namespace lamina::cli
