// An RGB triple as the commands' JSON reports write it: [r, g, b].
#pragma once

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace lamina::cli {

inline nlohmann::json json_rgb(glm::dvec3 v) { return {v.r, v.g, v.b}; }

}  // namespace lamina::cli
