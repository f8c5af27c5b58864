#include "graph/gltf/gltf_read.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "graph/gltf/uri.h"
#include "graph/json_type.h"
#include "graph/json_values.h"
#include "graph/limits.h"

namespace lamina::gltf {

namespace {

std::string plural(size_t n, const std::string& one, const std::string& many = {}) {
  return std::to_string(n) + " " + (n == 1 ? one : many.empty() ? one + "s" : many);
}

std::string at(const char* array, size_t index) { return "/" + std::string(array) + "/" + std::to_string(index); }

// a * b + c, or nothing when it would wrap around.
std::optional<size_t> mul_add(size_t a, size_t b, size_t c) {
  if (b != 0 && a > (std::numeric_limits<size_t>::max() - c) / b) return std::nullopt;
  return a * b + c;
}

uint32_t le32(std::string_view bytes, size_t offset) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[offset + size_t(i)]);
  return v;
}

int components_of(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

// RFC 4648 sec. 4 base64; nothing when `text` is not base64.
std::optional<std::string> decode_base64(std::string_view text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  if (text.size() % 4 == 1) return std::nullopt;
  std::string out;
  out.reserve(text.size() / 4 * 3 + 2);
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    const int v = value(c);
    if (v < 0) return std::nullopt;
    bits = (bits << 6) | uint32_t(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xffu);
    }
  }
  return out;
}

// The GLB container (glTF 2.0 sec. 4.4): its JSON chunk and BIN chunk, or every problem of it.
struct Container {
  std::string_view json;
  std::string_view bin;
  bool has_bin = false;
};

std::optional<Container> open_glb(std::string_view bytes, const std::string& file, Diagnostics& diagnostics) {
  auto error = [&](const std::string& message) {
    diagnostics.error(file, "", "not a valid .glb: " + message, "glTF 2.0 sec. 4.4 describes the GLB container");
    return std::nullopt;
  };
  if (bytes.size() < 12)
    return error("the file has " + plural(bytes.size(), "byte") + ", fewer than its 12-byte header");
  const uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
  if (version != kGlbVersion)
    return error("the header says version " + std::to_string(version) + "; lamina reads glTF 2.0 binaries (version 2)");
  if (length != bytes.size())
    return error("the header says the file has " + plural(length, "byte") + ", it has " + std::to_string(bytes.size()));
  Container out;
  bool has_json = false;
  size_t offset = 12, chunk = 0;
  while (offset < bytes.size()) {
    if (bytes.size() - offset < 8)
      return error("chunk " + std::to_string(chunk) + " at byte " + std::to_string(offset) +
                   " has no room for its 8-byte header");
    const uint32_t chunk_length = le32(bytes, offset), type = le32(bytes, offset + 4);
    const size_t start = offset + 8;
    if (chunk_length > bytes.size() - start)
      return error("chunk " + std::to_string(chunk) + " at byte " + std::to_string(offset) + " says it holds " +
                   plural(chunk_length, "byte") + ", beyond the end of the file");
    if (chunk_length % 4 != 0)
      return error("chunk " + std::to_string(chunk) + " at byte " + std::to_string(offset) + " holds " +
                   plural(chunk_length, "byte") + ", not a multiple of 4 (chunks are 4-byte aligned)");
    const std::string_view data = bytes.substr(start, chunk_length);
    if (chunk == 0 && type != kChunkJson) return error("the first chunk is not the JSON chunk");
    if (type == kChunkJson) {
      if (chunk != 0) return error("chunk " + std::to_string(chunk) + " is a second JSON chunk");
      out.json = data;
      has_json = true;
    } else if (type == kChunkBin) {
      if (chunk != 1) return error("chunk " + std::to_string(chunk) + " is a BIN chunk; only the second chunk may be");
      out.bin = data;
      out.has_bin = true;
    }  // other chunk types are skipped (sec. 4.4.3.1)
    offset = start + chunk_length;
    ++chunk;
  }
  if (!has_json) return error("there is no JSON chunk");
  return out;
}

