// Texture images: decoded once to linear RGBA floats, sampled bilinearly the way a GPU samples a
// linear-filtered texture with sRGB decoding before filtering. Every image lamina reads (material
// textures, environment maps, glTF images) is decoded here, from bytes read by file_access.h,
// after its header has been checked against the pixel budget.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "graph/cpu/image_header.h"
#include "graph/file_access.h"

namespace lamina {

struct LinearImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // row 0 is the top row of the file; uv (0, 0) is its top-left
};

enum class Wrap { Repeat = 0, Clamp = 1, Mirror = 2 };

// Decodes the first image of `bytes`, in a format of image_header.h (PNG through libpng, the others
// through OpenImageIO): grey gives r = g = b, missing alpha is 1, alpha stays straight (not
// multiplied into the colour), integer formats map to [0, 1]. With `srgb` the colour channels are
// decoded with the sRGB curve. Refuses, before any decoder runs, an image whose header is malformed
// or beyond `max_pixels`, and after decoding one holding a texel that is not finite. Throws
// ImageError.
std::shared_ptr<const LinearImage> decode_linear_image(std::string_view bytes, bool srgb, std::uint64_t max_pixels);

// A referenced image file read (file_access.h) and decoded under the policy's pixel budget.
// Throws ReferenceError for a reference that cannot be read and ImageError for one that does not
// decode.
std::shared_ptr<const LinearImage> load_image_reference(const Reference& reference, bool srgb,
                                                        const AssetPolicy& policy);

// An image file named directly (on the command line, or by a program), read as an input file and
// decoded. Throws IoError when it cannot be read, ImageError when it does not decode.
std::shared_ptr<const LinearImage> load_image_file(const std::filesystem::path& path, bool srgb,
                                                   std::uint64_t max_pixels = kDefaultMaxImagePixels);

// Bilinear lookup with texel centres at (i + 0.5) / width, as OpenGL's GL_LINEAR.
glm::vec4 sample_bilinear(const LinearImage& image, glm::vec2 uv, Wrap wrap);

}  // namespace lamina
