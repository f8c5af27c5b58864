// The BRDF-slice panels of `lamina plot`: log10 f per channel in the plane of incidence against
// the light's angle, for views at 0, 30, 60 and 80 degrees, at one uv.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "graph/cpu/evaluator.h"
#include "tools/plot_canvas.h"
#include "tools/plot_text.h"

namespace lamina::cli::plot {

struct Slice {
  float theta_o_deg;
  std::vector<float> theta_i_deg;
  std::vector<glm::vec3> f;
};

// One slice per view angle; light directions in the plane of incidence (x, z), theta_i > 0 on the
// mirror side of the view, every 0.25 degrees up to 89.5 (f is 0 at grazing).
std::vector<Slice> compute_slices(const cpu::Evaluator& evaluator, glm::vec2 uv);

struct Decades {
  int low, high;  // the y axis shows log10 f from low to high
};

// The decades every panel shows: up to the largest value, down to the smallest positive one within
// 80 degrees of the normal, at least 2 and at most 6 decades.
Decades value_range(const std::vector<Slice>& slices);

// Where one slice panel draws: its plot area inside `cell` and the mapping of (theta_i, log10 f)
// into it.
struct SliceGeometry {
  Rect cell, plot;
  Decades range;

  SliceGeometry(const Layout& l, Rect cell_, Decades range_);
  float x_of(float theta_deg) const;
  float y_of(float decade) const;
};

// Where `count` slice panels go in a figure: a 2 x 2 grid filling the area left of x = split below
// y = top, down to y = bottom.
std::vector<SliceGeometry> slice_grid(const Layout& l, int top, int split, int bottom, size_t count, Decades range);

// The panel's pixels: background, grid, the dashed mirror direction, the curves and the frame.
void draw_slice_pixels(Canvas& canvas, const Layout& l, const Slice& slice, const SliceGeometry& g);
// Measured points over a drawn panel, channel by channel in the curves' colours (adding up, as they
// do): a square at each value and a bar over value +- 2 standard errors. lamina compare --plot
// draws the reference solver's values so over the model's curves.
struct SlicePoints {
  std::vector<float> theta_i_deg;
  std::vector<glm::vec3> value, std_error;
};
void draw_slice_points(Canvas& canvas, const Layout& l, const SlicePoints& points, const SliceGeometry& g);
// Its text, drawn over the pixels: tick labels, the title and the axis labels.
void draw_slice_labels(Text& text, const Layout& l, const Slice& slice, const SliceGeometry& g);

}  // namespace lamina::cli::plot
