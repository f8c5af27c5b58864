#include "graph/scene/mesh_file.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <optional>

#include "graph/json_read.h"
#include "graph/number_text.h"
#include "graph/scene/mesh_shading.h"
#include "graph/scene/scene_fields.h"

namespace lamina {

namespace {

// glTF 2.0 sec. 5.11.4: bufferView.byteStride is at most 252.
constexpr size_t kMaxByteStride = 252;
// A node transform whose determinant is this small relative to its largest axis cubed flattens
// its meshes onto a plane or line: normals are undefined there.
constexpr double kSingularDeterminant = 1e-12;

constexpr int kUnvisited = -2;
constexpr int kRoot = -1;

// Geometry only: images are neither decoded nor checked.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::string at(const char* array, size_t index) { return "/" + std::string(array) + "/" + std::to_string(index); }
std::string at(const char* array, int index) { return at(array, static_cast<size_t>(index)); }

std::string plural(size_t n, const std::string& one, const std::string& many = {}) {
  return std::to_string(n) + " " + (n == 1 ? one : many.empty() ? one + "s" : many);
}

// a * b + c, or nothing when it would wrap around.
std::optional<size_t> mul_add(size_t a, size_t b, size_t c) {
  if (b != 0 && a > (std::numeric_limits<size_t>::max() - c) / b) return std::nullopt;
  return a * b + c;
}

const char* type_name(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "?";
  }
}

class MeshLoader {
 public:
  MeshLoader(const tinygltf::Model& model, const std::filesystem::path& path) : model_(model), file_(path.string()) {}

  TriangleMesh load() {
    if (!model_.scenes.empty()) {
      const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(scene) >= model_.scenes.size())
        fail("/scene", "the default scene " + std::to_string(scene) + " does not exist",
             "the file has " + plural(model_.scenes.size(), "scene"));
      walk_scene(static_cast<size_t>(scene));
    } else {
      for (size_t m = 0; m < model_.meshes.size(); ++m) add_mesh(m, glm::dmat4(1.0), at("meshes", m));
    }
    if (mesh_.indices.empty())
      fail("", "holds no triangles", "lamina reads the triangle, strip and fan primitives of the default scene");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& pointer, const std::string& message, const std::string& hint = {}) const {
    throw Error({Diagnostic{Severity::Error, file_, pointer, message, hint}});
  }

  // --- the node hierarchy ----------------------------------------------------------------------