// Reads and checks the JSON document into a GltfAsset, collecting every problem.
class Reader {
 public:
  Reader(GltfAsset& asset, const std::string& file, Diagnostics& diagnostics)
      : a_(asset), file_(file), diag_(diagnostics) {}

  void read(const Json& root) {
    if (!root.is_object()) return error("", "expected a glTF object, found " + json_kind(root));
    read_asset(root);
    read_strings(root, "extensionsUsed", a_.extensions_used);
    read_strings(root, "extensionsRequired", a_.extensions_required);
    // Sizes first: every index below is checked against them.
    for (const char* name : {"scenes", "nodes", "meshes", "accessors", "bufferViews", "buffers", "materials",
                             "textures", "images", "samplers"})
      sizes_[name] = array(root, name) ? array(root, name)->size() : 0;
    each(root, "buffers", [&](const Json& j, const std::string& p) { a_.buffers.push_back(read_buffer(j, p)); });
    each(root, "bufferViews", [&](const Json& j, const std::string& p) { a_.buffer_views.push_back(read_view(j, p)); });
    each(root, "accessors", [&](const Json& j, const std::string& p) { a_.accessors.push_back(read_accessor(j, p)); });
    each(root, "meshes", [&](const Json& j, const std::string& p) { a_.meshes.push_back(read_mesh(j, p)); });
    each(root, "nodes", [&](const Json& j, const std::string& p) { a_.nodes.push_back(read_node(j, p)); });
    each(root, "scenes", [&](const Json& j, const std::string& p) {
      GltfScene s;
      s.nodes = indices(j, "nodes", p, "nodes", "node");
      a_.scenes.push_back(std::move(s));
    });
    a_.scene = index(root, "scene", "", "scenes", "scene", false);
    each(root, "materials", [&](const Json& j, const std::string& p) { a_.materials.push_back(read_material(j, p)); });
    each(root, "textures", [&](const Json& j, const std::string& p) {
      GltfTexture t;
      t.sampler = index(j, "sampler", p, "samplers", "sampler", false);
      t.source = index(j, "source", p, "images", "image", false);
      a_.textures.push_back(t);
    });
    each(root, "images", [&](const Json& j, const std::string& p) { a_.images.push_back(read_image(j, p)); });
    each(root, "samplers", [&](const Json& j, const std::string& p) {
      GltfSampler s;
      s.wrap_s = wrap(j, "wrapS", p);
      s.wrap_t = wrap(j, "wrapT", p);
      a_.samplers.push_back(s);
    });
    if (diag_.ok()) check_ranges();
  }

 private:
  void error(const std::string& pointer, std::string message, std::string hint = {}) {
    diag_.error(file_, pointer, std::move(message), std::move(hint));
  }

  static const Json* member(const Json& object, const char* key) {
    auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }
  const Json* array(const Json& root, const char* key) {
    const Json* j = member(root, key);
    return j && j->is_array() ? j : nullptr;
  }

  template <class Visit>
  void each(const Json& root, const char* key, Visit visit) {
    const Json* j = member(root, key);
    if (!j) return;
    const std::string pointer = "/" + std::string(key);
    if (!j->is_array()) return error(pointer, "expected an array, found " + json_kind(*j));
    for (size_t i = 0; i < j->size(); ++i) {
      const Json& element = (*j)[i];
      const std::string p = pointer_append(pointer, i);
      if (!element.is_object()) {
        error(p, "expected an object, found " + json_kind(element));
        continue;
      }
      visit(element, p);
    }
  }

