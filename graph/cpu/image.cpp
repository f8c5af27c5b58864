#include "graph/cpu/image.h"

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>

#include "graph/image_codec.h"
#include "graph/png_trap.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

namespace {

// Fills `image` from rows of `channels` floats each.
void store_row(LinearImage& image, int y, const float* row, int channels, bool srgb) {
  for (int x = 0; x < image.width; ++x) {
    const float* p = row + static_cast<size_t>(x) * static_cast<size_t>(channels);
    glm::vec3 rgb = channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
    const float alpha = channels == 2 ? p[1] : channels >= 4 ? p[3] : 1.0f;
    if (srgb) rgb = kernels::srgb_to_linear(rgb);
    image.texels[static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x)] =
        glm::vec4(rgb, alpha);
  }
}

// --- PNG, through libpng with lamina's own error handlers ------------------------------------------
// (OpenImageIO's PNG reader lets libpng print its messages on standard error.)

// What the reader reads from, and libpng's error trap.
struct PngState : PngTrap {
  std::string_view bytes;
  size_t position = 0;
};

void png_read_bytes(png_structp png, png_bytep out, size_t count) {
  auto* state = static_cast<PngState*>(png_get_io_ptr(png));
  if (state->bytes.size() - state->position < count) png_error(png, "the file ends early: it is truncated");
  std::memcpy(out, state->bytes.data() + state->position, count);
  state->position += count;
}

// What libpng delivers after the transformations below.
struct PngLayout {
  std::uint32_t width = 0, height = 0;
  int channels = 0;
  int bit_depth = 0;
  bool interlaced = false;
  size_t row_bytes = 0;
};

// The two functions below are the only frames libpng may leave by longjmp. They create no C++
// object (not even a temporary) and allocate nothing: every buffer is sized by the caller between
// them, so a longjmp destroys nothing and no local is live after it.

// Reads the header, sets the transformations to 8- or 16-bit gray, gray-alpha, RGB or RGBA and
// fills the layout they give.
bool png_read_header(png_structp png, png_infop info, PngState& state, PngLayout& layout) {
  if (setjmp(state.jump)) return false;
  png_set_read_fn(png, &state, png_read_bytes);
  png_set_user_limits(png, static_cast<png_uint_32>(kMaxImageSide), static_cast<png_uint_32>(kMaxImageSide));
  // Text and colour-profile chunks decompress into a buffer of their own: without a cap, a small
  // zTXt chunk could inflate to gigabytes. Pixels (IDAT) are streamed and not limited by it.
  png_set_chunk_malloc_max(png, kMaxPngChunkBytes);
  png_read_info(png, info);
  layout.width = png_get_image_width(png, info);
  layout.height = png_get_image_height(png, info);
  const int color_type = png_get_color_type(png, info);
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (png_get_bit_depth(png, info) == 16) png_set_swap(png);  // little-endian host: samples in host order
  layout.interlaced = png_set_interlace_handling(png) > 1;
  png_read_update_info(png, info);
  layout.channels = png_get_channels(png, info);
  layout.bit_depth = png_get_bit_depth(png, info);
  layout.row_bytes = png_get_rowbytes(png, info);
  return true;
}

// Decodes the pixels into `image`. Interlaced images revisit rows, so `rows` holds all of them
// (through `pointers`); the others go through one row. `converted` holds one row of floats.
bool png_read_pixels(png_structp png, PngState& state, const PngLayout& layout, unsigned char* rows,
                     png_bytep* pointers, float* converted, bool srgb, LinearImage& image) {
  if (setjmp(state.jump)) return false;
  if (layout.interlaced) png_read_image(png, pointers);
  const size_t samples = static_cast<size_t>(layout.width) * static_cast<size_t>(layout.channels);
  for (std::uint32_t y = 0; y < layout.height; ++y) {
    unsigned char* row = layout.interlaced ? pointers[y] : rows;
    if (!layout.interlaced) png_read_row(png, row, nullptr);
    for (size_t i = 0; i < samples; ++i) {
      if (layout.bit_depth == 16) {
        std::uint16_t v;
        std::memcpy(&v, row + 2 * i, 2);
        converted[i] = static_cast<float>(v) / 65535.0f;
      } else {
        converted[i] = static_cast<float>(row[i]) / 255.0f;
      }
    }
    store_row(image, static_cast<int>(y), converted, layout.channels, srgb);
  }
  png_read_end(png, nullptr);
  return true;
}

// Owns libpng's structures for one decode.
class PngReader {
 public:
  explicit PngReader(PngState& state) {
    png_ =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, static_cast<PngTrap*>(&state), png_trap_error, png_drop_warning);
    if (png_) info_ = png_create_info_struct(png_);
    if (!png_ || !info_) {
      png_destroy_read_struct(&png_, nullptr, nullptr);
      throw ImageError("cannot start the PNG decoder");
    }
  }
  ~PngReader() { png_destroy_read_struct(&png_, &info_, nullptr); }
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;
  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

// Decodes a PNG whose header fits the budget.
std::shared_ptr<LinearImage> decode_png(std::string_view bytes, bool srgb) {
  PngState state;
  state.bytes = bytes;
  PngReader reader(state);
  auto failed = [&] {
    return ImageError("not a valid PNG image: " + (state.error.empty() ? std::string("decoding failed") : state.error));
  };
  PngLayout layout;
  if (!png_read_header(reader.png(), reader.info(), state, layout)) throw failed();
  auto image = std::make_shared<LinearImage>();
  image->width = static_cast<int>(layout.width);
  image->height = static_cast<int>(layout.height);
  image->texels.resize(static_cast<size_t>(layout.width) * layout.height);
  std::vector<unsigned char> rows(layout.row_bytes * (layout.interlaced ? layout.height : 1));
  std::vector<png_bytep> pointers;
  if (layout.interlaced)
    for (std::uint32_t y = 0; y < layout.height; ++y) pointers.push_back(rows.data() + y * layout.row_bytes);
  std::vector<float> converted(static_cast<size_t>(layout.width) * static_cast<size_t>(layout.channels));
  if (!png_read_pixels(reader.png(), state, layout, rows.data(), pointers.data(), converted.data(), srgb, *image))
    throw failed();
  return image;
}

