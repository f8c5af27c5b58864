// The figure `lamina plot` writes: a title and legend over four BRDF-slice panels (left) and the
// sphere (right), laid out for any width from the 1600 x 800 design.
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "graph/cpu/evaluator.h"
#include "tools/plot_text.h"

namespace lamina::cli::plot {

// The channel key of the figures' legends ("red", "green", "blue", each after a swatch of its curve
// colour), drawn from x on the text baseline y; returns where it ends.
int draw_channel_legend(Canvas& canvas, Text& text, const Layout& l, int x, int y, int size);

// Draws the figure over all of `canvas` (display sRGB values): the slices at `uv`, the sphere
// under a sky of radiance `ambient`, the title naming the material and `file`. Returns why a label
// could not be drawn, or an empty string.
std::string draw_figure(Canvas& canvas, const cpu::Evaluator& evaluator, const std::string& file, const Fonts& fonts,
                        glm::vec2 uv, float ambient);

}  // namespace lamina::cli::plot