  // An integer in [lo, hi]; JSON does not tell 1 from 1.0, so an integral number is an integer.
  std::optional<size_t> integer(const Json& object, const char* key, const std::string& pointer, size_t lo, size_t hi,
                                bool required) {
    const Json* j = member(object, key);
    const std::string p = pointer_append(pointer, key);
    if (!j) {
      if (required) error(pointer, std::string("missing \"") + key + "\"");
      return std::nullopt;
    }
    if (!j->is_number()) {
      error(p, "expected an integer, found " + json_describe(*j));
      return std::nullopt;
    }
    const double v = j->get<double>();
    if (!(v == std::floor(v))) {
      error(p, "expected an integer, found " + json_dump(*j));
      return std::nullopt;
    }
    if (!(v >= double(lo) && v <= double(hi))) {
      error(p, std::string(key) + " = " + json_dump(*j) + " is out of range: expected " + std::to_string(lo) + " to " +
                   std::to_string(hi));
      return std::nullopt;
    }
    return j->is_number_unsigned() ? j->get<size_t>() : static_cast<size_t>(v);
  }

  // An index into the file's array `array` (of `what`s), or -1 when absent (and not required).
  int index(const Json& object, const char* key, const std::string& pointer, const char* array, const char* what,
            bool required) {
    const auto v = integer(object, key, pointer, 0, size_t(std::numeric_limits<int>::max()), required);
    if (!v) return -1;
    return checked_index(*v, pointer_append(pointer, key), array, what);
  }
  int checked_index(size_t v, const std::string& pointer, const char* array, const char* what) {
    const size_t size = sizes_[array];
    if (v >= size) {
      error(pointer, std::string(what) + " " + std::to_string(v) + " does not exist",
            "the file has " + plural(size, what, std::string(what) == "mesh" ? "meshes" : ""));
      return -1;
    }
    return static_cast<int>(v);
  }

  std::vector<int> indices(const Json& object, const char* key, const std::string& pointer, const char* array,
                           const char* what) {
    std::vector<int> out;
    const Json* j = member(object, key);
    if (!j) return out;
    const std::string p = pointer_append(pointer, key);
    if (!j->is_array()) {
      error(p, "expected an array of " + std::string(what) + " indices, found " + json_kind(*j));
      return out;
    }
    for (size_t k = 0; k < j->size(); ++k) {
      const Json& e = (*j)[k];
      const std::string ep = pointer_append(p, k);
      if (!e.is_number() || e.get<double>() < 0 || e.get<double>() != std::floor(e.get<double>()) ||
          e.get<double>() > double(std::numeric_limits<int>::max())) {
        error(ep, "expected the index of a " + std::string(what) + ", found " + json_dump(e));
        continue;
      }
      const int i = checked_index(e.get<size_t>(), ep, array, what);
      if (i >= 0) out.push_back(i);
    }
    return out;
  }

  double number(const Json& object, const char* key, const std::string& pointer, double fallback, double lo,
                double hi) {
    const Json* j = member(object, key);
    if (!j) return fallback;
    const std::string p = pointer_append(pointer, key);
    if (!j->is_number()) {
      error(p, "expected a number, found " + json_describe(*j));
      return fallback;
    }
    const double v = j->get<double>();
    if (!(v >= lo && v <= hi)) {
      error(p, std::string(key) + " = " + json_dump(*j) + " is out of range: expected " + json_dump(Json(lo)) + " to " +
                   json_dump(Json(hi)));
      return fallback;
    }
    return v;
  }

  template <size_t N>
  std::array<double, N> numbers(const Json& object, const char* key, const std::string& pointer,
                                std::array<double, N> fallback, double lo, double hi) {
    const Json* j = member(object, key);
    if (!j) return fallback;
    const std::string p = pointer_append(pointer, key);
    if (!j->is_array() || j->size() != N) {
      error(p, "expected an array of " + std::to_string(N) + " numbers, found " +
                   (j->is_array() ? plural(j->size(), "element") : json_kind(*j)));
      return fallback;
    }
    std::array<double, N> out{};
    for (size_t k = 0; k < N; ++k) {
      const Json& e = (*j)[k];
      if (!e.is_number() || !(e.get<double>() >= lo && e.get<double>() <= hi)) {
        error(pointer_append(p, k), "expected a number from " + json_dump(Json(lo)) + " to " + json_dump(Json(hi)) +
                                        ", found " + json_dump(e));
        return fallback;
      }
      out[k] = e.get<double>();
    }
    return out;
  }

