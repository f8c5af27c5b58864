#include "tools/plot_sphere.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

#include "graph/cpu/frame.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cli::plot {

namespace {

using glm::vec2;
using glm::vec3;

// The sky's reflection, Evaluator::albedo: for an untextured material, which is isotropic, a table
// over cos(theta_o) of this many intervals, with this many points per lobe...
constexpr int kSkyTableSize = 256;
constexpr int kSkyTablePoints = 256;
// ... and for a textured one once per pixel, with this many.
constexpr int kSkyPixelPoints = 16;

}  // namespace

// An orthographic view down -z of the unit sphere, one directional light from the upper left with
// irradiance pi (a white Lambertian surface facing it shows 1), plus a uniform sky of radiance
// `ambient`, which a surface reflects as ambient times its directional albedo at wo (the albedo is
// the reflection of a uniform unit environment), exposure 1, clipped, sRGB. 4 x 4 samples per
// pixel for the light; the sky's term from a table over cos(theta_o) for untextured materials, else
// once per pixel at its first sample on the sphere. Rows are shared among threads, each pixel
// computed on its own.
void draw_sphere(Canvas& canvas, const cpu::Evaluator& evaluator, Rect area, vec3 background, float ambient) {
  constexpr double kPi = std::numbers::pi;
  const vec3 light = glm::normalize(vec3(-1.0f, 1.0f, 1.0f));
  const vec3 view(0.0f, 0.0f, 1.0f);
  const float irradiance = float(kPi), exposure = 1.0f;
  const int n = 4;
  int diameter = std::min(area.x1 - area.x0, area.y1 - area.y0);
  float radius = 0.5f * float(diameter);
  float cx = 0.5f * float(area.x0 + area.x1), cy = 0.5f * float(area.y0 + area.y1);
  vec3 background_linear = kernels::srgb_to_linear(background);
  std::vector<vec3> sky_table;
  if (ambient > 0.0f && evaluator.program().ops.empty())
    for (int i = 0; i <= kSkyTableSize; ++i) {
      float c = float(i) / float(kSkyTableSize);
      vec3 wo(std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c);
      sky_table.push_back(ambient * evaluator.albedo(ShadingContext{}, wo, kSkyTablePoints));
    }
  auto sky_at = [&](const ShadingContext& ctx, vec3 wo) {
    if (sky_table.empty()) return ambient * evaluator.albedo(ctx, wo, kSkyPixelPoints);
    float t = std::clamp(wo.z, 0.0f, 1.0f) * float(kSkyTableSize);
    int i = std::min(int(t), kSkyTableSize - 1);
    return glm::mix(sky_table[size_t(i)], sky_table[size_t(i + 1)], t - float(i));
  };
  auto shade_row = [&](int y) {
    for (int x = area.x0; x < area.x1; ++x) {
      vec3 sum(0.0f), sky(0.0f);
      bool have_sky = false;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          float sx = (float(x) + (float(i) + 0.5f) / float(n) - cx) / radius;
          float sy = (cy - (float(y) + (float(j) + 0.5f) / float(n))) / radius;
          float r2 = sx * sx + sy * sy;
          if (r2 >= 1.0f) {
            sum += background_linear;
            continue;
          }
          vec3 normal(sx, sy, std::sqrt(1.0f - r2));
          vec3 tangent(normal.z, 0.0f, -normal.x);  // along the longitude, around the vertical axis
          Frame frame = Frame::from_normal_tangent(normal, tangent);
          ShadingContext ctx;
          ctx.uv = vec2(0.5f + float(std::atan2(double(normal.x), double(normal.z)) / (2.0 * kPi)),
                        float(std::acos(double(std::clamp(normal.y, -1.0f, 1.0f))) / kPi));
          ctx.position = normal;
          ctx.normal = normal;
          ctx.tangent = frame.tangent;
          ctx.view_distance = 1.0f;
          vec3 wi = frame.to_local(light), wo = frame.to_local(view);
          vec3 radiance = wi.z > 0.0f ? evaluator.eval(ctx, wi, wo) * wi.z * irradiance : vec3(0.0f);
          if (ambient > 0.0f && !have_sky) {
            sky = sky_at(ctx, wo);
            have_sky = true;
          }
          radiance += sky;
          vec3 display = glm::clamp(radiance * exposure, vec3(0.0f), vec3(1.0f));
          if (!std::isfinite(display.r + display.g + display.b)) display = vec3(0.0f);
          sum += display;
        }
      vec3 mean = sum / float(n * n);
      canvas.at(x, y) = kernels::srgb_from_linear(mean);
    }
  };
  int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int y = area.y0 + t; y < area.y1; y += threads) shade_row(y);
    });
  for (auto& thread : pool) thread.join();
}

}  // namespace lamina::cli::plot
