// Triangle meshes from glTF 2.0 files (.gltf or .glb), read by graph/gltf/gltf_read.h.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>

#include "graph/scene/scene.h"

namespace lamina {

// What one mesh file may expand to, over every instance of its meshes: beyond this a scene mesh is
// surely a mistake (a runaway instancing tree, a corrupt count), and it keeps the memory a file can
// make lamina allocate to a few hundred megabytes.
inline constexpr size_t kMaxMeshVertices = size_t{1} << 22;    // 4,194,304
inline constexpr size_t kMaxMeshTriangles = size_t{1} << 23;   // 8,388,608
inline constexpr size_t kMaxMeshPrimitives = size_t{1} << 16;  // primitive instances

// Every triangle primitive (triangles, strips, fans) of the file's default scene (the first
// scene when none is marked; every mesh once when the file has no scene), node transforms applied,
// normals with the inverse transpose. Missing normals and tangents are generated
// (mesh_shading.h), missing uvs are (0, 0).
//
// Read through graph/gltf/gltf_read.h: throws ReferenceError when the file cannot be followed or
// read, and lamina::Error for every problem of the file itself (container, JSON, ranges, buffers)
// and for content lamina cannot use, each problem with the mesh file and the glTF JSON pointer of the
// offending value ("" for the file as a whole: no triangles): indices, accessors or buffer views
// out of range, accessors reading beyond their buffer, wrong types, values that are not finite,
// node hierarchies that are not strict trees (cycles, nodes with two parents), transforms that
// collapse a mesh, and files beyond the limits above. Nothing is allocated before it is checked
// against the file's own sizes and these limits.
TriangleMesh load_mesh_file(const Reference& file, const AssetPolicy& policy);
// A mesh file named directly (on the command line, or by a program): read as an input file
// (IoError when it cannot be), its buffers in its folder.
TriangleMesh load_mesh_file(const std::filesystem::path& path);
// The mesh of `bytes`, the content of `path` (whose folder its buffers are looked up in).
TriangleMesh load_mesh_bytes(std::string_view bytes, const std::filesystem::path& path, const AssetPolicy& policy);

}  // namespace lamina