  std::string string(const Json& object, const char* key, const std::string& pointer, bool required = false) {
    const Json* j = member(object, key);
    if (!j) {
      if (required) error(pointer, std::string("missing \"") + key + "\"");
      return {};
    }
    if (!j->is_string()) {
      error(pointer_append(pointer, key), "expected a string, found " + json_kind(*j));
      return {};
    }
    return j->get<std::string>();
  }

  bool boolean(const Json& object, const char* key, const std::string& pointer) {
    const Json* j = member(object, key);
    if (!j) return false;
    if (!j->is_boolean()) {
      error(pointer_append(pointer, key), "expected true or false, found " + json_kind(*j));
      return false;
    }
    return j->get<bool>();
  }

  // A number echoed in a message: as written, at most 32 characters.
  static std::string json_dump(const Json& j) {
    std::string text = j.is_string() ? json_describe(j) : j.dump();
    return text.size() > 32 ? text.substr(0, 32) + "..." : text;
  }

  // --- the properties lamina uses ------------------------------------------------------------------

  void read_asset(const Json& root) {
    const Json* asset = member(root, "asset");
    if (!asset) return error("", "missing \"asset\"", "every glTF file has \"asset\": {\"version\": \"2.0\"}");
    if (!asset->is_object()) return error("/asset", "expected an object, found " + json_kind(*asset));
    const std::string version = string(*asset, "version", "/asset", true);
    // "2.0" or any 2.x: minor versions are backwards compatible (sec. 2.1); minVersion may say more.
    auto major = [](const std::string& v) { return v.substr(0, v.find('.')); };
    if (!version.empty() && major(version) != "2")
      error("/asset/version", "glTF version " + quote_excerpt(version) + ": lamina reads glTF 2.x");
    const std::string min_version = string(*asset, "minVersion", "/asset");
    if (!min_version.empty() && min_version != "2.0")
      error("/asset/minVersion", "the file needs glTF " + min_version + "; lamina reads glTF 2.0");
  }

  void read_strings(const Json& root, const char* key, std::vector<std::string>& out) {
    const Json* j = member(root, key);
    if (!j) return;
    const std::string p = "/" + std::string(key);
    if (!j->is_array()) return error(p, "expected an array of extension names, found " + json_kind(*j));
    for (size_t k = 0; k < j->size(); ++k) {
      if (!(*j)[k].is_string()) {
        error(pointer_append(p, k), "expected an extension name, found " + json_kind((*j)[k]));
        continue;
      }
      out.push_back((*j)[k].get<std::string>());
    }
  }

  GltfBuffer read_buffer(const Json& j, const std::string& p) {
    GltfBuffer b;
    b.uri = string(j, "uri", p);
    b.byte_length = integer(j, "byteLength", p, 1, kMaxBinaryFileBytes, true).value_or(0);
    return b;
  }

  GltfBufferView read_view(const Json& j, const std::string& p) {
    GltfBufferView v;
    v.buffer = index(j, "buffer", p, "buffers", "buffer", true);
    v.byte_offset = integer(j, "byteOffset", p, 0, kMaxBinaryFileBytes, false).value_or(0);
    v.byte_length = integer(j, "byteLength", p, 1, kMaxBinaryFileBytes, true).value_or(0);
    if (const auto stride = integer(j, "byteStride", p, 4, 252, false)) {
      if (*stride % 4 != 0)
        error(pointer_append(p, "byteStride"), "byteStride = " + std::to_string(*stride) + " is not a multiple of 4");
      v.byte_stride = *stride;
    }
    return v;
  }

