// Cost of the generated layered GLSL against a single Torrance-Sparrow lobe on llvmpipe, rendered
// at the same resolution in one run (the papers' GPU ratio was 2.3 to 4.2).
// Run: bash tools/run_bench.sh (prints the ratios), or build/release/tests/glsl/lamina_glsl_bench.
//
// Each material is drawn as the --shader sphere wrapper (the preview of nodes/kernels/preview.glsl)
// at 1024 x 1024 in two forms: `light`, the directional light alone (an eval per subsample, 16 per
// pixel, as the papers' renderings), and `sphere`, the wrapper as shipped (the light plus 64
// importance-sampled sky directions per pixel).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "glsl/gl_runner.h"
#include "glsl/material_pass.h"
#include "graph/compile.h"
#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/load.h"
#include "graph/model.h"

namespace {

using namespace lamina;

constexpr int kSize = 1024;

// The CPU benchmark's single lobe: the Car Paint's aluminium base without its varnish.
const char* kSingleLobe = R"({"format": 1, "materials": [{"name": "single_lobe", "surface": "@metal", "nodes": [
    {"id": "metal", "type": "substrate/conductor", "metal": "aluminium", "roughness_deg": 12.0}]}]})";

// An example in its own (the default) model, or with the suffix "_weidlich_wilkie" in the seeds'.
Program program(const std::string& name) {
  if (name == "single_lobe") {
    CheckedFile checked = check_text(kSingleLobe, "bench.json");
    return compile(*checked.graphs[0], "bench.json");
  }
  const std::string suffix = "_weidlich_wilkie";
  const bool faithful = name.size() > suffix.size() && name.ends_with(suffix);
  const std::string example = faithful ? name.substr(0, name.size() - suffix.size()) : name;
  std::string file = std::string(LAMINA_SOURCE_DIR) + "/examples/materials/" + example + ".json";
  CheckedFile checked = check_file(file);
  Program p = compile(*checked.graphs[0], file);
  if (faithful) p.model = model_number("weidlich_wilkie");
  return p;
}

gltest::Runner& runner() {
  static std::unique_ptr<gltest::Runner> r = [] {
    std::string error;
    auto made = gltest::Runner::create(gltest::Api::Desktop, &error);
    if (!made) {
      std::fprintf(stderr, "no GL context: %s\n", error.c_str());
      std::exit(1);
    }
    return made;
  }();
  return *r;
}

// The sphere shader of `name` at kSize x kSize, the viewport set through a one-member block.
gltest::Pass pass(const std::string& name, bool ambient) {
  std::vector<Program> programs{program(name)};
  glsl::Options options;
  options.shader = glsl::Options::Shader::Sphere;
  const glsl::Module module = glsl::generate(programs, options);
  std::string source = module.source;
  // Edits of the wrapper's text, each of which must find what it replaces.
  auto edit = [&](const std::string& from, const std::string& to) {
    if (source.find(from) == std::string::npos) {
      std::fprintf(stderr, "the sphere shader has no '%s' to replace\n", from.c_str());
      std::exit(1);
    }
    source = glsl::replace_all(source, from, to);
  };
  const std::string sky = "const vec3 lamina_ambient_radiance = vec3(LAMINA_PREVIEW_AMBIENT);";
  if (!ambient) edit(sky, "const vec3 lamina_ambient_radiance = vec3(0.0f);");
  // The harness sets uniforms through a block; the wrapper's lamina_viewport becomes a constant.
  edit("uniform vec2 lamina_viewport;", "const vec2 lamina_viewport = vec2(" + std::to_string(kSize) + ".0f);");
  gltest::Pass p;
  p.fragment_source = source;
  p.width = kSize;
  p.height = kSize;
  test::bind_material(p, programs[0], module, module.materials.front(), false);  // the table, if any
  return p;
}

void BM_glsl(benchmark::State& state, const std::string& name, bool ambient) {
  gltest::Pass p = pass(name, ambient);
  for (auto _ : state) {
    std::string error;
    double seconds = runner().time_pass(p, 4, &error);
    if (seconds < 0.0) {
      state.SkipWithError(error.c_str());
      break;
    }
    state.SetIterationTime(seconds);
  }
  state.counters["pixels_per_second"] =
      benchmark::Counter(double(kSize) * kSize, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

#define LAMINA_GLSL_BENCH(name)                          \
  BENCHMARK_CAPTURE(BM_glsl, light_##name, #name, false) \
      ->UseManualTime()                                  \
      ->Iterations(8)                                    \
      ->Unit(benchmark::kMillisecond);                   \
  BENCHMARK_CAPTURE(BM_glsl, sphere_##name, #name, true)->UseManualTime()->Iterations(8)->Unit(benchmark::kMillisecond)

LAMINA_GLSL_BENCH(single_lobe);
LAMINA_GLSL_BENCH(car_paint);
LAMINA_GLSL_BENCH(house_paint);
LAMINA_GLSL_BENCH(car_paint_weidlich_wilkie);
LAMINA_GLSL_BENCH(house_paint_weidlich_wilkie);

BENCHMARK_MAIN();
