// glTF 2.0 export of a scene: meshes, nodes, cameras, KHR_lights_punctual, and per material the
// LAMINA_materials_layered extension (the exact graph) with a fitted standard-PBR fallback
// (core metallic-roughness plus KHR_materials_clearcoat, _ior and _specular where they help).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "graph/gltf/fallback.h"
#include "graph/scene/scene.h"

namespace lamina::gltf {

inline constexpr const char* kExtensionName = "LAMINA_materials_layered";
// The key of a label material's "extras" (its value is the label's text): materials that only show
// an object's label, which lamina import leaves out.
inline constexpr const char* kLabelExtra = "lamina_label";

struct ExportOptions {
  FallbackOptions fallback;
};

struct ExportedFile {
  std::filesystem::path path;  // the output itself, or a file next to it (OUT.bin for .gltf)
  std::vector<unsigned char> bytes;
};

struct MaterialReport {
  std::string name;
  Fallback fallback;
};

struct Export {
  std::vector<ExportedFile> files;
  std::vector<MaterialReport> materials;  // in the order of the glTF's materials
  std::vector<std::string> notes;         // what glTF cannot carry (environment lights)
};

// Exports a checked scene (read_scene with no errors). `output` ending in .glb gives one binary
// file with everything embedded; .gltf gives the JSON and OUT.bin next to it (images included; the
// buffer's URI percent-encoded). Objects with a label get a second node after all objects: an
// unlit (KHR_materials_unlit), alpha-blended quad under the object, facing the first camera, its
// text rendered to a texture; its material's extras hold kLabelExtra and it is not in `materials`.
// Deterministic: the same scene gives the same bytes. Throws IoError when a mesh or texture file
// cannot be read or the label font is missing, lamina::Error when a material or mesh file no
// longer checks.
Export export_scene(const Scene& scene, const std::filesystem::path& output, const ExportOptions& options = {});

}  // namespace lamina::gltf
