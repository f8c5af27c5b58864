#include "tools/plot_figure.h"

#include <cstdio>
#include <filesystem>
#include <vector>

#include "tools/plot_canvas.h"
#include "tools/plot_slices.h"
#include "tools/plot_sphere.h"
#include "tools/plot_style.h"

namespace lamina::cli::plot {

int draw_channel_legend(Canvas& canvas, Text& text, const Layout& l, int x, int y, int size) {
  const char* names[] = {"red", "green", "blue"};
  const int swatch = l.px(22), gap = l.px(6), space = l.px(14);
  for (int c = 0; c < 3; ++c) {
    x += space;
    int thick = std::max(2, l.px(3));
    int mid = y - size * 3 / 10;
    canvas.fill({x, mid - thick / 2, x + swatch, mid - thick / 2 + thick}, kChannel[size_t(c)]);
    x += swatch + gap;
    text.draw(x, y, names[c], size, kText);
    x += text.width(names[c], size);
  }
  return x;
}

std::string draw_figure(Canvas& canvas, const cpu::Evaluator& evaluator, const std::string& file, const Fonts& fonts,
                        glm::vec2 uv, float ambient) {
  const int width = canvas.width(), height = canvas.height();
  Layout l{double(width) / 1600.0};
  canvas.fill({0, 0, width, height}, kFigureBackground);

  std::vector<Slice> slices = compute_slices(evaluator, uv);
  Decades range = value_range(slices);
  int top = l.px(92);
  int split = l.px(960);

  // Draw the pixels first; text goes on top.
  Rect sphere_panel{split, top, width, height};
  canvas.fill(sphere_panel, kSphereBackground);
  Rect sphere{split + l.px(20), top + l.px(44), width - l.px(20), height - l.px(44)};
  int side = std::min(sphere.x1 - sphere.x0, sphere.y1 - sphere.y0);
  int sx0 = (sphere.x0 + sphere.x1 - side) / 2, sy0 = (sphere.y0 + sphere.y1 - side) / 2;
  draw_sphere(canvas, evaluator, {sx0, sy0, sx0 + side, sy0 + side}, ambient);

  const std::vector<SliceGeometry> geometry = slice_grid(l, top, split, height, slices.size(), range);
  for (size_t i = 0; i < slices.size(); ++i) draw_slice_pixels(canvas, l, slices[i], geometry[i]);

  // Text on top, through the image module.
  Text text(canvas, fonts);
  for (size_t i = 0; i < slices.size(); ++i) draw_slice_labels(text, l, slices[i], geometry[i]);

  // Title and legend.
  const Program& program = evaluator.program();
  int margin = l.px(24), x = margin;
  int title_font = text.fit(program.name, l.font(30), width / 2, true);
  text.draw(x, l.px(40), program.name, title_font, kText, -1, true);
  text.draw(x + text.width(program.name, title_font, true), l.px(40),
            "   " + std::filesystem::path(file).filename().string(), l.font(18), kTextDim, -1, false, width / 3);
  const std::string intro = "In-plane BRDF slices, log10 f (1/sr) per channel:";
  std::string rest = "(white where they agree); dashed: mirror direction";
  if (!program.ops.empty()) {
    char at[80];
    std::snprintf(at, sizeof at, "; textured: slices at uv = %g, %g", double(uv.x), double(uv.y));
    rest += at;
  }
  int legend_y = l.px(74), swatch = l.px(22), gap = l.px(6), space = l.px(14);
  const char* names[] = {"red", "green", "blue"};
  auto legend_width = [&](int size) {
    int w = text.width(intro, size) + text.width(rest, size);
    for (const char* name : names) w += space + swatch + gap + text.width(name, size);
    return w + space;
  };
  int legend_font = l.font(16);
  while (legend_font > 7 && legend_width(legend_font) > width - 2 * margin) --legend_font;
  text.draw(x, legend_y, intro, legend_font, kTextDim);
  x += text.width(intro, legend_font);
  x = draw_channel_legend(canvas, text, l, x, legend_y, legend_font);
  text.draw(x + space, legend_y, rest, legend_font, kTextDim);

  int centre = (sphere_panel.x0 + sphere_panel.x1) / 2;
  int panel_width = sphere_panel.x1 - sphere_panel.x0 - 2 * margin;
  text.draw(centre, top + l.px(30),
            ambient > 0.0f ? "sphere: one directional light from the upper left, a dim uniform sky"
                           : "sphere: one directional light from the upper left",
            l.font(18), kText, 0, true, panel_width);
  char footer[160];
  if (ambient > 0.0f)
    std::snprintf(footer, sizeof footer, "orthographic; light along (-1, 1, 1); radiance = pi f cos_i + %g albedo(wo)",
                  double(ambient));
  else
    std::snprintf(footer, sizeof footer, "orthographic; light along (-1, 1, 1); radiance = pi f cos_i");
  text.draw(centre, height - l.px(16), footer, l.font(15), kTextDim, 0, false, panel_width);
  return text.error();
}

}  // namespace lamina::cli::plot