  // glTF 2.0 sec. 3.5.1: the nodes form disjoint strict trees (no cycles, at most one parent each).
  // Checking that each node is reached once keeps the walk linear in the file's size: a node
  // listed twice as a child would otherwise be walked exponentially often in a deep hierarchy.
  void walk_scene(size_t scene) {
    struct Pending {
      int node;
      int parent;
      glm::dmat4 parent_world;
      std::string reference;  // where the file names this node
    };
    std::vector<int> parent_of(model_.nodes.size(), kUnvisited);
    std::vector<Pending> stack;
    const auto& roots = model_.scenes[scene].nodes;
    for (size_t k = roots.size(); k-- > 0;)
      stack.push_back({roots[k], kRoot, glm::dmat4(1.0), at("scenes", scene) + "/nodes/" + std::to_string(k)});
    while (!stack.empty()) {  // depth first, children in order: the order a recursion would take
      Pending item = std::move(stack.back());
      stack.pop_back();
      if (item.node < 0 || static_cast<size_t>(item.node) >= model_.nodes.size())
        fail(item.reference, "node " + std::to_string(item.node) + " does not exist",
             "the file has " + plural(model_.nodes.size(), "node"));
      const auto index = static_cast<size_t>(item.node);
      if (parent_of[index] != kUnvisited) fail(item.reference, second_reference(item.node, item.parent, parent_of));
      parent_of[index] = item.parent;
      const tinygltf::Node& node = model_.nodes[index];
      const std::string pointer = at("nodes", index);
      const glm::dmat4 world = item.parent_world * local_matrix(node, pointer);  // glTF: T * R * S
      if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
          fail(pointer + "/mesh", "mesh " + std::to_string(node.mesh) + " does not exist",
               "the file has " + plural(model_.meshes.size(), "mesh", "meshes"));
        // Only where it places a mesh: a collapsed node without one (a hidden helper) is harmless.
        check_transform(world, pointer);
        add_mesh(static_cast<size_t>(node.mesh), world, pointer + "/mesh");
      }
      for (size_t k = node.children.size(); k-- > 0;)
        stack.push_back({node.children[k], item.node, world, pointer + "/children/" + std::to_string(k)});
    }
  }

  // Why `node`, reached again from `parent`, breaks the strict tree.
  static std::string second_reference(int node, int parent, const std::vector<int>& parent_of) {
    std::string path = std::to_string(node);
    for (int p = parent; p >= 0; p = parent_of[static_cast<size_t>(p)]) {
      path = std::to_string(p) + " -> " + path;
      if (p == node) return "the node hierarchy has a cycle: " + path;
    }
    const int first = parent_of[static_cast<size_t>(node)];
    return "node " + std::to_string(node) + " is reached a second time (it is already " +
           (first == kRoot ? std::string("a root of the scene") : "a child of node " + std::to_string(first)) +
           "): glTF nodes form strict trees, each node with at most one parent";
  }

  glm::dmat4 local_matrix(const tinygltf::Node& node, const std::string& pointer) const {
    glm::dmat4 m(1.0);
    if (node.matrix.size() == 16) {
      m = glm::make_mat4(node.matrix.data());  // column-major, as glTF
    } else {
      if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
      if (node.rotation.size() == 4) {
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double length = glm::length(q);
        if (!(length > 1e-12) || !std::isfinite(length))
          fail(pointer + "/rotation", "the rotation quaternion has zero length or is not finite",
               "the identity is [0, 0, 0, 1] (x, y, z, w)");
        m *= glm::mat4_cast(q / length);
      }
      if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    }
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(m[c][r])) fail(pointer, "the node's transform is not finite");
    return m;
  }

  // The accumulated transform must keep meshes three-dimensional and within the scene's range.
  void check_transform(const glm::dmat4& world, const std::string& pointer) const {
    const glm::dmat3 linear(world);
    double largest = 0.0;
    for (int c = 0; c < 3; ++c) largest = std::max(largest, glm::length(linear[c]));
    const double det = glm::determinant(linear);
    if (!std::isfinite(det) || !(std::abs(det) > kSingularDeterminant * largest * largest * largest))
      fail(pointer,
           "the node's transform (with its ancestors') is singular: determinant " + number_text(det) +
               " flattens its meshes, whose normals are then undefined",
           "give every scale component a magnitude well above 0");
  }

  // --- accessors -------------------------------------------------------------------------------

  // Accessor `index`, referred to at `reference` as `what`, after checking that it exists, is
  // dense and has `components` components.
  const tinygltf::Accessor& accessor(int index, int components, const std::string& reference,
                                     const std::string& what) const {
    if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size())
      fail(reference, "accessor " + std::to_string(index) + " does not exist",
           "the file has " + plural(model_.accessors.size(), "accessor"));
    const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(index)];
    const std::string pointer = at("accessors", index);
    if (a.sparse.isSparse) fail(pointer + "/sparse", "sparse accessors are not supported", "store the values densely");
    if (tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type)) != components)
      fail(pointer + "/type", what + " must be " + type_name(components));
    switch (a.componentType) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      case TINYGLTF_COMPONENT_TYPE_SHORT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      case TINYGLTF_COMPONENT_TYPE_FLOAT: break;
      default:
        fail(pointer + "/componentType", "unknown component type " + std::to_string(a.componentType),
             "glTF's are 5120 to 5123, 5125 and 5126");
    }
    return a;
  }

  // Accessor `index` as accessor() checks it, and its layout against its buffer view and buffer:
  // nothing is read or allocated for it before this says the file holds its bytes.
  const tinygltf::Accessor& checked_accessor(int index, int components, const std::string& reference,
                                             const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, components, reference, what);
    if (a.bufferView < 0) return a;  // glTF: no buffer view reads zeros
    const std::string pointer = at("accessors", index);
    if (static_cast<size_t>(a.bufferView) >= model_.bufferViews.size())
      fail(pointer + "/bufferView", "buffer view " + std::to_string(a.bufferView) + " does not exist",
           "the file has " + plural(model_.bufferViews.size(), "buffer view"));
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(a.bufferView)];
    const std::string view_pointer = at("bufferViews", a.bufferView);
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model_.buffers.size())
      fail(view_pointer + "/buffer", "buffer " + std::to_string(view.buffer) + " does not exist",
           "the file has " + plural(model_.buffers.size(), "buffer"));
    const size_t buffer_size = model_.buffers[static_cast<size_t>(view.buffer)].data.size();
    const auto view_end = mul_add(1, view.byteOffset, view.byteLength);
    if (!view_end || *view_end > buffer_size)
      fail(view_pointer + "/byteLength", "buffer view " + std::to_string(a.bufferView) +
                                             " ends beyond its buffer, which holds " + plural(buffer_size, "byte"));
    const size_t element_size = element_bytes(a, components);
    const size_t stride = stride_of(a, view, components);
    if (stride < element_size || stride > kMaxByteStride || stride % component_bytes(a) != 0)
      fail(view_pointer + "/byteStride",
           "byteStride " + std::to_string(stride) + " does not fit " + what + " elements of " +
               plural(element_size, "byte"),
           "a stride is a multiple of the component size, at least one element and at most 252");
    if (a.count > 0) {
      const auto needed = mul_add(a.count - 1, stride, element_size);
      const auto end = needed ? mul_add(1, a.byteOffset, *needed) : std::nullopt;
      if (!end || *end > view.byteLength)
        fail(pointer + "/count", "count = " + std::to_string(a.count) + " elements of " + plural(element_size, "byte") +
                                     " from byte " + std::to_string(a.byteOffset) + " reach beyond buffer view " +
                                     std::to_string(a.bufferView) + ", which holds " + plural(view.byteLength, "byte"));
    }
    return a;
  }

  static size_t component_bytes(const tinygltf::Accessor& a) {
    return static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType)));
  }
  static size_t element_bytes(const tinygltf::Accessor& a, int components) {
    return component_bytes(a) * static_cast<size_t>(components);
  }
  static size_t stride_of(const tinygltf::Accessor& a, const tinygltf::BufferView& view, int components) {
    return view.byteStride != 0 ? view.byteStride : element_bytes(a, components);
  }

  // The elements of an accessor checked_accessor() passed, as doubles, normalised integers mapped
  // as the glTF 2.0 specification's "Accessor data types" section says.
  std::vector<double> read_accessor(int index, int components, const std::string& what) const {
    const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(index)];
    const auto n = static_cast<size_t>(components);
    if (a.bufferView < 0) return std::vector<double>(a.count * n, 0.0);
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(a.bufferView)];
    const size_t size = component_bytes(a), stride = stride_of(a, view, components);
    const unsigned char* data =
        model_.buffers[static_cast<size_t>(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    std::vector<double> out(a.count * n);
    for (size_t i = 0; i < a.count; ++i) {
      const unsigned char* element = data + i * stride;
      for (size_t c = 0; c < n; ++c) {
        const double v = component(element + c * size, a.componentType, a.normalized);
        if (!std::isfinite(v))
          fail(at("accessors", index), "element " + std::to_string(i) + " of " + what + " is not a finite number");
        out[i * n + c] = v;
      }
    }
    return out;
  }

  template <class T>
  static T load_as(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }

  static double component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load_as<uint8_t>(p) / (normalized ? 255.0 : 1.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load_as<uint16_t>(p) / (normalized ? 65535.0 : 1.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load_as<uint32_t>(p);
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return normalized ? std::max(load_as<int8_t>(p) / 127.0, -1.0) : load_as<int8_t>(p);
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return normalized ? std::max(load_as<int16_t>(p) / 32767.0, -1.0) : load_as<int16_t>(p);
      default: return load_as<float>(p);  // TINYGLTF_COMPONENT_TYPE_FLOAT; accessor() admits no other type
    }
  }

  static bool is_triangles(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
  }

  static std::vector<uint32_t> triangles(int mode, const std::vector<uint32_t>& v) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      out.assign(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 3 * 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // glTF 2.0 "Meshes: topology": odd triangles swap two vertices to keep the winding.
      for (size_t i = 0; i + 2 < v.size(); ++i)
        out.insert(out.end(), i % 2 ? std::initializer_list<uint32_t>{v[i + 1], v[i], v[i + 2]}
                                    : std::initializer_list<uint32_t>{v[i], v[i + 1], v[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (size_t i = 1; i + 1 < v.size(); ++i) out.insert(out.end(), {v[i], v[i + 1], v[0]});
    }
    return out;
  }

  // --- meshes ----------------------------------------------------------------------------------

  // The triangles `count` vertex references make in `mode` (glTF 2.0 "Meshes: topology").
  static size_t triangle_count(int mode, size_t count) {
    if (mode == TINYGLTF_MODE_TRIANGLES) return count / 3;
    return count >= 3 ? count - 2 : 0;  // strips and fans
  }

  // Checked before the indices are read: the first primitive over the limit is blamed by its
  // count, a later one by the instance that took the file over it.
  void check_triangle_budget(int mode, size_t count, const std::string& reference, const std::string& count_pointer) {
    if (triangle_count(mode, count) > kMaxMeshTriangles - triangles_)
      fail(triangles_ == 0 ? count_pointer : reference,
           "the file's meshes, over all their instances, have more than " + std::to_string(kMaxMeshTriangles) +
               " triangles, more than lamina reads from a mesh file",
           "simplify the mesh, or split it over several objects");
  }

  // One instance of mesh `index` under `world`; `reference` is where the file places it (the
  // node's "mesh", or the mesh itself for files without scenes), for the limits' errors.
  void add_mesh(size_t index, const glm::dmat4& world, const std::string& reference) {
    const tinygltf::Mesh& mesh = model_.meshes[index];
    const glm::dmat3 linear(world);
    const glm::dmat3 normal_matrix = glm::inverseTranspose(linear);
    const bool mirrored = glm::determinant(linear) < 0.0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      const std::string prim = at("meshes", index) + "/primitives/" + std::to_string(p);
      auto position = primitive.attributes.find("POSITION");
      // Points and lines have no surface; glTF says to skip primitives without positions.
      if (!is_triangles(primitive.mode) || position == primitive.attributes.end()) continue;
      if (++primitives_ > kMaxMeshPrimitives)
        fail(reference, "this instance takes the file beyond " + std::to_string(kMaxMeshPrimitives) +
                            " triangle primitives over all instances of its meshes, more than lamina reads");
      const std::string position_reference = prim + "/attributes/POSITION";
      const size_t count = checked_accessor(position->second, 3, position_reference, "POSITION").count;
      if (count > kMaxMeshVertices - vertices_)
        fail(vertices_ == 0 ? at("accessors", position->second) + "/count" : reference,
             "the file's meshes, over all their instances, have more than " + std::to_string(kMaxMeshVertices) +
                 " vertices, more than lamina reads from a mesh file",
             "simplify the mesh, or split it over several objects");
      vertices_ += count;
      const std::vector<double> positions = read_accessor(position->second, 3, "POSITION");
      std::vector<uint32_t> order;
      if (primitive.indices >= 0) {
        const std::string indices_reference = prim + "/indices";
        const tinygltf::Accessor& a = checked_accessor(primitive.indices, 1, indices_reference, "indices");
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
          fail(at("accessors", primitive.indices) + "/componentType", "indices must be unsigned integers",
               "5121 (byte), 5123 (short) or 5125 (int)");
        check_triangle_budget(primitive.mode, a.count, reference, at("accessors", primitive.indices) + "/count");
        const std::vector<double> indices = read_accessor(primitive.indices, 1, "indices");
        order.reserve(indices.size());
        for (size_t k = 0; k < indices.size(); ++k) {
          if (indices[k] >= static_cast<double>(count))
            fail(at("accessors", primitive.indices),
                 "index " + std::to_string(static_cast<uint64_t>(indices[k])) + " (element " + std::to_string(k) +
                     ") is beyond the " + std::to_string(count) + " vertices of POSITION",
                 "indices count from 0");
          order.push_back(static_cast<uint32_t>(indices[k]));
        }
      } else {
        check_triangle_budget(primitive.mode, count, reference, at("accessors", position->second) + "/count");
        for (size_t i = 0; i < count; ++i) order.push_back(static_cast<uint32_t>(i));
      }
      const std::vector<uint32_t> tris = triangles(primitive.mode, order);
      triangles_ += tris.size() / 3;
      if (tris.empty()) continue;
      auto attribute = [&](const char* name, int components) {
        auto it = primitive.attributes.find(name);
        if (it == primitive.attributes.end()) return std::vector<double>();
        const std::string attribute_reference = prim + "/attributes/" + name;
        const size_t n = checked_accessor(it->second, components, attribute_reference, name).count;
        if (n != count)
          fail(attribute_reference,
               std::string(name) + " has " + std::to_string(n) + " elements, POSITION " + std::to_string(count),
               "every attribute of a primitive has one element per vertex");
        return read_accessor(it->second, components, name);
      };
      const std::vector<double> n = attribute("NORMAL", 3), t = attribute("TANGENT", 4),
                                uv = attribute("TEXCOORD_0", 2);
      TriangleMesh piece;
      for (size_t i = 0; i < count; ++i) {
        const glm::dvec3 q(world * glm::dvec4(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0));
        for (int c = 0; c < 3; ++c)
          if (!(std::abs(q[c]) <= kSceneNumberLimit))
            fail(at("accessors", position->second), "vertex " + std::to_string(i) + " lies at " + number_text(q[c]) +
                                                        " after the node transforms, beyond the scene's range of " +
                                                        number_text(kSceneNumberLimit));
        piece.positions.emplace_back(q);
        if (!n.empty()) {
          const glm::dvec3 normal = normal_matrix * glm::make_vec3(&n[3 * i]);
          if (!(glm::length(normal) > 0.0))
            fail(at("accessors", primitive.attributes.at("NORMAL")), "normal " + std::to_string(i) + " has zero length",
                 "normals are unit vectors");
          piece.normals.emplace_back(glm::normalize(normal));
        }
        piece.uvs.push_back(uv.empty() ? glm::vec2(0.0f) : glm::vec2(uv[2 * i], uv[2 * i + 1]));
      }
      for (size_t k = 0; k < tris.size(); k += 3) {
        // A mirroring transform turns counter-clockwise triangles clockwise: swap two corners.
        piece.indices.insert(piece.indices.end(),
                             {tris[k], tris[mirrored ? k + 2 : k + 1], tris[mirrored ? k + 1 : k + 2]});
      }
      if (n.empty()) generate_normals(piece);
      if (t.empty() || n.empty()) {
        generate_tangents(piece);
      } else {
        for (size_t i = 0; i < count; ++i) {
          const glm::dvec3 normal(piece.normals[i]);
          glm::dvec3 tangent = linear * glm::make_vec3(&t[4 * i]);
          tangent -= normal * glm::dot(normal, tangent);
          if (!(glm::length(tangent) > 1e-12))
            fail(at("accessors", primitive.attributes.at("TANGENT")),
                 "tangent " + std::to_string(i) + " has zero length or is parallel to its normal",
                 "tangents are unit vectors orthogonal to the normal");
          const double w = t[4 * i + 3];
          // A mirroring transform flips cross(n, t) relative to the transformed bitangent.
          piece.tangents.emplace_back(glm::vec3(glm::normalize(tangent)), static_cast<float>(mirrored ? -w : w));
        }
      }
      append(piece);
    }
  }

  void append(const TriangleMesh& piece) {
    auto base = static_cast<uint32_t>(mesh_.positions.size());
    mesh_.positions.insert(mesh_.positions.end(), piece.positions.begin(), piece.positions.end());
    mesh_.normals.insert(mesh_.normals.end(), piece.normals.begin(), piece.normals.end());
    mesh_.tangents.insert(mesh_.tangents.end(), piece.tangents.begin(), piece.tangents.end());
    mesh_.uvs.insert(mesh_.uvs.end(), piece.uvs.begin(), piece.uvs.end());
    for (uint32_t i : piece.indices) mesh_.indices.push_back(base + i);
  }

  const tinygltf::Model& model_;
  std::string file_;
  TriangleMesh mesh_;
  size_t vertices_ = 0, triangles_ = 0, primitives_ = 0;  // over every instance so far
};

}  // namespace

namespace {

TriangleMesh load_mesh_bytes(const std::string& bytes, const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const bool binary = bytes.compare(0, 4, "glTF") == 0;
  const std::string base = path.parent_path().string();
  bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                 reinterpret_cast<const unsigned char*>(bytes.data()),
                                                 static_cast<unsigned>(bytes.size()), base)
                   : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(),
                                                static_cast<unsigned>(bytes.size()), base);
  if (!ok) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
    throw IoError(path.string() + ": cannot read glTF: " + (error.empty() ? "unknown error" : error));
  }
  return MeshLoader(model, path).load();
}

}  // namespace

TriangleMesh load_mesh_file(const Reference& file, const AssetPolicy& policy) {
  return load_mesh_bytes(read_reference(file, kMaxBinaryFileBytes, policy), file.path);
}

TriangleMesh load_mesh_file(const std::filesystem::path& path) {
  return load_mesh_bytes(read_input_file(path, kMaxBinaryFileBytes), path);
}

}  // namespace lamina
