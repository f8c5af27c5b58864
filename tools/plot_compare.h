// The figure `lamina compare --plot` writes: the model against the reference solver. The four
// in-plane BRDF slices of `lamina plot` (the model's curves) with the reference's values as points
// with error bars over them, beside the directional albedo from 0 to 89 degrees drawn the same way.
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "graph/cpu/compare.h"
#include "graph/cpu/evaluator.h"
#include "tools/plot_text.h"

namespace lamina::cli::plot {

// What the figure says about how the comparison was made.
struct ComparisonSource {
  std::string file;
  glm::vec2 uv{0.0f};
  int64_t albedo_walks = 0, slice_walks = 0;
};

// Draws the figure over all of `canvas` (display sRGB values). Returns why a label could not be
// drawn, or an empty string.
std::string draw_comparison(Canvas& canvas, const cpu::Evaluator& evaluator, const cpu::Comparison& comparison,
                            const ComparisonSource& source, const Fonts& fonts);

}  // namespace lamina::cli::plot
