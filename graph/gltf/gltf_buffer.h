// The binary side of a glTF file: one buffer of 4-byte aligned views (vertex data, indices,
// images), the accessors that read them, and the GLB container (glTF 2.0 spec, sec. 4.4).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "graph/json_type.h"

namespace lamina::gltf {

// Appends views and accessors to a glTF document's "bufferViews" and "accessors" arrays while
// collecting the bytes of its single buffer.
class BufferBuilder {
 public:
  explicit BufferBuilder(Json& document) : document_(document) {}

  // Vertex attributes and indices; each gets its own tightly packed view with the right target.
  // POSITION-like attributes carry min and max (required for POSITION by the spec, sec. 3.7.2.1).
  int add_vec3(std::span<const glm::vec3> values, bool with_bounds);
  int add_vec4(std::span<const glm::vec4> values);
  int add_vec2(std::span<const glm::vec2> values);
  int add_indices(std::span<const uint32_t> indices, uint32_t vertex_count);
  // An encoded image; returns the view's index for images[].bufferView.
  int add_image_bytes(std::span<const unsigned char> bytes);

  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  int add_view(const void* data, size_t size, int target);
  int add_accessor(int view, int component_type, size_t count, const char* type);

  Json& document_;
  std::vector<unsigned char> bytes_;
};

// A .glb: the JSON chunk padded with spaces and the BIN chunk padded with zeros.
std::vector<unsigned char> pack_glb(const std::string& json, std::span<const unsigned char> bin);

}  // namespace lamina::gltf
