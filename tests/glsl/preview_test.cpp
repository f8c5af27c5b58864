// One preview: the sphere shader of `lamina glsl --shader sphere`, run on Mesa llvmpipe, draws the
// picture lamina plot's sphere shows (cpu::render_preview), pixel by pixel, since both follow
// nodes/kernels/preview.glsl and differ only in who evaluates the material.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "glsl/gl_runner.h"
#include "glsl/gl_test_support.h"
#include "glsl/material_pass.h"
#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu/image.h"
#include "graph/cpu/preview.h"
#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/load.h"
#include "nodes/kernels/kernels.h"

using namespace lamina;
using glm::vec3;
using glm::vec4;

namespace {

// Large enough for the silhouette, the highlight and a few checker squares; llvmpipe draws it at
// once.
constexpr int kSize = 48;
// Display values (sRGB-encoded, unquantised) may differ by this much: one level of an 8-bit file.
constexpr float kTolerance = 1.0f / 255.0f;

struct Case {
  const char* file;  // under examples/materials
  glsl::Target target;
  bool uniforms;
};

// A layered material, a procedural texture and an image texture, across the targets and modes.
const Case kCases[] = {
    {"car_paint.json", glsl::Target::Glsl330, false},
    {"checker_tiles.json", glsl::Target::Es300, true},
    {"patina_map_copper.json", glsl::Target::Glsl450, false},
};

#ifdef LAMINA_SANITIZED
constexpr size_t kCasesRun = 1;
#else
constexpr size_t kCasesRun = std::size(kCases);
#endif

// The sphere shader's picture, row 0 at the top as render_preview's, sRGB-encoded as it writes it.
std::vector<vec3> gpu_preview(const Program& program, const Case& c) {
  glsl::Options options;
  options.target = c.target;
  options.uniforms = c.uniforms;
  options.shader = glsl::Options::Shader::Sphere;
  glsl::Module module = glsl::generate(std::span<const Program>(&program, 1), options);
  const glsl::MaterialInterface& mi = module.materials.front();
  // The runner sets uniforms through a block; the viewport becomes a constant.
  const std::string viewport = "uniform vec2 lamina_viewport;";
  REQUIRE(module.source.find(viewport) != std::string::npos);
  gltest::Pass pass;
  pass.fragment_source = glsl::replace_all(module.source, viewport,
                                           "const vec2 lamina_viewport = vec2(" + std::to_string(kSize) + ".0f);");
  pass.width = kSize;
  pass.height = kSize;
  test::bind_material(pass, program, module, mi, c.uniforms);
  std::vector<std::vector<vec4>> out;
  std::string error;
  bool ran = test::shared_runner(c.target == glsl::Target::Es300 ? gltest::Api::Es : gltest::Api::Desktop)
                 .run(pass, &out, &error);
  INFO(error);
  REQUIRE(ran);
  std::vector<vec3> picture(size_t(kSize) * kSize);
  for (int y = 0; y < kSize; ++y)  // GL's row 0 is the bottom one
    for (int x = 0; x < kSize; ++x)
      picture[size_t(kSize - 1 - y) * kSize + size_t(x)] = vec3(out[0][size_t(y) * kSize + size_t(x)]);
  return picture;
}

std::vector<vec3> cpu_preview(const cpu::Evaluator& evaluator, float ambient) {
  std::vector<vec3> picture = cpu::render_preview(evaluator, kSize, kSize, ambient);
  for (vec3& p : picture) p = kernels::srgb_from_linear(p);
  return picture;
}

struct Difference {
  float worst = 0.0f;
  size_t pixel = 0, over = 0;  // where the worst is; how many exceed kTolerance
};

Difference compare(const std::vector<vec3>& a, const std::vector<vec3>& b) {
  Difference d;
  for (size_t i = 0; i < a.size(); ++i) {
    vec3 e = glm::abs(a[i] - b[i]);
    float m = std::isfinite(e.x + e.y + e.z) ? std::max({e.x, e.y, e.z}) : INFINITY;
    if (m > kTolerance) ++d.over;
    if (m > d.worst) {
      d.worst = m;
      d.pixel = i;
    }
  }
  return d;
}

}  // namespace

TEST_CASE("preview: the GLSL sphere shader draws lamina plot's sphere within one 8-bit level, but at texture edges") {
  // Under the sanitisers, which watch lamina's code and not llvmpipe's (most of the cost), the first
  // case alone.
  for (const Case& c : std::span<const Case>(kCases, kCasesRun)) {
    CAPTURE(c.file);
    CAPTURE(glsl::target_name(c.target));
    CAPTURE(c.uniforms);
    Program program = test::example_program(c.file);
    cpu::Evaluator evaluator(program);
    std::vector<vec3> gpu = gpu_preview(program, c);
    std::vector<vec3> cpu = cpu_preview(evaluator, kernels::LAMINA_PREVIEW_AMBIENT);
    REQUIRE(gpu.size() == cpu.size());

    Difference same = compare(gpu, cpu);
    std::printf("%s (%s%s): worst difference %.3g of an 8-bit level at pixel (%zu, %zu)\n", c.file,
                glsl::target_name(c.target), c.uniforms ? ", uniforms" : "", double(same.worst * 255.0f),
                same.pixel % kSize, same.pixel / kSize);
    // llvmpipe's atan and acos differ from the C library's by a few ulps, and so the uv: where a
    // texture has a hard edge (the patina mask thresholded by a remap) a pixel may land on its other
    // side. Such pixels are a few in the whole picture; a wrong formula differs almost everywhere.
    CHECK(same.over <= gpu.size() / 200);

    // The comparison sees what matters: the sphere is drawn (most pixels differ from the
    // background), and the same material without the sky, which only the sky's estimate
    // separates from the real preview, fails it.
    const vec3 background = kernels::LAMINA_PREVIEW_BACKGROUND;
    size_t drawn = 0;
    for (const vec3& p : gpu) drawn += glm::length(p - background) > 0.05f ? 1 : 0;
    CHECK(drawn > gpu.size() / 2);
    CHECK(compare(gpu, cpu_preview(evaluator, 0.0f)).over > gpu.size() / 4);
  }
}
