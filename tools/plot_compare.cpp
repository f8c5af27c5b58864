#include "tools/plot_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "graph/model.h"
#include "tools/plot_canvas.h"
#include "tools/plot_figure.h"
#include "tools/plot_slices.h"
#include "tools/plot_style.h"

namespace lamina::cli::plot {

namespace {

using glm::vec2;
using glm::vec3;

constexpr int kAlbedoGridDeg = 15;

// The albedo panel: theta from 0 to 90 degrees across, albedo from 0 to `top` up.
struct AlbedoGeometry {
  Rect cell, plot;
  float top;
  float step;  // between grid lines

  AlbedoGeometry(const Layout& l, Rect cell_, float top_)
      : cell(cell_),
        plot{cell_.x0 + l.px(66), cell_.y0 + l.px(44), cell_.x1 - l.px(22), cell_.y1 - l.px(56)},
        top(top_),
        step(top_ <= 1.5f ? 0.25f : 0.5f) {}
  float x_of(double theta_deg) const { return float(plot.x0) + float(theta_deg) / 90.0f * float(plot.x1 - plot.x0); }
  float y_of(double a) const {
    return float(plot.y1) - std::clamp(float(a) / top, 0.0f, 1.0f) * float(plot.y1 - plot.y0);
  }
};

// The albedo axis reaches 1 (the white furnace's limit, drawn dashed) or the largest value.
float albedo_top(const cpu::Comparison& c) {
  double largest = 1.0;
  for (const cpu::AlbedoComparison& row : c.albedo)
    for (int k = 0; k < 3; ++k)
      largest = std::max({largest, row.albedo.model[k], row.albedo.reference[k] + 2.0 * row.albedo.std_error[k]});
  return float(std::ceil(largest * 4.0 - 1e-6) / 4.0);
}

void draw_albedo_pixels(Canvas& canvas, const Layout& l, const cpu::Comparison& c, const AlbedoGeometry& g) {
  const Rect& plot = g.plot;
  canvas.fill(plot, kPlotBackground);
  const int line = std::max(1, l.px(1.0));
  for (int theta = 0; theta <= 90; theta += kAlbedoGridDeg) {
    int x = std::min(int(g.x_of(theta)), plot.x1 - line);
    canvas.fill({x, plot.y0, x + line, plot.y1}, kGrid);
  }
  for (float a = 0.0f; a <= g.top + 1e-4f; a += g.step) {
    int y = std::min(int(g.y_of(a)), plot.y1 - line);
    canvas.fill({plot.x0, y, plot.x1, y + line}, kGrid);
  }
  // Albedo 1, dashed: a material above it reflects more than it receives.
  int one = std::min(int(g.y_of(1.0)), plot.y1 - line);
  for (int x = plot.x0; x < plot.x1; x += l.px(12))
    canvas.fill({x, one, std::min(x + l.px(6), plot.x1), one + line}, kMirror);
  const float half = float(std::max(2, l.px(3.5)));
  for (int k = 0; k < 3; ++k) {
    std::vector<vec2> curve;
    for (const cpu::AlbedoComparison& row : c.albedo) {
      const float x = g.x_of(row.theta_deg);
      curve.push_back(vec2(x, g.y_of(row.albedo.model[k])));
      const double r = row.albedo.reference[k], e = 2.0 * row.albedo.std_error[k];
      const float y = g.y_of(r);
      canvas.add_polyline({vec2(x - half, y), vec2(x + half, y)}, 2.0f * half, plot, kChannel[size_t(k)]);
      canvas.add_polyline({vec2(x, g.y_of(r - e)), vec2(x, g.y_of(r + e))}, float(std::max(1.0, l.s)), plot,
                          kChannel[size_t(k)]);
    }
    canvas.add_polyline(curve, float(std::max(1.6, 2.2 * l.s)), plot, kChannel[size_t(k)]);
  }
  canvas.fill({plot.x0, plot.y0, plot.x1, plot.y0 + line}, kFrame);
  canvas.fill({plot.x0, plot.y1 - line, plot.x1, plot.y1}, kFrame);
  canvas.fill({plot.x0, plot.y0, plot.x0 + line, plot.y1}, kFrame);
  canvas.fill({plot.x1 - line, plot.y0, plot.x1, plot.y1}, kFrame);
}

void draw_albedo_labels(Text& text, const Layout& l, const cpu::Comparison& c, const AlbedoGeometry& g) {
  const Rect& plot = g.plot;
  const int tick_font = l.font(14), label_font = l.font(16), width = plot.x1 - plot.x0;
  for (int theta = 0; theta <= 90; theta += kAlbedoGridDeg)
    text.draw(int(g.x_of(theta)), plot.y1 + l.px(20), std::to_string(theta), tick_font, kTextDim, 0);
  for (float a = 0.0f; a <= g.top + 1e-4f; a += g.step) {
    char tick[16];
    std::snprintf(tick, sizeof tick, "%.2f", double(a));
    text.draw(plot.x0 - l.px(8), int(g.y_of(a)) + l.px(5), tick, tick_font, kTextDim, 1);
  }
  char title[96];
  std::snprintf(title, sizeof title, "directional albedo: error at most %.1f%% (theta %g)", 100.0 * c.max_albedo_error,
                c.max_albedo_error_theta_deg);
  text.draw((plot.x0 + plot.x1) / 2, plot.y0 - l.px(14), title, l.font(18), kText, 0, true, width);
  text.draw((plot.x0 + plot.x1) / 2, plot.y1 + l.px(44), "theta_o (deg); dashed: albedo 1", label_font, kTextDim, 0,
            false, width);
}

// The reference's slice values as points, and as a Slice for the panels' common value range.
SlicePoints reference_points(const cpu::SliceComparison& s) {
  SlicePoints p;
  for (size_t k = 0; k < s.f.size(); ++k) {
    p.theta_i_deg.push_back(float(s.theta_i_deg[k]));
    p.value.push_back(vec3(s.f[k].reference));
    p.std_error.push_back(vec3(s.f[k].std_error));
  }
  return p;
}

}  // namespace

std::string draw_comparison(Canvas& canvas, const cpu::Evaluator& evaluator, const cpu::Comparison& comparison,
                            const ComparisonSource& source, const Fonts& fonts) {
  const int width = canvas.width(), height = canvas.height();
  Layout l{double(width) / 1600.0};
  canvas.fill({0, 0, width, height}, kFigureBackground);

  // The model's slices drawn densely, as lamina plot draws them; the reference's at its points.
  std::vector<Slice> slices = compute_slices(evaluator, source.uv);
  std::vector<SlicePoints> points;
  std::vector<Slice> everything = slices;
  for (const cpu::SliceComparison& s : comparison.slices) {
    points.push_back(reference_points(s));
    everything.push_back({float(s.theta_o_deg), points.back().theta_i_deg, points.back().value});
  }
  const Decades range = value_range(everything);
  const int top = l.px(92), split = l.px(960);
  const std::vector<SliceGeometry> geometry = slice_grid(l, top, split, height, slices.size(), range);
  for (size_t i = 0; i < slices.size(); ++i) {
    draw_slice_pixels(canvas, l, slices[i], geometry[i]);
    for (size_t j = 0; j < comparison.slices.size(); ++j)
      if (float(comparison.slices[j].theta_o_deg) == slices[i].theta_o_deg)
        draw_slice_points(canvas, l, points[j], geometry[i]);
  }
  const AlbedoGeometry albedo(l, Rect{split, top, width, height}, albedo_top(comparison));
  draw_albedo_pixels(canvas, l, comparison, albedo);

  Text text(canvas, fonts);
  for (size_t i = 0; i < slices.size(); ++i) draw_slice_labels(text, l, slices[i], geometry[i]);
  draw_albedo_labels(text, l, comparison, albedo);

  const Program& program = evaluator.program();
  const int margin = l.px(24);
  const std::string model(model_name(program.model));
  const std::string title = program.name + ": the " + model + " model against the reference solver";
  const int title_font = text.fit(title, l.font(30), width * 2 / 3, true);
  text.draw(margin, l.px(40), title, title_font, kText, -1, true);
  text.draw(margin + text.width(title, title_font, true), l.px(40),
            "   " + std::filesystem::path(source.file).filename().string(), l.font(18), kTextDim, -1, false, width / 4);
  char rest[200];
  std::snprintf(rest, sizeof rest,
                "  lines: the model; squares, bars +- 2 standard errors: the reference (%lld walks per albedo angle, "
                "%lld per BRDF point)",
                static_cast<long long>(source.albedo_walks), static_cast<long long>(source.slice_walks));
  const int legend_y = l.px(74);
  int legend_font = l.font(16);
  const std::string intro = "Per channel:";
  // The key and the explanation shrink together until they fit the width.
  while (legend_font > 7 &&
         text.width(intro, legend_font) + text.width(rest, legend_font) + l.px(200) > width - 2 * margin)
    --legend_font;
  text.draw(margin, legend_y, intro, legend_font, kTextDim);
  int x = draw_channel_legend(canvas, text, l, margin + text.width(intro, legend_font), legend_y, legend_font);
  text.draw(x, legend_y, rest, legend_font, kTextDim);
  return text.error();
}

}  // namespace lamina::cli::plot
