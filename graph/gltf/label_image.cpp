#include "graph/gltf/label_image.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>

#include "graph/image_codec.h"
#include "graph/json_read.h"

namespace lamina::gltf {

namespace {

constexpr int kFontSize = 48;  // pixels: sharp at the size a label fills on screen
constexpr int kHalo = 4;       // pixels of dark outline around the glyphs
constexpr int kPadding = kHalo + 2;

// DejaVu where the common systems keep it (Debian: fonts-dejavu-core).
std::string find_font() {
  const char* dirs[] = {"/usr/share/fonts/truetype/dejavu", "/usr/share/fonts/TTF", "/usr/share/fonts/dejavu",
                        "/usr/share/fonts/dejavu-sans-fonts", "/usr/local/share/fonts"};
  for (const char* dir : dirs) {
    const std::filesystem::path path = std::filesystem::path(dir) / "DejaVuSans-Bold.ttf";
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) return path.string();
  }
  throw IoError(
      "cannot render object labels: the font DejaVuSans-Bold.ttf was not found (Debian: apt-get install "
      "fonts-dejavu-core)");
}

TextBox measure(const std::string& text, const std::string& font) {
  const std::optional<TextBox> box = image_codec().text_box(text, kFontSize, font);
  if (!box) throw IoError("cannot render object labels with the font " + font);
  return *box;
}

}  // namespace

LabelImage render_label(const std::string& text) {
  const std::string font = find_font();
  // The line's height from glyphs that reach the font's usual extremes, not from this text, so
  // that "ace" and "Ply" make images of the same height.
  const TextBox line = measure("Hgjpqy|", font);
  const TextBox ink = measure(text, font);
  const int ascent = -line.y0, descent = line.y1;
  LabelImage out;
  out.content_width = std::max(1, ink.x1 - ink.x0) + 2 * kPadding;
  out.content_height = ascent + descent + 2 * kPadding;
  out.width = static_cast<int>(std::bit_ceil(static_cast<unsigned>(out.content_width)));
  out.height = static_cast<int>(std::bit_ceil(static_cast<unsigned>(out.content_height)));

  const auto w = static_cast<size_t>(out.width), h = static_cast<size_t>(out.height);
  std::vector<float> c(w * h, 0.0f);  // the glyphs' coverage
  const float white = 1.0f;
  if (std::string why = image_codec().draw_text({c.data(), out.width, out.height, 1}, kPadding - ink.x0,
                                                kPadding + ascent, text, kFontSize, font, &white, -1);
      !why.empty())
    throw IoError("cannot render the label '" + text + "': " + why);

  // The halo: the coverage dilated by a disk of radius kHalo, its rim antialiased. The disk's
  // weights are the same for every pixel: computed once.
  constexpr int kReach = kHalo + 1, kSide = 2 * kReach + 1;
  float rim[kSide][kSide];
  for (int dy = -kReach; dy <= kReach; ++dy)
    for (int dx = -kReach; dx <= kReach; ++dx)
      rim[dy + kReach][dx + kReach] = std::clamp(float(kHalo) + 1.0f - std::hypot(float(dx), float(dy)), 0.0f, 1.0f);
  // Spread from the covered pixels only (most of a label is empty); max is order-independent, so
  // the result is that of gathering at every pixel.
  std::vector<float> halo(w * h, 0.0f);
  for (int sy = 0; sy < out.height; ++sy)
    for (int sx = 0; sx < out.width; ++sx) {
      const float source = c[static_cast<size_t>(sy) * w + static_cast<size_t>(sx)];
      if (!(source > 0.0f)) continue;
      for (int dy = -kReach; dy <= kReach; ++dy)
        for (int dx = -kReach; dx <= kReach; ++dx) {
          const int x = sx - dx, y = sy - dy;
          if (x < 0 || y < 0 || x >= out.width || y >= out.height) continue;
          float& target = halo[static_cast<size_t>(y) * w + static_cast<size_t>(x)];
          target = std::max(target, rim[dy + kReach][dx + kReach] * source);
        }
    }

  // White text over the black halo ("over" compositing), stored with straight alpha as glTF wants.
  out.rgba.resize(w * h * 4);
  for (size_t i = 0; i < w * h; ++i) {
    const float text_alpha = std::clamp(c[i], 0.0f, 1.0f);
    const float alpha = text_alpha + halo[i] * (1.0f - text_alpha);
    const float value = alpha > 0.0f ? text_alpha / alpha : 0.0f;
    const auto byte = [](float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    out.rgba[4 * i] = out.rgba[4 * i + 1] = out.rgba[4 * i + 2] = byte(value);
    out.rgba[4 * i + 3] = byte(alpha);
  }
  return out;
}

}  // namespace lamina::gltf
