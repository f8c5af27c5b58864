// Texture images for the CPU evaluator: decoded once to linear RGBA floats, sampled bilinearly
// the way a GPU samples a linear-filtered texture with sRGB decoding before filtering.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lamina {

struct LinearImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // row 0 is the top row of the file; uv (0, 0) is its top-left
};

enum class Wrap { Repeat = 0, Clamp = 1, Mirror = 2 };

// Reads any image OpenImageIO reads; grey images give r = g = b, missing alpha is 1. With `srgb`
// the colour channels are decoded with the sRGB curve (alpha stays linear). Throws IoError.
std::shared_ptr<const LinearImage> load_linear_image(const std::filesystem::path& path, bool srgb);

// Bilinear lookup with texel centres at (i + 0.5) / width, as OpenGL's GL_LINEAR.
glm::vec4 sample_bilinear(const LinearImage& image, glm::vec2 uv, Wrap wrap);

}  // namespace lamina
