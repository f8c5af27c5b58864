#include "graph/gltf/label_image.h"

#include <doctest/doctest.h>

#include <bit>

using namespace lamina::gltf;

namespace {

struct Counts {
  int transparent = 0, text = 0, halo = 0;
};

// Opaque white texels are glyph interiors, opaque black ones the halo.
Counts count(const LabelImage& image) {
  Counts c;
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    const uint8_t value = image.rgba[i], alpha = image.rgba[i + 3];
    CHECK(image.rgba[i + 1] == value);  // grey: white text over a black halo
    CHECK(image.rgba[i + 2] == value);
    if (alpha == 0) ++c.transparent;
    if (alpha == 255 && value == 255) ++c.text;
    if (alpha == 255 && value == 0) ++c.halo;
  }
  return c;
}

}  // namespace

TEST_CASE("a label renders as white text in a black halo, in power-of-two images of one content height") {
  const LabelImage brass = render_label("brass");
  const LabelImage longer = render_label("frosted_acrylic_paint");
  const LabelImage tall = render_label("Ply|");
  for (const LabelImage* image : {&brass, &longer, &tall}) {
    CHECK(std::has_single_bit(static_cast<unsigned>(image->width)));
    CHECK(std::has_single_bit(static_cast<unsigned>(image->height)));
    CHECK(image->content_width <= image->width);
    CHECK(image->content_height <= image->height);
    REQUIRE(image->rgba.size() == static_cast<size_t>(image->width) * static_cast<size_t>(image->height) * 4);
    const Counts c = count(*image);
    CHECK(c.text > 0);
    CHECK(c.halo > 0);
    CHECK(c.transparent > 0);
    // Outside the content every texel is transparent, and so is the content's border.
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x)
        if (x == 0 || y == 0 || x >= image->content_width - 1 || y >= image->content_height - 1)
          CHECK(image->rgba[(static_cast<size_t>(y) * static_cast<size_t>(image->width) + static_cast<size_t>(x)) * 4 +
                            3] == 0);
  }
  // The line height is the font's, not the text's: every label's text has one size.
  CHECK(brass.content_height == longer.content_height);
  CHECK(brass.content_height == tall.content_height);
  CHECK(longer.content_width > 3 * brass.content_width);
  // The same text gives the same bytes.
  CHECK(render_label("brass").rgba == brass.rgba);
}