  GltfAccessor read_accessor(const Json& j, const std::string& p) {
    GltfAccessor a;
    a.buffer_view = index(j, "bufferView", p, "bufferViews", "buffer view", false);
    a.byte_offset = integer(j, "byteOffset", p, 0, kMaxBinaryFileBytes, false).value_or(0);
    a.component_type = int(integer(j, "componentType", p, 0, 1u << 16, true).value_or(kFloat));
    if (component_size(a.component_type) == 0)
      error(pointer_append(p, "componentType"), "unknown component type " + std::to_string(a.component_type),
            "glTF's are 5120 to 5123, 5125 and 5126");
    a.normalized = boolean(j, "normalized", p);
    a.count = integer(j, "count", p, 1, size_t{1} << 62, true).value_or(0);
    a.type = string(j, "type", p, true);
    a.components = components_of(a.type);
    if (!a.type.empty() && a.components == 0)
      error(pointer_append(p, "type"), "unknown accessor type " + quote_excerpt(a.type),
            "SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
    a.sparse = member(j, "sparse") != nullptr;
    return a;
  }

  GltfMesh read_mesh(const Json& j, const std::string& p) {
    GltfMesh m;
    m.name = string(j, "name", p);
    const Json* primitives = member(j, "primitives");
    if (!primitives) {
      error(p, "missing \"primitives\"");
      return m;
    }
    each(j, "primitives", [&](const Json& pj, const std::string& pp) {
      GltfPrimitive prim;
      const Json* attributes = member(pj, "attributes");
      if (!attributes || !attributes->is_object()) {
        error(attributes ? pointer_append(pp, "attributes") : pp,
              "expected \"attributes\": an object of accessor indices");
      } else {
        for (const auto& [name, value] : attributes->items()) {
          const std::string ap = pointer_append(pointer_append(pp, "attributes"), name);
          if (!value.is_number() || value.get<double>() < 0 || value.get<double>() != std::floor(value.get<double>()) ||
              value.get<double>() > double(std::numeric_limits<int>::max())) {
            error(ap, "expected the index of an accessor, found " + json_dump(value));
            continue;
          }
          const int i = checked_index(value.get<size_t>(), ap, "accessors", "accessor");
          if (i >= 0) prim.attributes[name] = i;
        }
      }
      prim.indices = index(pj, "indices", pp, "accessors", "accessor", false);
      prim.material = index(pj, "material", pp, "materials", "material", false);
      prim.mode = int(integer(pj, "mode", pp, 0, 6, false).value_or(kModeTriangles));
      m.primitives.push_back(std::move(prim));
    });
    return m;
  }

  GltfNode read_node(const Json& j, const std::string& p) {
    GltfNode n;
    n.name = string(j, "name", p);
    n.mesh = index(j, "mesh", p, "meshes", "mesh", false);
    n.children = indices(j, "children", p, "nodes", "node");
    constexpr double kHuge = std::numeric_limits<double>::max();
    if (member(j, "matrix")) {
      n.matrix = numbers<16>(j, "matrix", p, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, -kHuge, kHuge);
      for (const char* trs : {"translation", "rotation", "scale"})
        if (member(j, trs))
          error(pointer_append(p, trs), std::string("a node has either \"matrix\" or \"") + trs + "\", not both");
    }
    n.translation = numbers<3>(j, "translation", p, n.translation, -kHuge, kHuge);
    n.rotation = numbers<4>(j, "rotation", p, n.rotation, -1.0, 1.0);
    n.scale = numbers<3>(j, "scale", p, n.scale, -kHuge, kHuge);
    return n;
  }

  GltfTextureInfo texture_info(const Json& object, const char* key, const std::string& pointer) {
    GltfTextureInfo t;
    const Json* j = member(object, key);
    if (!j) return t;
    const std::string p = pointer_append(pointer, key);
    if (!j->is_object()) {
      error(p, "expected a texture reference {\"index\": ...}, found " + json_kind(*j));
      return t;
    }
    t.index = index(*j, "index", p, "textures", "texture", true);
    t.tex_coord = int(integer(*j, "texCoord", p, 0, 1u << 16, false).value_or(0));
    return t;
  }

  GltfMaterial read_material(const Json& j, const std::string& p) {
    GltfMaterial m;
    m.name = string(j, "name", p);
    if (const Json* pbr = member(j, "pbrMetallicRoughness")) {
      const std::string pp = pointer_append(p, "pbrMetallicRoughness");
      if (!pbr->is_object()) {
        error(pp, "expected an object, found " + json_kind(*pbr));
      } else {
        m.base_color_factor = numbers<4>(*pbr, "baseColorFactor", pp, m.base_color_factor, 0.0, 1.0);
        m.base_color_texture = texture_info(*pbr, "baseColorTexture", pp);
        m.metallic_factor = number(*pbr, "metallicFactor", pp, 1.0, 0.0, 1.0);
        m.roughness_factor = number(*pbr, "roughnessFactor", pp, 1.0, 0.0, 1.0);
        m.metallic_roughness_texture = texture_info(*pbr, "metallicRoughnessTexture", pp);
      }
    }
    m.normal_texture = texture_info(j, "normalTexture", p);
    m.occlusion_texture = texture_info(j, "occlusionTexture", p);
    m.emissive_texture = texture_info(j, "emissiveTexture", p);
    m.emissive_factor = numbers<3>(j, "emissiveFactor", p, m.emissive_factor, 0.0, 1.0);
    if (member(j, "alphaMode")) {
      m.alpha_mode = string(j, "alphaMode", p);
      if (m.alpha_mode != "OPAQUE" && m.alpha_mode != "MASK" && m.alpha_mode != "BLEND")
        error(pointer_append(p, "alphaMode"), "unknown alphaMode " + quote_excerpt(m.alpha_mode),
              "OPAQUE, MASK or BLEND");
    }
    if (const Json* extensions = member(j, "extensions")) {
      if (extensions->is_object())
        m.extensions = *extensions;
      else
        error(pointer_append(p, "extensions"), "expected an object, found " + json_kind(*extensions));
    }
    if (const Json* extras = member(j, "extras")) m.extras = *extras;
    return m;
  }

  GltfImage read_image(const Json& j, const std::string& p) {
    GltfImage image;
    image.name = string(j, "name", p);
    image.uri = string(j, "uri", p);
    image.buffer_view = index(j, "bufferView", p, "bufferViews", "buffer view", false);
    image.mime_type = string(j, "mimeType", p);
    const bool has_uri = member(j, "uri") != nullptr, has_view = member(j, "bufferView") != nullptr;
    if (has_uri == has_view)
      error(p, has_uri ? "an image has either \"uri\" or \"bufferView\", not both"
                       : "an image needs \"uri\" or \"bufferView\"");
    return image;
  }

  int wrap(const Json& j, const char* key, const std::string& p) {
    const auto v = integer(j, key, p, 0, 1u << 16, false);
    if (!v) return kRepeat;
    if (*v != size_t(kRepeat) && *v != size_t(kClampToEdge) && *v != size_t(kMirroredRepeat)) {
      error(pointer_append(p, key), "unknown wrap mode " + std::to_string(*v), "10497, 33071 or 33648");
      return kRepeat;
    }
    return int(*v);
  }

  // Every view inside its buffer, every accessor inside its view, aligned as sec. 3.6.2.4 asks:
  // from the lengths the file declares; the bytes behind them are checked when they are read.
  void check_ranges() {
    for (size_t v = 0; v < a_.buffer_views.size(); ++v) {
      const GltfBufferView& view = a_.buffer_views[v];
      const size_t buffer_length = a_.buffers[size_t(view.buffer)].byte_length;
      const auto end = mul_add(1, view.byte_offset, view.byte_length);
      if (!end || *end > buffer_length)
        error(at("bufferViews", v) + "/byteLength", "buffer view " + std::to_string(v) +
                                                        " ends beyond its buffer, which holds " +
                                                        plural(buffer_length, "byte"));
    }
    for (size_t i = 0; i < a_.accessors.size(); ++i) {
      const GltfAccessor& a = a_.accessors[i];
      if (a.buffer_view < 0 || a.components == 0) continue;
      const size_t component = component_size(a.component_type);
      if (component == 0) continue;
      const std::string pointer = at("accessors", i);
      const GltfBufferView& view = a_.buffer_views[size_t(a.buffer_view)];
      const size_t element = component * size_t(a.components);
      const size_t stride = view.byte_stride != 0 ? view.byte_stride : element;
      if (a.byte_offset % component != 0 || (view.byte_offset + a.byte_offset) % component != 0)
        error(pointer + "/byteOffset",
              "the accessor's data does not start at a multiple of its component size (" + plural(component, "byte") +
                  ")",
              "glTF 2.0 sec. 3.6.2.4: accessor and buffer view offsets are aligned to the component size");
      if (stride < element || stride % component != 0)
        error(at("bufferViews", size_t(a.buffer_view)) + "/byteStride",
              "byteStride " + std::to_string(stride) + " does not fit the elements of accessor " + std::to_string(i) +
                  " (" + plural(element, "byte") + ")",
              "a stride is a multiple of the component size and at least one element");
      const auto needed = mul_add(a.count - 1, stride, element);
      const auto end = needed ? mul_add(1, a.byte_offset, *needed) : std::nullopt;
      if (!end || *end > view.byte_length)
        error(pointer + "/count", "count = " + std::to_string(a.count) + " elements of " + plural(element, "byte") +
                                      " from byte " + std::to_string(a.byte_offset) + " reach beyond buffer view " +
                                      std::to_string(a.buffer_view) + ", which holds " +
                                      plural(view.byte_length, "byte"));
    }
  }

  GltfAsset& a_;
  const std::string& file_;
  Diagnostics& diag_;
  std::map<std::string, size_t> sizes_;
};

}  // namespace

