#include "graph/cpu/image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>

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

struct PngState {
  std::string_view bytes;
  size_t position = 0;
  std::string error;
  std::jmp_buf jump;
};

void png_failed(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngState*>(png_get_error_ptr(png));
  state->error = message;
  std::longjmp(state->jump, 1);
}

void png_warned(png_structp, png_const_charp) {}  // recoverable: the image still decodes

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
    png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, png_failed, png_warned);
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

// --- every other format, through OpenImageIO reading from memory ----------------------------------

// OpenImageIO keeps errors per thread until they are retrieved; one left behind is printed when
// the program ends, so every failure takes it.
std::string oiio_error(const OIIO::ImageInput* input) {
  std::string why = input ? input->geterror() : std::string();
  const std::string global = OIIO::geterror();
  if (why.empty()) why = global;
  while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
  for (char& c : why)
    if (c == '\n') c = ';';
  return why.empty() ? "decoding failed" : why;
}

// The bytes as OpenImageIO's readers see them. OpenImageIO 2.4's IOMemReader copies past its
// buffer when asked to read at an offset beyond its end (a fuzzer found a tiled OpenEXR whose tile
// offsets point there); this one reads nothing there. It stays an IOMemReader because the JPEG
// reader takes the whole buffer from that class (libjpeg then stays inside it).
class MemoryReader final : public OIIO::Filesystem::IOMemReader {
 public:
  explicit MemoryReader(std::string_view bytes) : IOMemReader(bytes.data(), bytes.size()), bytes_(bytes) {}
  size_t read(void* out, size_t count) override {
    const size_t n = pread(out, count, m_pos);
    m_pos += static_cast<std::int64_t>(n);
    return n;
  }
  size_t pread(void* out, size_t count, std::int64_t offset) override {
    if (offset < 0 || static_cast<std::uint64_t>(offset) >= bytes_.size()) return 0;
    const size_t n = std::min(count, bytes_.size() - static_cast<size_t>(offset));
    std::memcpy(out, bytes_.data() + offset, n);
    return n;
  }

 private:
  std::string_view bytes_;
};

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

// Decodes a JPEG, OpenEXR, Radiance HDR or TIFF image whose header (read by lamina) fits the
// budget, with that format's reader alone: OpenImageIO would otherwise try every reader it has on
// bytes its first choice refuses.
std::shared_ptr<LinearImage> decode_oiio(std::string_view bytes, const ImageHeader& header, bool srgb) {
  const std::string format = format_name(header.format);
  auto input = OIIO::ImageInput::create(oiio_reader(header.format));
  if (!input) throw ImageError("cannot start the " + format + " decoder: " + oiio_error(nullptr));
  MemoryReader proxy(bytes);
  if (!input->set_ioproxy(&proxy))
    throw ImageError("cannot start the " + format + " decoder: " + oiio_error(input.get()));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as texture/image outputs it
  OIIO::ImageSpec spec;
  // The name is never opened: the reader reads the proxy.
  if (!input->open("image", spec, config))
    throw ImageError("not a readable " + format + " image: " + oiio_error(input.get()));
  if (spec.depth > 1)
    throw ImageError("the image is a volume of " + std::to_string(spec.depth) + " slices, not a texture");
  if (spec.width < 0 || spec.height < 0 || static_cast<std::uint64_t>(spec.width) != header.width ||
      static_cast<std::uint64_t>(spec.height) != header.height)
    throw ImageError("the " + format + " decoder reads " + std::to_string(spec.width) + " x " +
                     std::to_string(spec.height) + " pixels where the header declares " + std::to_string(header.width) +
                     " x " + std::to_string(header.height));
  if (spec.nchannels < 1) throw ImageError("the image has no channels");
  const int channels = std::min(spec.nchannels, 4);
  auto image = std::make_shared<LinearImage>();
  image->width = spec.width;
  image->height = spec.height;
  image->texels.resize(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height));
  // A band of rows at a time: the only copy of the whole image is the texels themselves. A tiled
  // image is read a row of tiles at a time (OpenImageIO 2.4's read_scanlines divides by zero on
  // tiled files).
  const bool tiled = spec.tile_width > 0 && spec.tile_height > 0;
  // Bands of scanlines hold up to 64 rows and about a million pixels, so the decoder's copy of
  // them stays small beside the texels.
  const int band_rows = std::min(spec.height, tiled ? spec.tile_height : std::clamp((1 << 20) / spec.width, 1, 64));
  std::vector<float> band(static_cast<size_t>(spec.width) * static_cast<size_t>(band_rows) *
                          static_cast<size_t>(channels));
  for (int y = 0; y < spec.height; y += band_rows) {
    const int end = std::min(spec.height, y + band_rows);
    const bool read = tiled ? input->read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y, spec.y + end, spec.z,
                                                spec.z + 1, 0, channels, OIIO::TypeDesc::FLOAT, band.data())
                            : input->read_scanlines(0, 0, spec.y + y, spec.y + end, spec.z, 0, channels,
                                                    OIIO::TypeDesc::FLOAT, band.data());
    if (!read) throw ImageError("cannot decode the " + format + " image: " + oiio_error(input.get()));
    for (int row = y; row < end; ++row)
      store_row(*image, row, band.data() + static_cast<size_t>(row - y) * static_cast<size_t>(spec.width) * channels,
                channels, srgb);
  }
  // Some decoders (TIFF) report a damaged file and still return rows.
  if (input->has_error()) throw ImageError("cannot decode the " + format + " image: " + oiio_error(input.get()));
  input->close();
  return image;
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
