// The rasteriser of `lamina plot`: a float RGB canvas with the few primitives the figure needs
// (filled rectangles and anti-aliased polylines), and the encoding of the finished image.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "graph/image_codec.h"

namespace lamina::cli::plot {

struct Rect {
  int x0, y0, x1, y1;  // half-open
};

// Row 0 at the top; values are display-referred (sRGB), as written to the file.
class Canvas {
 public:
  Canvas(int width, int height, glm::vec3 fill) : w_(width), h_(height), rgb_(size_t(width) * size_t(height), fill) {}
  int width() const { return w_; }
  int height() const { return h_; }
  glm::vec3& at(int x, int y) { return rgb_[size_t(y) * size_t(w_) + size_t(x)]; }
  const std::vector<glm::vec3>& pixels() const { return rgb_; }
  // The pixels as the image module draws text into them and encodes them.
  FloatPixels view() {
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "a canvas is rows of packed RGB floats");
    return {&rgb_.front().x, w_, h_, 3};
  }

  // Sets the pixels of r that lie on the canvas to c.
  void fill(Rect r, glm::vec3 c);
  // Adds `colour` times the polyline's anti-aliased coverage (line_width wide) inside `clip`, each
  // channel clamped at 1, so that curves drawn over one another add up.
  void add_polyline(const std::vector<glm::vec2>& points, float line_width, Rect clip, glm::vec3 colour);

 private:
  int w_, h_;
  std::vector<glm::vec3> rgb_;
};

// Encodes `canvas` as 8-bit `format` (an OpenImageIO format name such as "png") in memory, with
// `metadata`. Returns why it cannot, or an empty string.
std::string encode_image(Canvas& canvas, const std::string& format,
                         const std::vector<std::pair<std::string, std::string>>& metadata,
                         std::vector<unsigned char>& encoded);

}  // namespace lamina::cli::plot
