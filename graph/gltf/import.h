// glTF 2.0 import: every material of a .gltf or .glb becomes a lamina material. Materials
// carrying LAMINA_materials_layered come back exactly (the embedded graph, read by the regular
// reader); the others are approximated from core metallic-roughness, KHR_materials_ior,
// KHR_materials_specular and KHR_materials_clearcoat (graph/gltf/pbr_to_layers.h).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/file_access.h"

namespace lamina::gltf {

// An image of the glTF, as encoded there (never re-encoded), to be written next to the
// material file under `file_name`, which the document's texture/image nodes refer to.
struct ExtractedTexture {
  std::string file_name;
  std::vector<unsigned char> bytes;
};

struct ImportResult {
  Document document;
  std::vector<ExtractedTexture> textures;
  std::vector<std::string> notes;  // approximations made (what the lamina graph does not carry)
};

// Reads `path` (.gltf with its buffers and images, or .glb; told apart by content) through
// graph/gltf/gltf_read.h: buffers and images are read only when an imported material uses them,
// from inside the glTF file's folder. Problems in the glTF go to `diagnostics` with the file and
// the glTF JSON pointer: malformed glTF, a broken LAMINA_materials_layered object or graph, an
// image that is not one lamina decodes (under the policy's pixel budget) are errors; extensions
// lamina does not read are warnings. The document is checked as `lamina validate` checks a file,
// with the extracted textures in memory (nothing is written anywhere); with errors in
// `diagnostics` the result must not be written. Throws IoError when the file cannot be read.
ImportResult import_gltf(const std::filesystem::path& path, Diagnostics& diagnostics, const AssetPolicy& policy = {});
// As import_gltf, on `bytes`, the content of `path`.
ImportResult import_gltf_bytes(std::string_view bytes, const std::filesystem::path& path, Diagnostics& diagnostics,
                               const AssetPolicy& policy = {});

}  // namespace lamina::gltf
