// The material preview of nodes/kernels/preview.glsl rendered by the CPU evaluator: the picture
// `lamina plot` shows and `lamina glsl --shader sphere` draws on the GPU.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "graph/cpu/evaluator.h"

namespace lamina::cpu {

// The preview in a viewport of width x height pixels under a sky of radiance `ambient` (0: the
// light alone; LAMINA_PREVIEW_AMBIENT is the usual one): width * height linear RGB values, row 0
// at the top, each the mean of its subsamples' clipped radiance, ready for sRGB encoding. Rows are
// shared among threads; every pixel is computed on its own, so the result does not depend on how.
std::vector<glm::vec3> render_preview(const Evaluator& evaluator, int width, int height, float ambient);

}  // namespace lamina::cpu
