// Inside glTF import (graph/gltf/import.h is its public face): the glTF as loaded and what both
// material paths share. import_load.cpp reads and checks the file, extracts images (each decoded
// once, named truthfully and uniquely) and names materials; import_layered.cpp and import_pbr.cpp
// turn one glTF material each into a lamina material; import.cpp runs them and checks the result.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/file_access.h"
#include "graph/gltf/gltf_read.h"
#include "graph/gltf/import.h"

namespace lamina::gltf {

// The KHR material extensions the approximate path reads.
inline constexpr const char* kIor = "KHR_materials_ior";
inline constexpr const char* kSpecular = "KHR_materials_specular";
inline constexpr const char* kClearcoat = "KHR_materials_clearcoat";
inline constexpr const char* kIridescence = "KHR_materials_iridescence";

// Where an imported material came from, to give the checker's findings glTF pointers.
struct Origin {
  size_t gltf_index = 0;
  bool layered = false;  // from LAMINA_materials_layered
};

// One import from start to end: what was read, and the result as it grows.
struct ImportSession {
  ImportSession(std::string_view bytes, const std::filesystem::path& path, Diagnostics& diagnostics,
                const AssetPolicy& policy);

  // Reads and checks the glTF into `model`; false (the problems in `diagnostics`) when it cannot.
  bool load();
  // A lamina identifier from `wanted`, unique among the materials imported so far.
  std::string unique_material_name(const std::string& wanted, size_t index);
  // The encoded bytes of the image of glTF texture `texture`, read and decoded once (as an image
  // under the pixel budget: bytes that are no image are never extracted), or nullptr after an error.
  const std::string* image_of(int texture, const std::string& pointer);
  // The extracted file name for glTF texture `texture` (its image's bytes), or "" after an error.
  std::string texture_file(int texture, const std::string& pointer, const std::string& wanted);
  void add(Material m, Origin origin);

  std::string_view bytes;
  std::filesystem::path path;
  std::string file;
  Diagnostics& diagnostics;
  AssetPolicy policy;
  GltfAsset model;
  ImportResult result;
  std::vector<Origin> origins;  // per material of `result.document`
  std::set<int> wrap_notes;     // textures whose wrapT differs from their wrapS

 private:
  std::string default_image_name(size_t source, const std::string& bytes) const;
  std::string claim_file_name(const std::string& name, const std::string& bytes);

  std::map<int, std::optional<std::string>> images_;  // per image index: its bytes once read and decoded
  std::set<std::string> names_;                       // material names taken
};

// A JSON pointer's reference token for `token` ("a/b" -> "a~1b").
std::string pointer_escape(const std::string& token);

}  // namespace lamina::gltf
