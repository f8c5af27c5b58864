// The lossless half of glTF import: a material carrying LAMINA_materials_layered comes back as the
// graph it embeds, read by the regular reader, with its image nodes pointed at extracted textures.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>

#include "graph/gltf/import_load.h"

namespace lamina::gltf {

// Adds glTF material `index`, whose LAMINA_materials_layered object is `extension`, to the
// session's document; its problems go to the session's diagnostics at their glTF pointers.
void import_layered(ImportSession& session, size_t index, const nlohmann::ordered_json& extension);

}  // namespace lamina::gltf
