#include "graph/scene/mesh_file.h"

#include <tiny_gltf.h>

#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "graph/json_read.h"
#include "graph/scene/mesh_shading.h"

namespace lamina {

namespace {

// Geometry only: images are neither decoded nor checked.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

class MeshLoader {
 public:
  MeshLoader(const tinygltf::Model& model, const std::filesystem::path& path) : model_(model), path_(path) {}

  TriangleMesh load() {
    if (!model_.scenes.empty()) {
      size_t scene = model_.defaultScene >= 0 ? static_cast<size_t>(model_.defaultScene) : 0;
      if (scene >= model_.scenes.size()) fail("the default scene " + std::to_string(scene) + " does not exist");
      for (int node : model_.scenes[scene].nodes) add_node(node, glm::dmat4(1.0), 0);
    } else {
      for (size_t m = 0; m < model_.meshes.size(); ++m) add_mesh(model_.meshes[m], glm::dmat4(1.0));
    }
    if (mesh_.indices.empty()) fail("holds no triangles");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { throw IoError(path_.string() + ": " + message); }

  static glm::dmat4 local_matrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major, as glTF
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4)
      m *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    return m;
  }

  void add_node(int index, const glm::dmat4& parent, int depth) {
    if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size())
      fail("node " + std::to_string(index) + " does not exist");
    if (depth > 1000) fail("the node hierarchy has a cycle");
    const tinygltf::Node& node = model_.nodes[static_cast<size_t>(index)];
    glm::dmat4 world = parent * local_matrix(node);  // glTF: T * R * S, children inherit
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
        fail("mesh " + std::to_string(node.mesh) + " does not exist");
      add_mesh(model_.meshes[static_cast<size_t>(node.mesh)], world);
    }
    for (int child : node.children) add_node(child, world, depth + 1);
  }

  // The accessor's elements as doubles, normalised integers mapped as the glTF 2.0 specification's
  // "Accessor data types" section says.
  std::vector<double> read_accessor(int index, int components) const {
    if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size())
      fail("accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(index)];
    if (a.sparse.isSparse) fail("sparse accessors are not supported");
    if (tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type)) != components)
      fail("accessor " + std::to_string(index) + " has the wrong number of components");
    std::vector<double> out(a.count * static_cast<size_t>(components), 0.0);
    if (a.bufferView < 0) return out;  // glTF: an accessor without a buffer view is all zeros
    const tinygltf::BufferView& view = model_.bufferViews.at(static_cast<size_t>(a.bufferView));
    const tinygltf::Buffer& buffer = model_.buffers.at(static_cast<size_t>(view.buffer));
    int stride = a.ByteStride(view);
    int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    if (stride <= 0 || size <= 0) fail("accessor " + std::to_string(index) + " has an invalid layout");
    size_t start = view.byteOffset + a.byteOffset;
    if (a.count > 0 && start + (a.count - 1) * static_cast<size_t>(stride) + static_cast<size_t>(size * components) >
                           std::min(buffer.data.size(), view.byteOffset + view.byteLength))
      fail("accessor " + std::to_string(index) + " reads beyond its buffer");
    for (size_t i = 0; i < a.count; ++i) {
      const unsigned char* element = buffer.data.data() + start + i * static_cast<size_t>(stride);
      for (int c = 0; c < components; ++c)
        out[i * static_cast<size_t>(components) + static_cast<size_t>(c)] =
            component(element + c * size, a.componentType, a.normalized);
    }
    return out;
  }

  template <class T>
  static T load_as(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }

  double component(const unsigned char* p, int type, bool normalized) const {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return load_as<float>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load_as<uint8_t>(p) / (normalized ? 255.0 : 1.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load_as<uint16_t>(p) / (normalized ? 65535.0 : 1.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load_as<uint32_t>(p);
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return normalized ? std::max(load_as<int8_t>(p) / 127.0, -1.0) : load_as<int8_t>(p);
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return normalized ? std::max(load_as<int16_t>(p) / 32767.0, -1.0) : load_as<int16_t>(p);
      default: fail("unsupported component type " + std::to_string(type));
    }
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

  void add_mesh(const tinygltf::Mesh& mesh, const glm::dmat4& world) {
    glm::dmat3 linear(world);
    glm::dmat3 normal_matrix = glm::inverseTranspose(linear);
    bool mirrored = glm::determinant(linear) < 0.0;
    for (const auto& primitive : mesh.primitives) {
      auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) continue;
      std::vector<double> p = read_accessor(position->second, 3);
      size_t count = p.size() / 3;
      std::vector<uint32_t> order;
      if (primitive.indices >= 0) {
        for (double i : read_accessor(primitive.indices, 1)) {
          if (i >= static_cast<double>(count)) fail("an index is beyond the vertex count");
          order.push_back(static_cast<uint32_t>(i));
        }
      } else {
        for (size_t i = 0; i < count; ++i) order.push_back(static_cast<uint32_t>(i));
      }
      std::vector<uint32_t> tris = triangles(primitive.mode, order);
      if (tris.empty()) continue;
      auto attribute = [&](const char* name, int components) {
        auto it = primitive.attributes.find(name);
        std::vector<double> values;
        if (it != primitive.attributes.end()) values = read_accessor(it->second, components);
        if (!values.empty() && values.size() != count * static_cast<size_t>(components))
          fail(std::string(name) + " and POSITION have different counts");
        return values;
      };
      std::vector<double> n = attribute("NORMAL", 3), t = attribute("TANGENT", 4), uv = attribute("TEXCOORD_0", 2);
      TriangleMesh piece;
      for (size_t i = 0; i < count; ++i) {
        piece.positions.emplace_back(world * glm::dvec4(p[3 * i], p[3 * i + 1], p[3 * i + 2], 1.0));
        if (!n.empty()) piece.normals.emplace_back(glm::normalize(normal_matrix * glm::make_vec3(&n[3 * i])));
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
          glm::dvec3 normal(piece.normals[i]);
          glm::dvec3 tangent = linear * glm::make_vec3(&t[4 * i]);
          tangent -= normal * glm::dot(normal, tangent);
          double w = t[4 * i + 3];
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
  const std::filesystem::path& path_;
  TriangleMesh mesh_;
};

}  // namespace

TriangleMesh load_mesh_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw IoError(path.string() + ": no such file");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  std::string ext = path.extension().string();
  bool binary = ext == ".glb" || ext == ".GLB";
  bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path.string())
                   : loader.LoadASCIIFromFile(&model, &error, &warning, path.string());
  if (!ok) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
    throw IoError(path.string() + ": cannot read glTF: " + (error.empty() ? "unknown error" : error));
  }
  return MeshLoader(model, path).load();
}

}  // namespace lamina
