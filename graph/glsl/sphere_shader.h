// The --shader sphere wrapper: a fragment shader main() around a generated module.
#pragma once

#include <string>

namespace lamina::glsl {

// main() drawing the material preview of nodes/kernels/preview.glsl (the sphere of lamina plot)
// with the material whose functions start with `prefix`. The host sets `uniform vec2
// lamina_viewport` to the viewport size in pixels.
std::string sphere_shader(const std::string& prefix);

// `vec3 <prefix>_preview_sky_weights(vec3 view, LaminaPoint point)`: the sum of the sky
// estimator's LAMINA_PREVIEW_SKY_POINTS weights (nodes/kernels/preview.glsl) that the material's
// sample() gives seen from `view`. Both wrappers, sphere and plane, estimate their sky with it.
std::string preview_sky_weights(const std::string& prefix);

}  // namespace lamina::glsl
