// The --shader sphere wrapper: a fragment shader main() around a generated module.
#pragma once

#include <string>

namespace lamina::glsl {

// main() shading an analytic unit sphere with the material whose functions start with `prefix`,
// seen orthographically and lit by a directional light plus a constant ambient. The host sets
// `uniform vec2 lamina_viewport` to the viewport size in pixels.
std::string sphere_shader(const std::string& prefix);

}  // namespace lamina::glsl
