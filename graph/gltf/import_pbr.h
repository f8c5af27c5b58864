// The approximate half of glTF import: a material without LAMINA_materials_layered is read from
// core metallic-roughness and the KHR material extensions, and mapped to layers
// (graph/gltf/pbr_to_layers.h); what the layers cannot carry becomes a note.
#pragma once

#include <cstddef>

#include "graph/gltf/import_load.h"

namespace lamina::gltf {

// Adds glTF material `index` to the session's document, approximated; its problems go to the
// session's diagnostics, the approximations made to the result's notes.
void import_pbr(ImportSession& session, size_t index);

}  // namespace lamina::gltf
