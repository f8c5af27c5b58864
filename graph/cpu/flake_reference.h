// The full model of a flake paint (flake_slab.h) for a material as it stands at a shading point:
// its surface a layer (a clear medium under a dielectric interface) over a substrate/flake_paint,
// the layer's index the binder's. What `lamina reference --flakes` solves, as the ground truth the
// fast model (nodes/kernels/flakes.glsl) approximates.
#pragma once

#include <array>

#include "graph/cpu/evaluator.h"
#include "graph/cpu/flake_slab.h"

namespace lamina::cpu {

struct FlakePaintSlabs {
  std::array<FlakeSlab, 3> channels;  // red, green, blue; coated flakes' film at 645, 525 and 445 nm
  // The full model's boundary is smooth: the layer's interface's slope, which it leaves out.
  float boundary_slope = 0.0f;
  // Coated flakes whose material folds the film's spectrum into each channel (integration
  // "spectral"), where the full model takes the film at the channel's wavelength.
  bool spectral_fold = false;
};

// The paint's slabs at `point`, with its parameters as they are resolved there (textures read at
// the point's uv). Throws std::invalid_argument, saying why, for any other stack.
FlakePaintSlabs flake_paint_slabs(const ShadingPoint& point);

}  // namespace lamina::cpu
