// lamina preview MATERIAL.json -o ball.png: a material on a sphere resting on a checkered floor in
// a studio environment, path traced (tools/render/preview_scene.h); with --compare, every material
// given side by side, each labelled with its name.
#include <cmath>
#include <iostream>

#include "graph/image_codec.h"
#include "tools/commands.h"
#include "tools/figure_file.h"
#include "tools/plot_canvas.h"
#include "tools/plot_text.h"
#include "tools/progress.h"
#include "tools/render/display.h"
#include "tools/render/path_tracer.h"
#include "tools/render/preview_scene.h"

namespace lamina::cli {

namespace {

constexpr int64_t kMaxSheetSide = 16384;
constexpr int kMinPreviewSize = 16, kMaxPreviewSize = 4096;
constexpr int kMaxPreviewSamples = 65536;
constexpr double kMaxPreviewExposure = 64.0;

struct PreviewOptions {
  std::vector<std::string> inputs;
  std::string output;
  std::string material;
  bool compare = false;
  int size = 256;
  int samples = 32;
  uint64_t seed = 0;
  int threads = 0;
  double exposure = 0.0;
  std::string tone_map = "reinhard";
  std::string environment;
  double environment_rotation = 0.0;
  int columns = 6;
  InputOptions input_options;
};

struct Shown {
  std::filesystem::path file;
  Document document;
  std::string material;
};

int run_preview(const PreviewOptions& o) {
  auto refuse = [](const std::string& text) {
    print_problem(text);
    return kExitInvalid;
  };
  const std::string sizes = std::to_string(kMinPreviewSize) + " to " + std::to_string(kMaxPreviewSize);
  if (o.size < kMinPreviewSize || o.size > kMaxPreviewSize) return refuse("--size: expected " + sizes + " pixels");
  if (o.samples < 1 || o.samples > kMaxPreviewSamples)
    return refuse("--spp: expected 1 to " + std::to_string(kMaxPreviewSamples) + " samples per pixel");
  if (!(std::abs(o.exposure) <= kMaxPreviewExposure)) return refuse("--exposure: expected -64 to 64 stops");
  if (!(std::abs(o.environment_rotation) <= 360.0))
    return refuse("--environment-rotation: expected -360 to 360 degrees");
  const std::string format = image_format(o.output);
  try {
    if (format.empty() || !image_codec().writes(format))
      return refuse("-o: cannot tell an image format from '" + o.output + "' (name the file e.g. preview.png)");
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  }

  std::vector<Shown> shown;
  int code = for_each_checked_file(o.inputs, o.input_options, [&](const std::filesystem::path& file, CheckedFile& c) {
    if (!print_diagnostics(c.diagnostics)) return false;
    bool found = o.material.empty();
    for (const Material& m : c.document.materials)
      if (o.material.empty() || m.name == o.material) {
        shown.push_back({file, c.document, m.name});
        found = true;
      }
    if (!found) {
      std::vector<std::string> names;
      for (const Material& m : c.document.materials) names.push_back(m.name);
      const std::string close = closest_match(o.material, names);
      print_problem(file.string() + ": no material called '" + o.material + "'" +
                    (close.empty() ? "" : "; did you mean '" + close + "'?"));
    }
    return found;
  });
  if (code != kExitOk) return code;
  if (shown.empty()) return refuse("no material to show");
  if (shown.size() > 1 && !o.compare)
    return refuse(std::to_string(shown.size()) +
                  " materials given: name one with --material, or show them side by side with --compare");

  render::Environment environment;
  try {
    environment = o.environment.empty()
                      ? render::Environment(render::studio_environment(), glm::vec3(1.0f))
                      : render::Environment(load_image_file(o.environment, false, o.input_options.max_image_pixels),
                                            glm::vec3(1.0f));
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  } catch (const ImageError& e) {
    return refuse("--environment: '" + o.environment + "' is not a readable image: " + e.what());
  }
  environment.set_rotation(float(o.environment_rotation));
  plot::Fonts fonts;
  if (o.compare) {
    fonts = plot::find_fonts();
    if (!plot::fonts_usable(fonts)) {
      print_problem(
          "no font for the labels: DejaVuSans.ttf was not found (on Debian: apt-get install "
          "fonts-dejavu-core)");
      return kExitIo;
    }
  }
  if (int c = check_outputs({o.output}); c != kExitOk) return c;  // before the rendering

  // Tiles in rows of --columns, each with a label strip under it when comparing.
  const int count = int(shown.size());
  const int columns = o.compare ? std::min(count, std::max(1, o.columns)) : 1;
  const int rows = (count + columns - 1) / columns;
  const int label = o.compare ? std::max(14, o.size / 9) : 0;
  if (int64_t(columns) * o.size > kMaxSheetSide || int64_t(rows) * (o.size + label) > kMaxSheetSide)
    return refuse("the sheet of " + std::to_string(count) + " previews of " + std::to_string(o.size) +
                  " pixels would be more than " + std::to_string(kMaxSheetSide) +
                  " pixels a side: lower --size or change --columns");
  plot::Canvas canvas(columns * o.size, rows * (o.size + label), glm::vec3(0.12f));
  plot::Text text(canvas, fonts);
  Progress progress;
  const float scale = float(std::exp2(o.exposure));
  const auto tone = o.tone_map == "clip" ? render::ToneMap::Clip : render::ToneMap::Reinhard;
  for (int i = 0; i < count; ++i) {
    const Shown& s = shown[size_t(i)];
    render::RenderResult image;
    try {
      const Scene scene = render::preview_scene(s.document, s.file, s.material);
      render::RenderScene prepared(scene, scene.policy);
      prepared.set_environment(environment);
      render::RenderOptions options;
      options.width = options.height = o.size;
      options.samples = o.samples;
      options.seed = o.seed;
      options.threads = o.threads;
      options.progress = [&](double done) { progress((double(i) + done) / double(count)); };
      image = render::render(prepared, scene.cameras.front(), options);
    } catch (const IoError& e) {
      print_problem(e.what());
      return kExitIo;
    }
    const int x0 = (i % columns) * o.size, y0 = (i / columns) * (o.size + label);
    for (int y = 0; y < o.size; ++y)
      for (int x = 0; x < o.size; ++x)
        canvas.at(x0 + x, y0 + y) =
            render::display_srgb(image.radiance[size_t(y) * size_t(o.size) + size_t(x)], scale, tone);
    if (o.compare)
      text.draw(x0 + o.size / 2, y0 + o.size + label * 3 / 4, s.material, label * 2 / 3, glm::vec3(0.9f), 0, false,
                o.size - 4);
  }
  if (!text.error().empty()) {
    print_problem("cannot draw the labels with " + fonts.regular + ": " + text.error());
    return kExitIo;
  }
  std::vector<unsigned char> encoded;
  const std::string why = plot::encode_image(
      canvas, format, {{"oiio:ColorSpace", "sRGB"}, {"ImageDescription", "lamina preview"}}, encoded);
  if (!why.empty()) {
    print_problem("cannot encode " + o.output + ": " + why);
    return kExitIo;
  }
  return write_outputs({{o.output, std::string(encoded.begin(), encoded.end())}});
}

}  // namespace

void add_preview(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<PreviewOptions>();
  auto* cmd = app.add_subcommand(
      "preview",
      "Show a material on a sphere on a checkered floor in a studio light, path traced; --compare for several");
  cmd->add_option("inputs", o->inputs, "material files (directories: every *.json under them)")->required();
  cmd->add_option("-o,--output", o->output, "the image, e.g. ball.png")->required();
  cmd->add_option("--material", o->material, "the material to show, in a file with several");
  cmd->add_flag("--compare", o->compare, "show every material given side by side, labelled");
  cmd->add_option("--columns", o->columns, "previews per row with --compare")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--size", o->size, "pixels a side of each preview")->capture_default_str();
  cmd->add_option("--spp", o->samples, "samples per pixel")->capture_default_str();
  cmd->add_option("--seed", o->seed, "the random sequence (the same seed gives the same image)")->capture_default_str();
  cmd->add_option("--threads", o->threads, "worker threads; 0: one per core")->capture_default_str();
  cmd->add_option("--exposure", o->exposure, "stops: radiance is multiplied by 2^EXPOSURE")->capture_default_str();
  cmd->add_option("--tone-map", o->tone_map, "reinhard (x / (1 + x) per channel) or clip")
      ->check(CLI::IsMember({"clip", "reinhard"}))
      ->capture_default_str();
  cmd->add_option("--environment", o->environment,
                  "an equirectangular image to light the preview with instead of the studio (radiance as stored)");
  cmd->add_option("--environment-rotation", o->environment_rotation,
                  "degrees to turn the environment (the studio or --environment) about the up axis; 90 brings "
                  "the light from +x to -z")
      ->capture_default_str();
  add_input_options(*cmd, o->input_options);
  cmd->callback([o, &runner] { runner = [o] { return run_preview(*o); }; });
}

}  // namespace lamina::cli
