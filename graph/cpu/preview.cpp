#include "graph/cpu/preview.h"

#include <algorithm>
#include <thread>

#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace k = kernels;
using glm::vec2;
using glm::vec3;

std::vector<vec3> render_preview(const Evaluator& evaluator, int width, int height, float ambient) {
  std::vector<vec3> pixels(size_t(std::max(width, 0)) * size_t(std::max(height, 0)));
  const vec2 viewport{float(width), float(height)};
  const vec3 background = k::lamina_preview_background();
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
        ShadingContext ctx;  // uv alone: directions are given in the local frame
        ctx.uv = k::lamina_preview_uv(n);
        vec3 wo = k::lamina_preview_local(k::LAMINA_PREVIEW_VIEW, n);
        vec3 wi = k::lamina_preview_local(k::LAMINA_PREVIEW_LIGHT, n);
        vec3 radiance(0.0f);
        if (wi.z > 0.0f) radiance = k::lamina_preview_light(evaluator.eval(ctx, wi, wo), wi);
        if (ambient > 0.0f && !have_sky) {
          vec3 weights(0.0f);
          for (int i = 0; i < k::LAMINA_PREVIEW_SKY_POINTS; ++i) {
            vec3 p = k::lamina_preview_sky_point(i);
            Sample drawn = evaluator.sample(ctx, wo, vec2(p.x, p.y), p.z);
            weights += k::lamina_preview_sky_weight(drawn.f, drawn.wi, drawn.pdf);
          }
          sky = k::lamina_preview_sky(weights, vec3(ambient));
          have_sky = true;
        }
        sum += k::lamina_preview_display(radiance + sky);
      }
      pixels[size_t(row) * size_t(width) + size_t(x)] = k::lamina_preview_mean(sum);
    }
  };
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int row = t; row < height; row += threads) shade_row(row);
    });
  for (std::thread& thread : pool) thread.join();
  return pixels;
}

}  // namespace lamina::cpu
