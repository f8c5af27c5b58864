#include "tools/plot_slices.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "tools/plot_style.h"

namespace lamina::cli::plot {

namespace {

using glm::vec2;
using glm::vec3;

constexpr std::array<float, 4> kViewAngles = {0.0f, 30.0f, 60.0f, 80.0f};
constexpr float kThetaLimit = 89.5f;  // the slices stop short of grazing, where f is 0
constexpr float kThetaStep = 0.25f;   // lands exactly on every view angle's mirror direction
constexpr int kGridStepDeg = 30;

}  // namespace

std::vector<Slice> compute_slices(const cpu::Evaluator& evaluator, vec2 uv) {
  std::vector<Slice> slices;
  int count = int(std::lround(2.0f * kThetaLimit / kThetaStep)) + 1;
  ShadingContext ctx;
  ctx.uv = uv;
  for (float theta_o : kViewAngles) {
    Slice s{theta_o, {}, {}};
    const vec3 wo = direction_in_plane(double(theta_o));
    for (int k = 0; k < count; ++k) {
      float theta_i = -kThetaLimit + kThetaStep * float(k);
      s.theta_i_deg.push_back(theta_i);
      s.f.push_back(evaluator.eval(ctx, direction_in_plane(-double(theta_i)), wo));
    }
    slices.push_back(std::move(s));
  }
  return slices;
}

Decades value_range(const std::vector<Slice>& slices) {
  float largest = 0.0f, smallest = std::numeric_limits<float>::infinity();
  for (const Slice& s : slices)
    for (size_t k = 0; k < s.f.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        float v = s.f[k][c];
        if (!std::isfinite(v) || v <= 0.0f) continue;
        largest = std::max(largest, v);
        if (std::abs(s.theta_i_deg[k]) <= 80.0f) smallest = std::min(smallest, v);
      }
  if (largest <= 0.0f) return {-3, 0};
  int high = int(std::ceil(std::log10(largest) + 0.02f));
  int low = std::isfinite(smallest) ? int(std::floor(std::log10(smallest) - 0.02f)) : high - 3;
  low = std::clamp(low, high - 6, high - 2);
  return {low, high};
}

SliceGeometry::SliceGeometry(const Layout& l, Rect cell_, Decades range_)
    : cell(cell_),
      plot{cell_.x0 + l.px(66), cell_.y0 + l.px(40), cell_.x1 - l.px(22), cell_.y1 - l.px(56)},
      range(range_) {}

float SliceGeometry::x_of(float theta_deg) const {
  return float(plot.x0) + (theta_deg + 90.0f) / 180.0f * float(plot.x1 - plot.x0);
}

float SliceGeometry::y_of(float decade) const {
  float t = (decade - float(range.low)) / float(range.high - range.low);
  return float(plot.y1) - std::clamp(t, 0.0f, 1.0f) * float(plot.y1 - plot.y0);
}

std::vector<SliceGeometry> slice_grid(const Layout& l, int top, int split, int bottom, size_t count, Decades range) {
  const int cell_w = split / 2, cell_h = (bottom - top) / 2;
  std::vector<SliceGeometry> geometry;
  for (size_t i = 0; i < count; ++i) {
    int col = int(i % 2), row = int(i / 2);
    geometry.emplace_back(l, Rect{col * cell_w, top + row * cell_h, (col + 1) * cell_w, top + (row + 1) * cell_h},
                          range);
  }
  return geometry;
}

void draw_slice_pixels(Canvas& canvas, const Layout& l, const Slice& slice, const SliceGeometry& g) {
  const Rect& plot = g.plot;
  canvas.fill(plot, kPlotBackground);
  int line = std::max(1, l.px(1.0));
  // Grid: every 30 degrees and every decade.
  for (int theta = -90; theta <= 90; theta += kGridStepDeg) {
    int x = std::min(int(g.x_of(float(theta))), plot.x1 - line);
    canvas.fill({x, plot.y0, x + line, plot.y1}, kGrid);
  }
  for (int d = g.range.low; d <= g.range.high; ++d) {
    int y = std::min(int(g.y_of(float(d))), plot.y1 - line);
    canvas.fill({plot.x0, y, plot.x1, y + line}, kGrid);
  }
  // The mirror direction, dashed.
  int mirror = std::min(int(g.x_of(slice.theta_o_deg)), plot.x1 - line);
  for (int y = plot.y0; y < plot.y1; y += l.px(12))
    canvas.fill({mirror, y, mirror + line, std::min(y + l.px(6), plot.y1)}, kMirror);
  // The curves, added channel by channel; f = 0 sits on the bottom edge.
  for (int c = 0; c < 3; ++c) {
    std::vector<vec2> points;
    for (size_t k = 0; k < slice.f.size(); ++k) {
      float v = slice.f[k][c];
      float decade = (std::isfinite(v) && v > 0.0f) ? std::log10(v) : float(g.range.low);
      points.push_back(vec2(g.x_of(slice.theta_i_deg[k]), g.y_of(decade)));
    }
    canvas.add_polyline(points, float(std::max(1.6, 2.2 * l.s)), plot, kChannel[size_t(c)]);
  }
  // Frame.
  canvas.fill({plot.x0, plot.y0, plot.x1, plot.y0 + line}, kFrame);
  canvas.fill({plot.x0, plot.y1 - line, plot.x1, plot.y1}, kFrame);
  canvas.fill({plot.x0, plot.y0, plot.x0 + line, plot.y1}, kFrame);
  canvas.fill({plot.x1 - line, plot.y0, plot.x1, plot.y1}, kFrame);
}

void draw_slice_points(Canvas& canvas, const Layout& l, const SlicePoints& points, const SliceGeometry& g) {
  const float half = float(std::max(2, l.px(3.5)));
  auto decade = [&](float v) { return (std::isfinite(v) && v > 0.0f) ? std::log10(v) : float(g.range.low); };
  for (size_t k = 0; k < points.value.size(); ++k) {
    const float x = g.x_of(points.theta_i_deg[k]);
    for (int c = 0; c < 3; ++c) {
      const float v = points.value[k][c], e = 2.0f * points.std_error[k][c];
      const float y = g.y_of(decade(v));
      canvas.add_polyline({vec2(x - half, y), vec2(x + half, y)}, 2.0f * half, g.plot, kChannel[size_t(c)]);
      canvas.add_polyline({vec2(x, g.y_of(decade(v - e))), vec2(x, g.y_of(decade(v + e)))}, float(std::max(1.0, l.s)),
                          g.plot, kChannel[size_t(c)]);
    }
  }
}

void draw_slice_labels(Text& text, const Layout& l, const Slice& slice, const SliceGeometry& g) {
  const Rect& plot = g.plot;
  int tick_font = l.font(14), label_font = l.font(16);
  for (int theta = -90; theta <= 90; theta += kGridStepDeg)
    text.draw(int(g.x_of(float(theta))), plot.y1 + l.px(20), std::to_string(theta), tick_font, kTextDim, 0);
  for (int d = g.range.low; d <= g.range.high; ++d)
    text.draw(plot.x0 - l.px(8), int(g.y_of(float(d))) + l.px(5), std::to_string(d), tick_font, kTextDim, 1);
  char title[64];
  std::snprintf(title, sizeof title, "theta_o = %g deg", double(slice.theta_o_deg));
  int plot_width = plot.x1 - plot.x0;
  text.draw((plot.x0 + plot.x1) / 2, plot.y0 - l.px(12), title, l.font(18), kText, 0, true, plot_width / 2);
  text.draw(g.cell.x0 + l.px(10), plot.y0 - l.px(12), "log10 f", label_font, kTextDim, -1);
  text.draw((plot.x0 + plot.x1) / 2, plot.y1 + l.px(44), "theta_i (deg), > 0 toward the mirror direction", label_font,
            kTextDim, 0, false, plot_width);
}

}  // namespace lamina::cli::plot
