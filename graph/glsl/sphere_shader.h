// The --shader sphere wrapper: a fragment shader main() around a generated module.
#pragma once

#include <string>

namespace lamina::glsl {

// main() drawing the material preview of nodes/kernels/preview.glsl (the sphere of lamina plot)
// with the material whose functions start with `prefix`. The host sets `uniform vec2
// lamina_viewport` to the viewport size in pixels.
std::string sphere_shader(const std::string& prefix);

}  // namespace lamina::glsl
