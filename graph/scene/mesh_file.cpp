#include "graph/scene/mesh_file.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <optional>

#include "graph/gltf/gltf_read.h"
#include "graph/json_read.h"
#include "graph/number_text.h"
#include "graph/scene/mesh_shading.h"
#include "graph/scene/scene_fields.h"

namespace lamina {

namespace {

// A node transform whose determinant is this small relative to its largest axis cubed flattens
// its meshes onto a plane or line: normals are undefined there.
constexpr double kSingularDeterminant = 1e-12;

constexpr int kUnvisited = -2;
constexpr int kRoot = -1;

std::string at(const char* array, size_t index) { return "/" + std::string(array) + "/" + std::to_string(index); }
std::string at(const char* array, int index) { return at(array, static_cast<size_t>(index)); }

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
  MeshLoader(const gltf::GltfAsset& model, const std::filesystem::path& path) : model_(model), file_(path.string()) {}

  TriangleMesh load() {
    // An extension a file requires changes what its data means (compressed or quantised geometry).
    for (size_t k = 0; k < model_.extensions_required.size(); ++k)
      if (model_.extensions_required[k].rfind("KHR_materials_", 0) != 0)
        fail("/extensionsRequired/" + std::to_string(k),
             "the file requires the extension " + model_.extensions_required[k] + ", which lamina does not read",
             "export the mesh without compression or quantisation");
    if (!model_.scenes.empty()) {
      const int scene = model_.scene >= 0 ? model_.scene : 0;
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
      const auto index = static_cast<size_t>(item.node);
      if (parent_of[index] != kUnvisited) fail(item.reference, second_reference(item.node, item.parent, parent_of));
      parent_of[index] = item.parent;
      const gltf::GltfNode& node = model_.nodes[index];
      const std::string pointer = at("nodes", index);
      const glm::dmat4 world = item.parent_world * local_matrix(node, pointer);  // glTF: T * R * S
      if (node.mesh >= 0) {
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

  glm::dmat4 local_matrix(const gltf::GltfNode& node, const std::string& pointer) const {
    glm::dmat4 m(1.0);
    if (node.matrix) {
      m = glm::make_mat4(node.matrix->data());  // column-major, as glTF
    } else {
      m = glm::translate(m, glm::make_vec3(node.translation.data()));
      const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      const double length = glm::length(q);
      if (!(length > 1e-12) || !std::isfinite(length))
        fail(pointer + "/rotation", "the rotation quaternion has zero length or is not finite",
             "the identity is [0, 0, 0, 1] (x, y, z, w)");
      m *= glm::mat4_cast(q / length);
      m = glm::scale(m, glm::make_vec3(node.scale.data()));
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

  // Accessor `index`, referred to at `reference` as `what`, after checking that it is dense and
  // has `components` components; its ranges the reader checked.
  const gltf::GltfAccessor& accessor(int index, int components, const std::string& reference,
                                     const std::string& what) const {
    (void)reference;
    const gltf::GltfAccessor& a = model_.accessors[static_cast<size_t>(index)];
    const std::string pointer = at("accessors", index);
    if (a.sparse) fail(pointer + "/sparse", "sparse accessors are not supported", "store the values densely");
    if (a.components != components || a.type.rfind("MAT", 0) == 0)
      fail(pointer + "/type", what + " must be " + type_name(components));
    return a;
  }

  // The elements of accessor `index`, as doubles, normalised integers mapped as the glTF 2.0
  // specification's "Accessor data types" section says.
  std::vector<double> read_accessor(int index, int components, const std::string& what) const {
    const gltf::GltfAccessor& a = model_.accessors[static_cast<size_t>(index)];
    const auto n = static_cast<size_t>(components);
    const gltf::GltfAccessorData data = model_.accessor_data(index);
    if (!data.data) return std::vector<double>(a.count * n, 0.0);
    const size_t size = gltf::component_size(a.component_type);
    std::vector<double> out(a.count * n);
    for (size_t i = 0; i < a.count; ++i) {
      const unsigned char* element = data.data + i * data.stride;
      for (size_t c = 0; c < n; ++c) {
        const double v = component(element + c * size, a.component_type, a.normalized);
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
      case gltf::kUnsignedByte: return load_as<uint8_t>(p) / (normalized ? 255.0 : 1.0);
      case gltf::kUnsignedShort: return load_as<uint16_t>(p) / (normalized ? 65535.0 : 1.0);
      case gltf::kUnsignedInt: return load_as<uint32_t>(p);
      case gltf::kByte: return normalized ? std::max(load_as<int8_t>(p) / 127.0, -1.0) : load_as<int8_t>(p);
      case gltf::kShort: return normalized ? std::max(load_as<int16_t>(p) / 32767.0, -1.0) : load_as<int16_t>(p);
      default: return load_as<float>(p);  // kFloat; the reader admits no other type
    }
  }

  static bool is_triangles(int mode) {
    return mode == gltf::kModeTriangles || mode == gltf::kModeTriangleStrip || mode == gltf::kModeTriangleFan;
  }

  static std::vector<uint32_t> triangles(int mode, const std::vector<uint32_t>& v) {
    std::vector<uint32_t> out;
    if (mode == gltf::kModeTriangles) {
      out.assign(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 3 * 3));
    } else if (mode == gltf::kModeTriangleStrip) {
      // glTF 2.0 "Meshes: topology": odd triangles swap two vertices to keep the winding.
      for (size_t i = 0; i + 2 < v.size(); ++i)
        out.insert(out.end(), i % 2 ? std::initializer_list<uint32_t>{v[i + 1], v[i], v[i + 2]}
                                    : std::initializer_list<uint32_t>{v[i], v[i + 1], v[i + 2]});
    } else if (mode == gltf::kModeTriangleFan) {
      for (size_t i = 1; i + 1 < v.size(); ++i) out.insert(out.end(), {v[i], v[i + 1], v[0]});
    }
    return out;
  }

  // --- meshes ----------------------------------------------------------------------------------

  // The triangles `count` vertex references make in `mode` (glTF 2.0 "Meshes: topology").
  static size_t triangle_count(int mode, size_t count) {
    if (mode == gltf::kModeTriangles) return count / 3;
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
    const gltf::GltfMesh& mesh = model_.meshes[index];
    const glm::dmat3 linear(world);
    const glm::dmat3 normal_matrix = glm::inverseTranspose(linear);
    const bool mirrored = glm::determinant(linear) < 0.0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const gltf::GltfPrimitive& primitive = mesh.primitives[p];
      const std::string prim = at("meshes", index) + "/primitives/" + std::to_string(p);
      auto position = primitive.attributes.find("POSITION");
      // Points and lines have no surface; glTF says to skip primitives without positions.
      if (!is_triangles(primitive.mode) || position == primitive.attributes.end()) continue;
      if (++primitives_ > kMaxMeshPrimitives)
        fail(reference, "this instance takes the file beyond " + std::to_string(kMaxMeshPrimitives) +
                            " triangle primitives over all instances of its meshes, more than lamina reads");
      const std::string position_reference = prim + "/attributes/POSITION";
      const size_t count = accessor(position->second, 3, position_reference, "POSITION").count;
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
        const gltf::GltfAccessor& a = accessor(primitive.indices, 1, indices_reference, "indices");
        if (a.component_type != gltf::kUnsignedByte && a.component_type != gltf::kUnsignedShort &&
            a.component_type != gltf::kUnsignedInt)
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
        const size_t n = accessor(it->second, components, attribute_reference, name).count;
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

  const gltf::GltfAsset& model_;
  std::string file_;
  TriangleMesh mesh_;
  size_t vertices_ = 0, triangles_ = 0, primitives_ = 0;  // over every instance so far
};

}  // namespace

TriangleMesh load_mesh_bytes(std::string_view bytes, const std::filesystem::path& path, const AssetPolicy& policy) {
  const gltf::GltfAsset asset = gltf::read_gltf(bytes, path, policy);
  return MeshLoader(asset, path).load();
}

TriangleMesh load_mesh_file(const Reference& file, const AssetPolicy& policy) {
  return load_mesh_bytes(read_reference(file, kMaxBinaryFileBytes, policy), file.path, policy);
}

TriangleMesh load_mesh_file(const std::filesystem::path& path) {
  return load_mesh_bytes(read_input_file(path, kMaxBinaryFileBytes), path, AssetPolicy{}.with_default_root(path));
}

}  // namespace lamina
