// The --shader plane wrapper: a fragment shader main() drawing a generated material on a ground
// plane that recedes to the horizon, where a pixel's footprint grows from a fraction of a texture's
// detail to thousands of its cells: the view that shows whether a texture aliases.
#pragma once

#include <string>

namespace lamina::glsl {

// main() drawing the material whose functions start with `prefix` on the plane z = 0, uv its x and
// y, seen from a pinhole camera one unit above it. The host sets `uniform vec2 lamina_viewport`
// (pixels), `uniform float lamina_footprint_scale` (1 filters textures over the pixel's footprint
// from dFdx and dFdy; 0 point-samples them) and `uniform float lamina_ambient_radiance` (the sky;
// 0 for the light alone).
std::string plane_shader(const std::string& prefix);

}  // namespace lamina::glsl
