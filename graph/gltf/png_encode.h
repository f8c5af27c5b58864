// PNG encoding in memory, for images lamina writes into glTF buffers.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace lamina::gltf {

// 8-bit PNG of `channels` (1 to 4) interleaved channels per pixel, rows top to bottom.
// Deterministic: no time stamps or software tags. Throws std::runtime_error if encoding fails.
std::vector<unsigned char> encode_png(int width, int height, int channels, std::span<const uint8_t> pixels);

}  // namespace lamina::gltf
