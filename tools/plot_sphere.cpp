#include "tools/plot_sphere.h"

#include <vector>

#include "graph/cpu/preview.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cli::plot {

void draw_sphere(Canvas& canvas, const cpu::Evaluator& evaluator, Rect area, float ambient) {
  const int width = area.x1 - area.x0, height = area.y1 - area.y0;
  std::vector<glm::vec3> linear = cpu::render_preview(evaluator, width, height, ambient);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      canvas.at(area.x0 + x, area.y0 + y) = kernels::srgb_from_linear(linear[size_t(y) * size_t(width) + size_t(x)]);
}

}  // namespace lamina::cli::plot
