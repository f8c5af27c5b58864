// Reading glTF 2.0 (.gltf and .glb) as lamina uses it: the scene graph and meshes for scene mesh
// files, materials, textures and images for lamina import. Every file from anywhere goes through
// the same checks, in one place: the GLB container, the JSON (nesting limit, syntax, duplicate
// keys: graph/json_values.h), each property's type and range as the glTF 2.0 JSON schema gives
// them, every index into another array, and every buffer, buffer view and accessor range against
// the bytes that are really there. Buffers and images are read lazily, only when something lamina
// uses refers to them, and only through graph/file_access.h (relative URIs inside the glTF file's
// folder, regular files, size caps). Every problem is a lamina::Error naming the file and the
// glTF JSON pointer ("" for the container or the file as a whole), in lamina's own words.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graph/diagnostics.h"
#include "graph/file_access.h"
#include "graph/gltf/constants.h"

namespace lamina::gltf {

// Bytes of one component of an accessor.componentType; 0 for a value that is not one.
size_t component_size(int component_type);

struct GltfTextureInfo {
  int index = -1;  // -1: none
  int tex_coord = 0;
};

struct GltfMaterial {
  std::string name;
  std::array<double, 4> base_color_factor{1.0, 1.0, 1.0, 1.0};
  GltfTextureInfo base_color_texture;
  double metallic_factor = 1.0;
  double roughness_factor = 1.0;
  GltfTextureInfo metallic_roughness_texture;
  GltfTextureInfo normal_texture, occlusion_texture, emissive_texture;
  std::array<double, 3> emissive_factor{0.0, 0.0, 0.0};
  std::string alpha_mode = "OPAQUE";
  nlohmann::ordered_json extensions = nlohmann::ordered_json::object();  // as written
  nlohmann::ordered_json extras;                                         // as written; null when absent
};

struct GltfTexture {
  int sampler = -1;
  int source = -1;
};

struct GltfImage {
  std::string name;
  std::string uri;  // as written (percent-encoded, or a data: URI); empty when in a buffer view
  int buffer_view = -1;
  std::string mime_type;
};

struct GltfSampler {
  int wrap_s = kRepeat;
  int wrap_t = kRepeat;
};

struct GltfBuffer {
  std::string uri;  // empty: the BIN chunk of a .glb (buffer 0 only)
  size_t byte_length = 0;
};

struct GltfBufferView {
  int buffer = 0;
  size_t byte_offset = 0;
  size_t byte_length = 0;
  size_t byte_stride = 0;  // 0: tightly packed
};

struct GltfAccessor {
  int buffer_view = -1;  // -1: every element is zero
  size_t byte_offset = 0;
  int component_type = kFloat;
  bool normalized = false;
  size_t count = 0;
  int components = 1;  // SCALAR 1, VEC2 2, VEC3 3, VEC4 4, MAT2 4, MAT3 9, MAT4 16
  std::string type;    // "SCALAR", "VEC3", ...
  bool sparse = false;
};

struct GltfPrimitive {
  std::map<std::string, int> attributes;
  int indices = -1;
  int material = -1;
  int mode = kModeTriangles;
};

struct GltfMesh {
  std::string name;
  std::vector<GltfPrimitive> primitives;
};

struct GltfNode {
  std::string name;
  int mesh = -1;
  std::vector<int> children;
  std::optional<std::array<double, 16>> matrix;  // column-major; else translation, rotation, scale
  std::array<double, 3> translation{0.0, 0.0, 0.0};
  std::array<double, 4> rotation{0.0, 0.0, 0.0, 1.0};  // x, y, z, w
  std::array<double, 3> scale{1.0, 1.0, 1.0};
};

struct GltfScene {
  std::vector<int> nodes;
};

// The elements of an accessor as they lie in memory: `count` elements of `element_size` bytes,
// `stride` bytes apart from `data`, every byte of them inside the buffer. `data` is null for an
// accessor without a buffer view (all zeros).
struct GltfAccessorData {
  const unsigned char* data = nullptr;
  size_t stride = 0;
  size_t element_size = 0;
  size_t count = 0;
};

class GltfAsset {
 public:
  std::filesystem::path path;  // the glTF file, for messages and its folder
  bool binary = false;         // a .glb
  std::vector<std::string> extensions_used, extensions_required;
  int scene = -1;  // the default scene; -1 when none is marked
  std::vector<GltfScene> scenes;
  std::vector<GltfNode> nodes;
  std::vector<GltfMesh> meshes;
  std::vector<GltfAccessor> accessors;
  std::vector<GltfBufferView> buffer_views;
  std::vector<GltfBuffer> buffers;
  std::vector<GltfMaterial> materials;
  std::vector<GltfTexture> textures;
  std::vector<GltfImage> images;
  std::vector<GltfSampler> samplers;

  // The bytes of accessor `index` (its ranges were checked when the file was read; the buffer is
  // read now, once). Throws lamina::Error when the buffer cannot be read or holds fewer bytes than
  // its byteLength.
  GltfAccessorData accessor_data(int index) const;
  // The encoded bytes of image `index`: a data: URI, a file next to the glTF file, or a buffer view.
  // Throws lamina::Error (at /images/index/...) when they cannot be had.
  std::string image_bytes(int index) const;

 private:
  friend GltfAsset read_gltf(std::string_view, const std::filesystem::path&, const AssetPolicy&);
  const std::string& buffer_data(int index) const;
  std::string_view view_data(int index) const;
  std::string decode_data_uri(const std::string& uri, const std::string& pointer) const;
  [[noreturn]] void fail(const std::string& pointer, const std::string& message, const std::string& hint = {}) const;

  AssetPolicy policy_;
  std::string bin_chunk_;                                   // a .glb's BIN chunk
  mutable std::vector<std::unique_ptr<std::string>> data_;  // per buffer, once read
};

// Reads `bytes`, the content of the glTF file `path` (.gltf or .glb, told apart by the "glTF" magic
// of a binary), checking everything but the buffers' and images' contents, which are read when
// asked for. Throws lamina::Error with every problem found.
GltfAsset read_gltf(std::string_view bytes, const std::filesystem::path& path, const AssetPolicy& policy);

}  // namespace lamina::gltf
