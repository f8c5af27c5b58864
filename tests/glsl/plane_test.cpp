// The plane shader of `lamina glsl --shader plane`, run on Mesa llvmpipe: glitter on a plane that
// recedes to the horizon does not alias. A pixel evaluates the material once, at its centre, with
// the footprint dFdx and dFdy give; drawn at four times the resolution and box-filtered down, the
// same view must agree with it wherever a pixel covers many glitter cells. Point-sampled (footprint
// scale 0), the far plane is noise that no two resolutions agree on, so the check can fail.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "glsl/gl_runner.h"
#include "glsl/gl_test_support.h"
#include "glsl/material_pass.h"
#include "graph/compile.h"
#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/load.h"
#include "nodes/kernels/kernels.h"

using namespace lamina;
using glm::vec3;
using glm::vec4;

namespace {

// The plane at width x height pixels, linear, row 0 at the bottom (GL's), lit by the light alone.
// The plane's uniforms become one std140 block, so that every picture draws the same source: Mesa
// compiles it once and finds it in its shader cache after.
std::vector<vec3> draw_plane(const Program& program, int width, int height, float footprint_scale) {
  glsl::Options options;
  options.shader = glsl::Options::Shader::Plane;
  glsl::Module module = glsl::generate(std::span<const Program>(&program, 1), options);
  REQUIRE(!module.materials.front().block_size);  // the material's constants are inlined
  std::string source = module.source;
  const char* uniforms[] = {"uniform vec2 lamina_viewport;", "uniform float lamina_footprint_scale;",
                            "uniform float lamina_ambient_radiance;"};
  for (const char* uniform : uniforms) {
    REQUIRE(source.find(uniform) != std::string::npos);
    source = glsl::replace_all(source, uniform, "");
  }
  const std::string main = "void main() {";
  REQUIRE(source.find(main) != std::string::npos);
  source.insert(source.find(main),
                "layout(std140) uniform LaminaPlaneView {\n  vec2 lamina_viewport;\n  float lamina_footprint_scale;\n"
                "  float lamina_ambient_radiance;\n};\n\n");
  const float block[4] = {float(width), float(height), footprint_scale, 0.0f};
  gltest::Pass pass;
  pass.fragment_source = source;
  pass.width = width;
  pass.height = height;
  test::bind_material(pass, program, module, module.materials.front(), false);
  pass.uniform_block_name = "LaminaPlaneView";
  pass.uniform_block_data.resize(sizeof(block));
  std::memcpy(pass.uniform_block_data.data(), block, sizeof(block));
  std::vector<std::vector<vec4>> out;
  std::string error;
  const bool ran = test::shared_runner(gltest::Api::Desktop).run(pass, &out, &error);
  INFO(error);
  REQUIRE(ran);
  std::vector<vec3> picture(out[0].size());
  for (size_t i = 0; i < picture.size(); ++i) picture[i] = kernels::srgb_to_linear(vec3(out[0][i]));
  return picture;
}

// v of the plane's point at the centre column of row `row` of a picture `height` pixels high (row 0
// at the bottom), from the camera plane_shader.h describes; negative above the horizon.
double plane_v(double row, int height) {
  const double pitch = 20.0 * M_PI / 180.0, tan_half_fov = std::tan(30.0 * M_PI / 180.0);
  const double ndc = (2.0 * (row + 0.5) - height) / height;
  const double y = std::cos(pitch) + tan_half_fov * ndc * std::sin(pitch);
  const double z = -std::sin(pitch) + tan_half_fov * ndc * std::cos(pitch);
  return z < 0.0 ? y / -z : -1.0;
}

// A row's pixels as the sum of their channels.
std::vector<double> row_sums(const std::vector<vec3>& picture, int width, int row) {
  std::vector<double> sums(static_cast<size_t>(width));
  for (int x = 0; x < width; ++x) {
    const vec3 c = picture[size_t(row) * size_t(width) + size_t(x)];
    sums[size_t(x)] = double(c.x) + double(c.y) + double(c.z);
  }
  return sums;
}

}  // namespace

TEST_CASE("plane: glitter far away converges to its cells' mean, the same at two resolutions") {
  // Aventurine glass: glitter cells of 60 per uv unit over a surface map of 400 (its README row).
  const Program program = test::example_program("aventurine_glass.json");
  constexpr double kGlitterCells = 60.0;
  constexpr int kWidth = 96, kHeight = 64, kFactor = 4;
  // Rows whose coarse pixels span 8 glitter cells or more, so that a fine pixel spans 2 or more:
  // there both pictures filter fully (lamina_voronoi_cell), and they must agree to this share
  // of the row's mean radiance. Measured: at most 1.1%, at the row below the horizon.
  constexpr double kFarCells = 8.0, kTolerance = 0.02;
  double worst_filtered = 0.0, point_sampled_sum = 0.0;
  int far_rows = 0, point_sampled_rows = 0;
  for (float scale : {1.0f, 0.0f}) {
    CAPTURE(scale);
    const std::vector<vec3> coarse = draw_plane(program, kWidth, kHeight, scale);
    const std::vector<vec3> fine = draw_plane(program, kWidth * kFactor, kHeight * kFactor, scale);
    // The fine picture box-filtered to the coarse one's pixels.
    std::vector<vec3> boxed(coarse.size(), vec3(0.0f));
    for (int y = 0; y < kHeight * kFactor; ++y)
      for (int x = 0; x < kWidth * kFactor; ++x)
        boxed[size_t(y / kFactor) * kWidth + size_t(x / kFactor)] +=
            fine[size_t(y) * size_t(kWidth * kFactor) + size_t(x)] / float(kFactor * kFactor);
    for (int y = 0; y + 1 < kHeight; ++y) {
      const double v0 = plane_v(y, kHeight), v1 = plane_v(y + 1, kHeight);
      if (v0 < 0.0 || v1 < 0.0 || (v1 - v0) * kGlitterCells < kFarCells) continue;  // near, or not on the plane
      const std::vector<double> a = row_sums(coarse, kWidth, y), b = row_sums(boxed, kWidth, y);
      double diff = 0.0, mean = 0.0;
      for (int x = 0; x < kWidth; ++x) {
        diff += std::abs(a[size_t(x)] - b[size_t(x)]);
        mean += b[size_t(x)];
      }
      CAPTURE(y);
      REQUIRE(mean > 0.0);
      if (scale > 0.0f) {
        CHECK(diff / mean <= kTolerance);
        worst_filtered = std::max(worst_filtered, diff / mean);
        ++far_rows;
      } else {
        point_sampled_sum += diff / mean;
        ++point_sampled_rows;
      }
    }
  }
  const double mean_point_sampled = point_sampled_sum / std::max(point_sampled_rows, 1);
  MESSAGE(far_rows << " far rows: filtered, the two resolutions differ by at most " << 100.0 * worst_filtered
                   << "% of a row's radiance; point-sampled, by " << 100.0 * mean_point_sampled << "% on average");
  // The plane reaches far enough to test, and the test sees aliasing where there is some.
  CHECK(far_rows >= kHeight / 4);
  CHECK(point_sampled_rows == far_rows);
  CHECK(mean_point_sampled > 10.0 * kTolerance);
}
