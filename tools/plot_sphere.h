// The sphere panel of `lamina plot`: the material preview of nodes/kernels/preview.glsl, the same
// picture `lamina glsl --shader sphere` draws on the GPU.
#pragma once

#include "graph/cpu/evaluator.h"
#include "tools/plot_canvas.h"

namespace lamina::cli::plot {

// Draws the preview, under a sky of radiance `ambient` (0: the light alone), into `area` of the
// canvas, sRGB-encoded; around the sphere it shows the preview's background.
void draw_sphere(Canvas& canvas, const cpu::Evaluator& evaluator, Rect area, float ambient);

}  // namespace lamina::cli::plot
