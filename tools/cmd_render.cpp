// lamina render SCENE.json -o OUT.png|OUT.exr: the scene (or a material file's sample sheet) path
// traced with lamina's own eval, sample and pdf at every hit (tools/render/path_tracer.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "graph/image_codec.h"
#include "tools/commands.h"
#include "tools/figure_file.h"
#include "tools/progress.h"
#include "tools/render/display.h"
#include "tools/render/path_tracer.h"

namespace lamina::cli {

namespace {

constexpr int kMaxRenderSide = 16384;
constexpr int kMaxRenderSamples = 1 << 20;
constexpr int kMaxRenderDepth = 1024;
constexpr double kMaxRenderExposure = 64.0;
constexpr double kMaxRenderTime = 7.0 * 24.0 * 3600.0;  // a week

struct RenderCliOptions {
  std::string input;
  std::string output;
  std::string camera;
  int width = 480;
  int height = 0;  // from the camera's aspect
  int samples = 16;
  bool samples_given = false;
  double time = 0.0;
  uint64_t seed = 0;
  int threads = 0;
  int max_depth = 8;
  double exposure = 0.0;
  std::string tone_map = "clip";
  std::string estimator = "mis";
  bool aovs = false;
  bool stats = false;
  int columns = 4;
  InputOptions input_options;
};

int run_render(const RenderCliOptions& o) {
  auto refuse = [](const std::string& text) {
    print_problem(text);
    return kExitInvalid;
  };
  if (o.width < 1 || o.width > kMaxRenderSide) return refuse("--width: expected 1 to 16384 pixels");
  if (o.height < 0 || o.height > kMaxRenderSide) return refuse("--height: expected 1 to 16384 pixels, or 0");
  if (o.samples < 1 || o.samples > kMaxRenderSamples) return refuse("--spp: expected 1 to 1048576 samples per pixel");
  if (!(o.time >= 0.0 && o.time <= kMaxRenderTime))
    return refuse("--time: expected 0 (none) to " + std::to_string(int(kMaxRenderTime)) + " seconds");
  if (o.max_depth < 1 || o.max_depth > kMaxRenderDepth) return refuse("--max-depth: expected 1 to 1024 surfaces");
  if (o.threads < 0 || o.threads > 1024) return refuse("--threads: expected 0 (one per core) to 1024");
  if (!(std::abs(o.exposure) <= kMaxRenderExposure)) return refuse("--exposure: expected -64 to 64 stops");
  const std::string output_format = image_format(o.output);
  const bool exr = output_format == "exr";
  try {
    if (output_format.empty() || !image_codec().writes(output_format))
      return refuse("-o: cannot tell an image format from '" + o.output + "' (name the file e.g. render.png or .exr)");
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  }
  if (o.aovs && !exr) return refuse("--aovs: the albedo and normal layers need an .exr output");

  Scene scene;
  Diagnostics diagnostics;
  if (int code = read_scene_input(o.input, o.input_options, o.columns, scene, diagnostics); code != kExitOk)
    return code;
  const Camera* camera = diagnostics.ok() ? render::check_renderable(scene, o.camera, diagnostics) : nullptr;
  if (!print_diagnostics(diagnostics)) return kExitInvalid;
  if (int code = check_outputs({o.output}); code != kExitOk) return code;  // before the rendering

  render::RenderOptions options;
  options.width = o.width;
  options.height = o.height > 0 ? o.height : std::max(1, int(std::lround(double(o.width) / camera->aspect)));
  if (options.height > kMaxRenderSide) return refuse("the camera's aspect makes the image taller than 16384 pixels");
  options.samples = o.time > 0.0 && !o.samples_given ? kMaxRenderSamples : o.samples;
  options.time_budget = o.time;
  options.seed = o.seed;
  options.threads = o.threads;
  options.max_depth = o.max_depth;
  options.aovs = o.aovs;
  options.estimator = o.estimator == "light"  ? render::Estimator::LightSampling
                      : o.estimator == "brdf" ? render::Estimator::BrdfSampling
                                              : render::Estimator::Mis;
  Progress progress;
  options.progress = [&progress](double done) { progress(done); };

  render::RenderResult image;
  const auto start = std::chrono::steady_clock::now();
  try {
    Diagnostics warnings;
    const render::RenderScene prepared(scene, o.input_options.policy_for(o.input), &warnings);
    print_diagnostics(warnings);
    image = render::render(prepared, *camera, options);
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  } catch (const Error& e) {
    for (const auto& d : e.diagnostics()) std::cerr << format(d) << "\n";
    return kExitInvalid;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const float scale = float(std::exp2(camera->exposure + o.exposure));
  const size_t pixels = image.radiance.size();
  const int channels = o.aovs ? 9 : 3;
  std::vector<float> data(pixels * size_t(channels));
  for (size_t i = 0; i < pixels; ++i) {
    float* p = &data[i * size_t(channels)];
    const glm::vec3 c =
        exr ? image.radiance[i] * scale
            : render::display_srgb(image.radiance[i], scale,
                                   o.tone_map == "reinhard" ? render::ToneMap::Reinhard : render::ToneMap::Clip);
    for (int k = 0; k < 3; ++k) p[k] = c[k];
    if (o.aovs)
      for (int k = 0; k < 3; ++k) {
        p[3 + k] = image.albedo[i][k];
        p[6 + k] = image.normal[i][k];
      }
  }
  const FloatPixels view{data.data(), image.width, image.height, channels};
  const std::string description = "lamina render of " + std::filesystem::path(o.input).filename().string() + ", " +
                                  std::to_string(image.samples) + " spp, seed " + std::to_string(o.seed);
  std::vector<unsigned char> encoded;
  std::string why;
  if (exr) {
    std::vector<std::string> names{"R", "G", "B"};
    if (o.aovs) names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z"});
    why = image_codec().encode_linear(output_format, view, names, {{"ImageDescription", description}}, encoded);
  } else {
    why = image_codec().encode(output_format, view, {{"oiio:ColorSpace", "sRGB"}, {"ImageDescription", description}},
                               encoded);
  }
  if (!why.empty()) {
    print_problem("cannot encode " + o.output + ": " + why);
    return kExitIo;
  }
  if (int code = write_outputs({{o.output, std::string(encoded.begin(), encoded.end())}}); code != kExitOk) return code;
  if (o.time > 0.0 && !o.stats) std::printf("%d samples per pixel in %.2f s\n", image.samples, seconds);
  if (o.stats) {
    const double paths = double(pixels) * double(image.samples);
    const double rays = double(image.camera_rays + image.shadow_rays + image.bounce_rays);
    std::printf("%d x %d, %d spp in %.2f s: %.3g samples/s, %.3g rays/s (camera %llu, bounce %llu, shadow %llu)\n",
                image.width, image.height, image.samples, seconds, paths / seconds, rays / seconds,
                static_cast<unsigned long long>(image.camera_rays), static_cast<unsigned long long>(image.bounce_rays),
                static_cast<unsigned long long>(image.shadow_rays));
  }
  return kExitOk;
}

}  // namespace

void add_render(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<RenderCliOptions>();
  auto* cmd = app.add_subcommand(
      "render", "Path trace a scene, or a material file as a sheet of spheres, with lamina's materials");
  cmd->add_option("input", o->input, "a scene file, or a material file")->required();
  cmd->add_option("-o,--output", o->output,
                  "the image: .exr is linear half float (radiance times the exposure); .png and other formats are "
                  "sRGB after the exposure and the tone map")
      ->required();
  cmd->add_option("--camera", o->camera, "the scene camera to render from; default: the first");
  cmd->add_option("--width", o->width, "image width in pixels")->capture_default_str();
  cmd->add_option("--height", o->height, "image height in pixels; 0: from the camera's aspect")->capture_default_str();
  cmd->add_option("--spp", o->samples, "samples per pixel; with --time, the most it may take (default: no limit)")
      ->capture_default_str();
  cmd->add_option("--time", o->time,
                  "seconds of path tracing: passes of samples until the next would not fit (at least one sample). "
                  "An image of N samples equals --spp N bit for bit; N is printed and written in the image's "
                  "description")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "the random sequence: the same seed gives the same image, whatever --threads")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "worker threads; 0: one per core")->capture_default_str();
  cmd->add_option("--max-depth", o->max_depth, "surfaces a path may meet")->capture_default_str();
  cmd->add_option(
         "--exposure", o->exposure,
         "stops added to the camera's exposure: the image's radiance is multiplied by 2^(camera exposure + EXPOSURE)")
      ->capture_default_str();
  cmd->add_option("--tone-map", o->tone_map, "clip (linear, clipped at 1) or reinhard (x / (1 + x) per channel)")
      ->check(CLI::IsMember({"clip", "reinhard"}))
      ->capture_default_str();
  cmd->add_option("--estimator", o->estimator,
                  "mis (light and BRDF sampling with the power heuristic), light (light sampling only) or brdf "
                  "(BRDF sampling only): the same image in the limit, with different noise")
      ->check(CLI::IsMember({"mis", "light", "brdf"}))
      ->capture_default_str();
  cmd->add_flag("--aovs", o->aovs, "also write the first hit's albedo and normal as EXR layers, for denoisers");
  cmd->add_flag("--stats", o->stats, "print the time, samples and rays per second");
  add_sheet_columns_option(*cmd, o->columns);
  add_input_options(*cmd, o->input_options);
  cmd->footer(
      "Lights keep KHR_lights_punctual's units (candela for point and spot lights, lux for directional ones) and "
      "the image holds radiance in the matching units: a white Lambertian surface facing a 1 lux light shows 1/pi. "
      "Nothing is written for an invalid scene; the image is complete or absent.");
  cmd->callback([o, cmd, &runner] {
    o->samples_given = cmd->count("--spp") > 0;
    runner = [o] { return run_render(*o); };
  });
}

}  // namespace lamina::cli