size_t component_size(int component_type) {
  switch (component_type) {
    case kByte:
    case kUnsignedByte: return 1;
    case kShort:
    case kUnsignedShort: return 2;
    case kUnsignedInt:
    case kFloat: return 4;
    default: return 0;
  }
}

GltfAsset read_gltf(std::string_view bytes, const std::filesystem::path& path, const AssetPolicy& policy) {
  GltfAsset asset;
  asset.path = path;
  asset.policy_ = policy;
  const std::string file = path.string();
  Diagnostics diagnostics;
  std::string_view json = bytes;
  asset.binary = bytes.size() >= 4 && le32(bytes, 0) == kGlbMagic;
  if (asset.binary) {
    const auto container = open_glb(bytes, file, diagnostics);
    if (!container) throw Error(diagnostics.errors());
    json = container->json;
    if (container->has_bin) asset.bin_chunk_ = std::string(container->bin);
  }
  if (json.size() > kMaxJsonFileBytes)
    throw Error({Diagnostic{Severity::Error, file, "",
                            "the glTF JSON is " + std::to_string(json.size()) + " bytes, more than the " +
                                byte_size_text(kMaxJsonFileBytes) + " lamina reads",
                            ""}});
  const auto root = parse_json(json, file, diagnostics, "a glTF file is a JSON object with \"asset\"");
  if (!root) throw Error(diagnostics.errors());
  Reader(asset, file, diagnostics).read(*root);
  if (!diagnostics.ok()) throw Error(diagnostics.errors());
  asset.data_.resize(asset.buffers.size());
  return asset;
}

