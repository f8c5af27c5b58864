// glTF 2.0's enumerants and GLB markers, once for the reader, the writer and the importer.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lamina::gltf {

// accessor.componentType (glTF 2.0 sec. 5.1.3).
inline constexpr int kByte = 5120;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kShort = 5122;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;

// bufferView.target (sec. 5.11.6).
inline constexpr int kArrayBuffer = 34962;
inline constexpr int kElementArrayBuffer = 34963;

// mesh.primitive.mode (sec. 5.24.1): the three that make triangles.
inline constexpr int kModeTriangles = 4;
inline constexpr int kModeTriangleStrip = 5;
inline constexpr int kModeTriangleFan = 6;

// sampler filters and wrap modes (sec. 5.26).
inline constexpr int kLinear = 9729;
inline constexpr int kLinearMipmapLinear = 9987;
inline constexpr int kRepeat = 10497;
inline constexpr int kClampToEdge = 33071;
inline constexpr int kMirroredRepeat = 33648;

// The GLB container (sec. 4.4): magic "glTF", version 2, chunk types "JSON" and "BIN\0",
// little-endian.
inline constexpr std::uint32_t kGlbMagic = 0x46546C67u;
inline constexpr std::uint32_t kGlbVersion = 2;
inline constexpr std::uint32_t kChunkJson = 0x4E4F534Au;
inline constexpr std::uint32_t kChunkBin = 0x004E4942u;

}  // namespace lamina::gltf
