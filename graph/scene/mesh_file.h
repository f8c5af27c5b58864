// Triangle meshes from glTF 2.0 files (.gltf or .glb), through Debian's shared tinygltf.
#pragma once

#include <filesystem>

#include "graph/scene/scene.h"

namespace lamina {

// Every triangle primitive (triangles, strips, fans) of the file's default scene (the first
// scene when none is marked; every mesh when the file has no scene), node transforms applied,
// normals with the inverse transpose. Missing normals and tangents are generated
// (mesh_shading.h), missing uvs are (0, 0). Throws IoError when the file cannot be read or holds
// no triangle.
TriangleMesh load_mesh_file(const std::filesystem::path& path);

}  // namespace lamina
