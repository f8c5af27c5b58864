// Object labels for glTF viewers: the text rendered to an image that an unlit quad shows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lamina::gltf {

// White text with a dark halo on a transparent background (readable over any surface), straight
// (not premultiplied) alpha, rows top to bottom. The text fills the top-left content_width x
// content_height texels of an image whose sides are powers of two (which every viewer can
// mipmap); the rest is transparent. Every label has the same content height, so labels side by
// side show their text at the same size.
struct LabelImage {
  int width = 0, height = 0;
  int content_width = 0, content_height = 0;
  std::vector<uint8_t> rgba;
};

// Renders `text` (UTF-8, one line) in DejaVu Sans Bold, the font Debian's fonts-dejavu-core
// installs, through OpenImageIO's FreeType renderer (the image module). Deterministic for a given font file. Throws
// IoError when the font cannot be found or used.
LabelImage render_label(const std::string& text);

}  // namespace lamina::gltf