void GltfAsset::fail(const std::string& pointer, const std::string& message, const std::string& hint) const {
  throw Error({Diagnostic{Severity::Error, path.string(), pointer, message, hint}});
}

std::string GltfAsset::decode_data_uri(const std::string& uri, const std::string& pointer) const {
  // RFC 2397: data:[<mediatype>][;base64],<data>; glTF's are base64 (sec. 3.3.3).
  const size_t comma = uri.find(',');
  if (comma == std::string::npos) fail(pointer, "a data: URI without ',' before its data");
  const std::string_view header(uri.data(), comma);
  if (header.size() < 7 || header.substr(header.size() - 7) != ";base64")
    fail(pointer, "a data: URI that is not base64-encoded", "glTF data URIs are data:<type>;base64,<data>");
  auto decoded = decode_base64(std::string_view(uri).substr(comma + 1));
  if (!decoded) fail(pointer, "the data: URI's data is not valid base64");
  return std::move(*decoded);
}

const std::string& GltfAsset::buffer_data(int index) const {
  auto& slot = data_[size_t(index)];
  if (slot) return *slot;
  const GltfBuffer& buffer = buffers[size_t(index)];
  const std::string pointer = at("buffers", size_t(index));
  std::string bytes;
  std::string source;
  if (buffer.uri.empty()) {
    if (!binary || index != 0)
      fail(pointer, "buffer " + std::to_string(index) + " has no \"uri\"",
           binary ? "in a .glb only buffer 0 may be the BIN chunk" : "a .gltf names each buffer's file by its uri");
    if (bin_chunk_.empty() && buffer.byte_length > 0) fail(pointer, "buffer 0 is the BIN chunk, but the .glb has none");
    // sec. 4.4.3.3: the chunk may be up to 3 bytes longer than byteLength (padding).
    if (bin_chunk_.size() < buffer.byte_length || bin_chunk_.size() > buffer.byte_length + 3)
      fail(pointer + "/byteLength",
           "byteLength = " + std::to_string(buffer.byte_length) + ", but the BIN chunk holds " +
               plural(bin_chunk_.size(), "byte"),
           "the BIN chunk holds the buffer and at most 3 bytes of padding");
    bytes = bin_chunk_;
    source = "the BIN chunk";
  } else if (buffer.uri.rfind("data:", 0) == 0) {
    bytes = decode_data_uri(buffer.uri, pointer + "/uri");
    source = "its data: URI";
  } else {
    try {
      const Reference ref = resolve_reference(path, uri_decode(buffer.uri), ReferenceScope::NamingFolder, policy_);
      bytes = read_reference(ref, kMaxBinaryFileBytes, policy_);
    } catch (const ReferenceError& e) {
      fail(pointer + "/uri", std::string("buffer file ") + e.what(), e.hint());
    }
    source = "its file";
  }
  if (bytes.size() < buffer.byte_length)
    fail(pointer + "/byteLength", "byteLength = " + std::to_string(buffer.byte_length) + ", but " + source + " holds " +
                                      plural(bytes.size(), "byte"));
  bytes.resize(buffer.byte_length);
  slot = std::make_unique<std::string>(std::move(bytes));
  return *slot;
}

