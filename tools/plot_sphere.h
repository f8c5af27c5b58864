// The sphere panel of `lamina plot`: the material on a sphere under one directional light and a
// dim uniform sky.
#pragma once

#include "graph/cpu/evaluator.h"
#include "tools/plot_canvas.h"

namespace lamina::cli::plot {

// Shades the unit sphere into the square `area` of the canvas, `background` (display sRGB) around
// it, with a uniform sky of radiance `ambient` (0: the light alone).
void draw_sphere(Canvas& canvas, const cpu::Evaluator& evaluator, Rect area, glm::vec3 background, float ambient);

}  // namespace lamina::cli::plot
