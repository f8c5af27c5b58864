// The text of `lamina plot`: DejaVu fonts drawn through OpenImageIO's FreeType renderer (the image
// module), and the
// figure's scale, by which every length and font size of the 1600-pixel design is multiplied.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "tools/plot_canvas.h"

namespace lamina::cli::plot {

struct Fonts {
  std::string regular, bold;
};

// DejaVu Sans and DejaVu Sans Bold (Debian: fonts-dejavu-core) where the common systems keep them,
// else names for OpenImageIO to search its font path with (the bold one falls back to the regular).
Fonts find_fonts();
// Whether OpenImageIO can measure text with the regular font, i.e. whether labels can be drawn.
bool fonts_usable(const Fonts& fonts);

class Text {
 public:
  Text(Canvas& canvas, const Fonts& fonts) : canvas_(canvas), fonts_(fonts) {}

  // The width in pixels of `text` at `size`.
  int width(const std::string& text, int size, bool bold = false) const;
  // The largest size up to `size` at which `text` is at most `max_width` wide (never below 7).
  int fit(const std::string& text, int size, int max_width, bool bold = false) const;
  // Draws `text` with its baseline at y; align < 0 left, 0 centre, > 0 right of x. With
  // max_width > 0 the size shrinks until the text fits.
  void draw(int x, int y, const std::string& text, int size, glm::vec3 colour, int align = -1, bool bold = false,
            int max_width = 0);
  // Why the first draw that failed failed; empty while every one succeeded.
  const std::string& error() const { return error_; }

 private:
  Canvas& canvas_;
  const Fonts& fonts_;
  std::string error_;
};

// The figure's scale against the 1600-pixel design.
struct Layout {
  double s;
  int px(double v) const { return int(std::lround(v * s)); }
  int font(double design_size) const { return std::max(8, px(design_size)); }
};

}  // namespace lamina::cli::plot
