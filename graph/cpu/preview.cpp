#include "graph/cpu/preview.h"

#include <algorithm>
#include <cmath>

#include "graph/parallel.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace k = kernels;
using glm::vec2;
using glm::vec3;

namespace {

// The kernels' sky estimate at wo: lamina_preview_sky of the weights of the points' draws, all at
// one resolved point (a textured material's stack is resolved once, not for every draw).
vec3 sky_estimate(const ShadingPoint& point, vec3 wo, float ambient) {
  const vec3 view = k::lamina_preview_sky_view(wo);
  vec3 weights(0.0f);
  for (int i = 0; i < k::LAMINA_PREVIEW_SKY_POINTS; ++i) {
    vec3 p = k::lamina_preview_sky_point(i);
    Sample drawn = point.sample(view, vec2(p.x, p.y), p.z);
    weights += k::lamina_preview_sky_weight(drawn.f, drawn.wi, drawn.pdf);
  }
  return k::lamina_preview_sky(weights, vec3(ambient));
}

// Intervals of the sky table over cos(theta_o). The estimate jumps where one of its points moves to
// another lobe or below the horizon, and interpolation smooths those jumps: with 1024 intervals the
// table stays within about one 8-bit level of the GLSL sphere's estimate per pixel (the preview
// test's bound), at 1/100 of the draws of a 1000 x 1000 sphere.
constexpr int kSkyTableSize = 1024;

}  // namespace

std::vector<vec3> render_preview(const Evaluator& evaluator, int width, int height, float ambient) {
  std::vector<vec3> pixels(size_t(std::max(width, 0)) * size_t(std::max(height, 0)));
  const vec2 viewport{float(width), float(height)};
  const vec3 background = k::lamina_preview_background();
  // A material without textures is the same at every point, so its sky term depends on
  // cos(theta_o) alone (lamina_preview_sky_view): the kernels' estimate is tabulated over it once
  // instead of drawn anew in every pixel (5 times faster for `lamina plot`).
  std::vector<vec3> sky_table;
  if (ambient > 0.0f && evaluator.program().ops.empty())
    for (int i = 0; i <= kSkyTableSize; ++i) {
      const float c = float(i) / float(kSkyTableSize);
      sky_table.push_back(sky_estimate(evaluator.bind({}), vec3(std::sqrt(1.0f - c * c), 0.0f, c), ambient));
    }
  auto sky_at = [&](const ShadingPoint& point, vec3 wo) {
    if (sky_table.empty()) return sky_estimate(point, wo, ambient);
    const float t = std::clamp(wo.z, 0.0f, 1.0f) * float(kSkyTableSize);
    const int i = std::min(int(t), kSkyTableSize - 1);
    return glm::mix(sky_table[size_t(i)], sky_table[size_t(i) + 1], t - float(i));
  };
  // The preview's loops over subsamples and sky points; the kernels do everything else.
  auto shade_row = [&](int row) {
    for (int x = 0; x < width; ++x) {
      const vec2 pixel(float(x), float(height - 1 - row));  // the kernels count rows from the bottom
      vec3 sum(0.0f), sky(0.0f);
      bool have_sky = false;
      for (int s = 0; s < k::LAMINA_PREVIEW_SUBSAMPLES * k::LAMINA_PREVIEW_SUBSAMPLES; ++s) {
        vec2 q = k::lamina_preview_disk(k::lamina_preview_subsample(pixel, s), viewport);
        if (!k::lamina_preview_on_sphere(q)) {
          sum += background;
          continue;
        }
        vec3 n = k::lamina_preview_normal(q);
        // uv, position and footprint: directions are given in the local frame, so the frame stays
        // the default.
        const k::LaminaContext point = k::lamina_preview_context(q, viewport);
        ShadingContext ctx;
        ctx.uv = point.uv;
        ctx.position = point.position;
        ctx.footprint = point.footprint;
        vec3 wo = k::lamina_preview_local(k::LAMINA_PREVIEW_VIEW, n);
        vec3 wi = k::lamina_preview_local(k::LAMINA_PREVIEW_LIGHT, n);
        // Bound once for both terms where either needs it: a textured point resolves its stack.
        const bool lit = wi.z > 0.0f, needs_sky = ambient > 0.0f && !have_sky;
        if (!lit && !needs_sky) {
          sum += k::lamina_preview_display(sky);
          continue;
        }
        const ShadingPoint bound = evaluator.bind(ctx);
        vec3 radiance(0.0f);
        if (lit) radiance = k::lamina_preview_light(bound.eval(wi, wo), wi);
        if (needs_sky) {
          sky = sky_at(bound, wo);
          have_sky = true;
        }
        sum += k::lamina_preview_display(radiance + sky);
      }
      pixels[size_t(row) * size_t(width) + size_t(x)] = k::lamina_preview_mean(sum);
    }
  };
  parallel_for(size_t(std::max(height, 0)), [&](size_t row) { shade_row(int(row)); });
  return pixels;
}

}  // namespace lamina::cpu