// --- every other format, through the image module's OpenImageIO -----------------------------------

// OpenImageIO's name for the reader of a format.
const char* oiio_reader(ImageFormat format) {
  switch (format) {
    case ImageFormat::Jpeg: return "jpeg";
    case ImageFormat::OpenExr: return "openexr";
    case ImageFormat::RadianceHdr: return "hdr";
    case ImageFormat::Tiff: return "tiff";
    case ImageFormat::Png: break;
  }
  throw ImageError("no OpenImageIO reader for " + format_name(format));
}

// Fills a LinearImage from the decoder's bands, once their size agrees with the header lamina read.
class LinearImageSink final : public DecodeSink {
 public:
  LinearImageSink(const ImageHeader& header, bool srgb) : header_(header), srgb_(srgb) {}

  std::string start(int width, int height, int depth, int channels) override {
    if (depth > 1) return "the image is a volume of " + std::to_string(depth) + " slices, not a texture";
    if (width < 0 || height < 0 || static_cast<std::uint64_t>(width) != header_.width ||
        static_cast<std::uint64_t>(height) != header_.height)
      return "the decoder reads " + std::to_string(width) + " x " + std::to_string(height) +
             " pixels where the header declares " + std::to_string(header_.width) + " x " +
             std::to_string(header_.height);
    if (channels < 1) return "the image has no channels";
    channels_ = std::min(channels, 4);
    image_ = std::make_shared<LinearImage>();
    image_->width = width;
    image_->height = height;
    image_->texels.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
    return {};
  }

  void rows(int y0, int y1, const float* band) override {
    const size_t row_floats = static_cast<size_t>(image_->width) * static_cast<size_t>(channels_);
    for (int y = y0; y < y1; ++y)
      store_row(*image_, y, band + static_cast<size_t>(y - y0) * row_floats, channels_, srgb_);
  }

  std::shared_ptr<LinearImage> image() const { return image_; }

 private:
  const ImageHeader& header_;
  bool srgb_;
  int channels_ = 0;
  std::shared_ptr<LinearImage> image_;
};

// Decodes a JPEG, OpenEXR, Radiance HDR or TIFF image whose header (read by lamina) fits the
// budget, with that format's reader alone: OpenImageIO would otherwise try every reader it has on
// bytes its first choice refuses.
std::shared_ptr<LinearImage> decode_oiio(std::string_view bytes, const ImageHeader& header, bool srgb) {
  const char* reader = oiio_reader(header.format);
  LinearImageSink sink(header, srgb);
  if (std::string why = image_codec().decode(reader, bytes, sink); !why.empty())
    throw ImageError(format_name(header.format) + ": " + why);
  return sink.image();
}

}  // namespace

std::shared_ptr<const LinearImage> decode_linear_image(std::string_view bytes, bool srgb, std::uint64_t max_pixels) {
  const ImageHeader header = read_image_header(bytes);
  if (std::string why = image_budget_problem(header, max_pixels); !why.empty()) throw ImageError(why);
  std::shared_ptr<LinearImage> image =
      header.format == ImageFormat::Png ? decode_png(bytes, srgb) : decode_oiio(bytes, header, srgb);
  // Float formats (EXR, HDR, TIFF) can hold NaN and infinity, which no clamp downstream removes
  // (a NaN fails every comparison): such a texel would make the BRDF NaN wherever it is sampled.
  for (size_t i = 0; i < image->texels.size(); ++i) {
    const glm::vec4& t = image->texels[i];
    if (!std::isfinite(t.r) || !std::isfinite(t.g) || !std::isfinite(t.b) || !std::isfinite(t.a)) {
      const size_t width = static_cast<size_t>(image->width);
      throw ImageError("texel (" + std::to_string(i % width) + ", " + std::to_string(i / width) +
                       ") is not a finite number (NaN or infinity); lamina's images hold finite values");
    }
  }
  return image;
}

std::shared_ptr<const LinearImage> load_image_reference(const Reference& reference, bool srgb,
                                                        const AssetPolicy& policy) {
  const std::string bytes = read_reference(reference, kMaxBinaryFileBytes, policy);
  return decode_linear_image(bytes, srgb, policy.max_image_pixels);
}

std::shared_ptr<const LinearImage> load_image_file(const std::filesystem::path& path, bool srgb,
                                                   std::uint64_t max_pixels) {
  return decode_linear_image(read_input_file(path, kMaxBinaryFileBytes), srgb, max_pixels);
}

glm::vec4 sample_bilinear(const LinearImage& image, glm::vec2 uv, Wrap wrap) {
  if (image.width <= 0 || image.height <= 0) return glm::vec4(0.0f);
  glm::ivec4 t;
  glm::vec2 w = kernels::lamina_bilinear_texels(uv, image.width, image.height, int(wrap), t);
  auto texel = [&](int x, int y) {
    return image.texels[static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x)];
  };
  glm::vec4 top = glm::mix(texel(t.x, t.y), texel(t.z, t.y), w.x);
  glm::vec4 bottom = glm::mix(texel(t.x, t.w), texel(t.z, t.w), w.x);
  return glm::mix(top, bottom, w.y);
}

}  // namespace lamina