std::string_view GltfAsset::view_data(int index) const {
  const GltfBufferView& view = buffer_views[size_t(index)];
  return std::string_view(buffer_data(view.buffer)).substr(view.byte_offset, view.byte_length);
}

GltfAccessorData GltfAsset::accessor_data(int index) const {
  const GltfAccessor& a = accessors[size_t(index)];
  GltfAccessorData out;
  out.element_size = component_size(a.component_type) * size_t(a.components);
  out.count = a.count;
  out.stride = out.element_size;
  if (a.buffer_view < 0) return out;
  const GltfBufferView& view = buffer_views[size_t(a.buffer_view)];
  if (view.byte_stride != 0) out.stride = view.byte_stride;
  out.data = reinterpret_cast<const unsigned char*>(view_data(a.buffer_view).data()) + a.byte_offset;
  return out;
}

std::string GltfAsset::image_bytes(int index) const {
  const GltfImage& image = images[size_t(index)];
  const std::string pointer = at("images", size_t(index));
  if (image.buffer_view >= 0) return std::string(view_data(image.buffer_view));
  if (image.uri.rfind("data:", 0) == 0) return decode_data_uri(image.uri, pointer + "/uri");
  try {
    const Reference ref = resolve_reference(path, uri_decode(image.uri), ReferenceScope::NamingFolder, policy_);
    return read_reference(ref, kMaxBinaryFileBytes, policy_);
  } catch (const ReferenceError& e) {
    fail(pointer + "/uri", std::string("image file ") + e.what(), e.hint());
  }
}

}  // namespace lamina::gltf
