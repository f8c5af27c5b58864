#include "graph/gltf/gltf_buffer.h"

#include "graph/gltf/constants.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace lamina::gltf {

namespace {

void pad_to_four(std::vector<unsigned char>& bytes, unsigned char fill) {
  while (bytes.size() % 4 != 0) bytes.push_back(fill);
}

void append_u32(std::vector<unsigned char>& out, uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>((value >> (8 * i)) & 0xffu));
}

}  // namespace

int BufferBuilder::add_view(const void* data, size_t size, int target) {
  pad_to_four(bytes_, 0);
  const size_t offset = bytes_.size();
  bytes_.resize(offset + size);
  if (size) std::memcpy(bytes_.data() + offset, data, size);
  Json view{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
  if (target) view["target"] = target;
  Json& views = document_["bufferViews"];
  views.push_back(std::move(view));
  return static_cast<int>(views.size()) - 1;
}

int BufferBuilder::add_accessor(int view, int component_type, size_t count, const char* type) {
  Json& accessors = document_["accessors"];
  accessors.push_back(Json{{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
  return static_cast<int>(accessors.size()) - 1;
}

int BufferBuilder::add_vec3(std::span<const glm::vec3> values, bool with_bounds) {
  int view = add_view(values.data(), values.size_bytes(), kArrayBuffer);
  int accessor = add_accessor(view, kFloat, values.size(), "VEC3");
  if (with_bounds && !values.empty()) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const auto& v : values) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    Json& a = document_["accessors"][static_cast<size_t>(accessor)];
    a["min"] = Json::array({lo.x, lo.y, lo.z});
    a["max"] = Json::array({hi.x, hi.y, hi.z});
  }
  return accessor;
}

int BufferBuilder::add_vec4(std::span<const glm::vec4> values) {
  return add_accessor(add_view(values.data(), values.size_bytes(), kArrayBuffer), kFloat, values.size(), "VEC4");
}

int BufferBuilder::add_vec2(std::span<const glm::vec2> values) {
  return add_accessor(add_view(values.data(), values.size_bytes(), kArrayBuffer), kFloat, values.size(), "VEC2");
}

int BufferBuilder::add_indices(std::span<const uint32_t> indices, uint32_t vertex_count) {
  // 16-bit indices when they fit: half the bytes, and what every viewer reads fastest.
  if (vertex_count <= 65535u) {
    std::vector<uint16_t> narrow(indices.begin(), indices.end());
    int view = add_view(narrow.data(), narrow.size() * sizeof(uint16_t), kElementArrayBuffer);
    return add_accessor(view, kUnsignedShort, narrow.size(), "SCALAR");
  }
  int view = add_view(indices.data(), indices.size_bytes(), kElementArrayBuffer);
  return add_accessor(view, kUnsignedInt, indices.size(), "SCALAR");
}

int BufferBuilder::add_image_bytes(std::span<const unsigned char> bytes) {
  return add_view(bytes.data(), bytes.size(), 0);
}

std::vector<unsigned char> pack_glb(const std::string& json, std::span<const unsigned char> bin) {
  std::vector<unsigned char> json_chunk(json.begin(), json.end());
  pad_to_four(json_chunk, ' ');
  std::vector<unsigned char> bin_chunk(bin.begin(), bin.end());
  pad_to_four(bin_chunk, 0);
  const bool has_bin = !bin_chunk.empty();
  const size_t total = 12 + 8 + json_chunk.size() + (has_bin ? 8 + bin_chunk.size() : 0);
  std::vector<unsigned char> out;
  out.reserve(total);
  append_u32(out, kGlbMagic);
  append_u32(out, kGlbVersion);
  append_u32(out, static_cast<uint32_t>(total));
  append_u32(out, static_cast<uint32_t>(json_chunk.size()));
  append_u32(out, kChunkJson);
  out.insert(out.end(), json_chunk.begin(), json_chunk.end());
  if (has_bin) {
    append_u32(out, static_cast<uint32_t>(bin_chunk.size()));
    append_u32(out, kChunkBin);
    out.insert(out.end(), bin_chunk.begin(), bin_chunk.end());
  }
  return out;
}

}  // namespace lamina::gltf
