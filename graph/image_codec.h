// What lamina asks of OpenImageIO, behind one narrow interface: decoding the image formats lamina
// does not decode itself, encoding figures, and drawing text. OpenImageIO and the ~250 shared
// libraries it pulls in live in a module (lamina_oiio) that liblamina loads the first time one of
// these is needed: linked directly, they cost every lamina process about 0.4 s of dynamic linking
// before main, most of it in commands that never touch an image.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lamina {

// Receives a decoded image: its size first, then every row in bands from the top.
class DecodeSink {
 public:
  // The image's size, depth (slices) and channels before any row. An empty string accepts it;
  // anything else is the reason it is refused, and decoding stops there.
  virtual std::string start(int width, int height, int depth, int channels) = 0;
  // Rows [y0, y1): (y1 - y0) * width * min(channels, 4) floats, rows top to bottom.
  virtual void rows(int y0, int y1, const float* band) = 0;

 protected:
  ~DecodeSink() = default;
};

// Pixels of a figure: `channels` interleaved floats (display-referred, 0..1) per pixel, rows top
// to bottom.
struct FloatPixels {
  float* data = nullptr;
  int width = 0, height = 0, channels = 0;
};

// The ink of a text relative to its pen position on the baseline, in pixels (y grows downwards):
// [x0, x1) x [y0, y1).
struct TextBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Every function reports failure by returning why (an empty string is success); nothing throws
// across the module boundary.
class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // OpenImageIO's version, as the module runs it.
  virtual std::string version() const = 0;
  // Decodes `bytes` with OpenImageIO's reader `reader` ("jpeg", "openexr", "hdr", "tiff") alone,
  // never another: the caller has read the header and knows the format.
  virtual std::string decode(const char* reader, std::string_view bytes, DecodeSink& sink) const = 0;
  // Whether OpenImageIO writes the format its name or extension names ("png", "tif", ...).
  virtual bool writes(const std::string& format) const = 0;
  // Encodes `pixels` as 8-bit `format` in memory, with metadata (name, value) such as
  // "ImageDescription".
  virtual std::string encode(const std::string& format, const FloatPixels& pixels,
                             const std::vector<std::pair<std::string, std::string>>& metadata,
                             std::vector<unsigned char>& encoded) const = 0;
  // Encodes `pixels` (linear, any range) as half floats in `format` ("exr"), the channels named
  // `channel_names` (one per channel: "R", "G", "B", "albedo.R", ...), with metadata as above.
  virtual std::string encode_linear(const std::string& format, const FloatPixels& pixels,
                                    const std::vector<std::string>& channel_names,
                                    const std::vector<std::pair<std::string, std::string>>& metadata,
                                    std::vector<unsigned char>& encoded) const = 0;
  // The ink of `text` at `size` pixels in `font` (a font file, or a name to search OpenImageIO's
  // font path for); nothing when the font cannot be used.
  virtual std::optional<TextBox> text_box(const std::string& text, int size, const std::string& font) const = 0;
  // Draws `text` with its baseline at y, left of, centred on or right of x (align < 0, 0, > 0),
  // in `colour` (one value per channel), into `pixels`.
  virtual std::string draw_text(const FloatPixels& pixels, int x, int y, const std::string& text, int size,
                                const std::string& font, const float* colour, int align) const = 0;
};

// The codec, loaded on first use from the module beside liblamina. Throws IoError (naming the
// module's path and the loader's reason) when the module cannot be loaded.
const ImageCodec& image_codec();

}  // namespace lamina

// The module's one entry point.
extern "C" {
using LaminaImageCodecEntry = const lamina::ImageCodec* (*)();
}
