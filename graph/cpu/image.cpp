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

bool starts_with(std::string_view bytes, std::string_view magic) { return bytes.substr(0, magic.size()) == magic; }

// The decoder to use: what the bytes say they are, else the file name's extension.
std::string format_of(std::string_view bytes, const std::string& name) {
  if (std::string format = image_format_of(bytes); !format.empty()) return format;
  std::string ext = std::filesystem::path(name).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

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

// Everything that may longjmp lives here, with no C++ object that needs destroying in its frame:
// `rows` and `image` belong to the caller.
// The buffers of a decode, owned outside the frame that may be left by longjmp.
struct PngBuffers {
  std::vector<unsigned char> rows;
  std::vector<png_bytep> pointers;
  std::vector<float> converted;
};

// Why `width` x `height` is refused, or "" when it fits the budget.
std::string budget_problem(std::uint64_t width, std::uint64_t height, std::uint64_t max_pixels) {
  if (width == 0 || height == 0)
    return "the image has no pixels (" + std::to_string(width) + " x " + std::to_string(height) + ")";
  if (width > kMaxImageSide || height > kMaxImageSide || width * height > max_pixels)
    return "the image is " + std::to_string(width) + " x " + std::to_string(height) +
           " pixels, more than the budget of " + std::to_string(max_pixels) +
           " pixels (raise it with --max-image-pixels)";
  return "";
}

bool png_run(png_structp png, png_infop info, PngState& state, std::uint64_t max_pixels, bool header_only, bool srgb,
             PngLayout& layout, PngBuffers& buffers, LinearImage& image, std::string& budget_error) {
  if (setjmp(state.jump)) return false;
  png_set_read_fn(png, &state, png_read_bytes);
  png_set_user_limits(png, static_cast<png_uint_32>(kMaxImageSide), static_cast<png_uint_32>(kMaxImageSide));
  png_read_info(png, info);
  layout.width = png_get_image_width(png, info);
  layout.height = png_get_image_height(png, info);
  const int color_type = png_get_color_type(png, info);
  int bit_depth = png_get_bit_depth(png, info);
  if (header_only) {
    layout.channels = (color_type & PNG_COLOR_MASK_PALETTE) ? 3 : (color_type & PNG_COLOR_MASK_COLOR) ? 3 : 1;
    if ((color_type & PNG_COLOR_MASK_ALPHA) || png_get_valid(png, info, PNG_INFO_tRNS)) ++layout.channels;
    return true;
  }
  budget_error = budget_problem(layout.width, layout.height, max_pixels);
  if (!budget_error.empty()) return false;
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (bit_depth == 16) png_set_swap(png);  // little-endian host: 16-bit samples in host order
  layout.interlaced = png_set_interlace_handling(png) > 1;
  png_read_update_info(png, info);
  layout.channels = png_get_channels(png, info);
  layout.bit_depth = bit_depth = png_get_bit_depth(png, info);
  layout.row_bytes = png_get_rowbytes(png, info);

  image.width = static_cast<int>(layout.width);
  image.height = static_cast<int>(layout.height);
  image.texels.resize(static_cast<size_t>(layout.width) * layout.height);
  // Interlaced images revisit rows, so they need every row at once; the others go row by row.
  std::vector<unsigned char>& rows = buffers.rows;
  std::vector<float>& converted = buffers.converted;
  rows.resize(layout.row_bytes * (layout.interlaced ? layout.height : 1));
  if (layout.interlaced) {
    for (std::uint32_t y = 0; y < layout.height; ++y) buffers.pointers.push_back(rows.data() + y * layout.row_bytes);
    png_read_image(png, buffers.pointers.data());
  }
  converted.resize(static_cast<size_t>(layout.width) * static_cast<size_t>(layout.channels));
  for (std::uint32_t y = 0; y < layout.height; ++y) {
    unsigned char* row = layout.interlaced ? rows.data() + y * layout.row_bytes : rows.data();
    if (!layout.interlaced) png_read_row(png, row, nullptr);
    for (size_t i = 0; i < converted.size(); ++i) {
      if (bit_depth == 16) {
        std::uint16_t v;
        std::memcpy(&v, row + 2 * i, 2);
        converted[i] = static_cast<float>(v) / 65535.0f;
      } else {
        converted[i] = static_cast<float>(row[i]) / 255.0f;
      }
    }
    store_row(image, static_cast<int>(y), converted.data(), layout.channels, srgb);
  }
  png_read_end(png, nullptr);
  return true;
}

// Decodes (or with `header_only` only reads the header of) a PNG.
std::shared_ptr<LinearImage> decode_png(std::string_view bytes, std::uint64_t max_pixels, bool srgb, bool header_only,
                                        ImageHeader& header) {
  PngState state;
  state.bytes = bytes;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, png_failed, png_warned);
  if (!png) throw ImageError("cannot start the PNG decoder");
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw ImageError("cannot start the PNG decoder");
  }
  auto image = std::make_shared<LinearImage>();
  PngBuffers buffers;
  PngLayout layout;
  std::string budget_error;
  bool ok = false;
  try {
    ok = png_run(png, info, state, max_pixels, header_only, srgb, layout, buffers, *image, budget_error);
  } catch (...) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw;
  }
  png_destroy_read_struct(&png, &info, nullptr);
  if (!budget_error.empty()) throw ImageError(budget_error);
  if (!ok) throw ImageError("not a valid PNG image: " + (state.error.empty() ? "decoding failed" : state.error));
  header = ImageHeader{"png", static_cast<int>(layout.width), static_cast<int>(layout.height), layout.channels};
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

std::shared_ptr<LinearImage> decode_oiio(std::string_view bytes, const std::string& format, std::uint64_t max_pixels,
                                         bool srgb, bool header_only, ImageHeader& header) {
  OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
  OIIO::Filesystem::IOProxy* proxy_pointer = &proxy;
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as texture/image outputs it
  // The readers take the memory proxy from the configuration (OpenImageIO 2.4); the name only picks
  // the reader and is never opened.
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_pointer);
  const std::string pseudo_name = "image." + format;
  auto input = OIIO::ImageInput::open(pseudo_name, &config);
  if (!input) throw ImageError("not a readable " + format + " image: " + oiio_error(nullptr));
  const OIIO::ImageSpec spec = input->spec();
  header = ImageHeader{input->format_name(), spec.width, spec.height, spec.nchannels};
  if (header_only) {
    input->close();
    return nullptr;
  }
  if (spec.depth > 1)
    throw ImageError("the image is a volume of " + std::to_string(spec.depth) + " slices, not a texture");
  if (spec.width < 0 || spec.height < 0) throw ImageError("the image's header gives a negative size");
  if (std::string why =
          budget_problem(static_cast<std::uint64_t>(spec.width), static_cast<std::uint64_t>(spec.height), max_pixels);
      !why.empty())
    throw ImageError(why);
  if (spec.nchannels < 1) throw ImageError("the image has no channels");
  const int channels = std::min(spec.nchannels, 4);
  auto image = std::make_shared<LinearImage>();
  image->width = spec.width;
  image->height = spec.height;
  image->texels.resize(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height));
  // A band of rows at a time: the only copy of the whole image is the texels themselves.
  constexpr int kBand = 64;
  std::vector<float> band(static_cast<size_t>(spec.width) * kBand * static_cast<size_t>(channels));
  for (int y = 0; y < spec.height; y += kBand) {
    const int end = std::min(spec.height, y + kBand);
    if (!input->read_scanlines(0, 0, spec.y + y, spec.y + end, spec.z, 0, channels, OIIO::TypeDesc::FLOAT, band.data()))
      throw ImageError("cannot decode the " + format + " image: " + oiio_error(input.get()));
    for (int row = y; row < end; ++row)
      store_row(*image, row, band.data() + static_cast<size_t>(row - y) * static_cast<size_t>(spec.width) * channels,
                channels, srgb);
  }
  // Some decoders (TIFF) report a damaged file and still return rows.
  if (input->has_error()) throw ImageError("cannot decode the " + format + " image: " + oiio_error(input.get()));
  input->close();
  return image;
}

std::shared_ptr<LinearImage> decode(std::string_view bytes, const std::string& name, std::uint64_t max_pixels,
                                    bool srgb, bool header_only, ImageHeader& header) {
  const std::string format = format_of(bytes, name);
  if (format.empty())
    throw ImageError("not an image lamina recognises (no known signature, and the name has no extension)");
  if (format == "png") return decode_png(bytes, max_pixels, srgb, header_only, header);
  return decode_oiio(bytes, format, max_pixels, srgb, header_only, header);
}

}  // namespace

std::string image_format_of(std::string_view bytes) {
  using namespace std::string_view_literals;
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n"sv)) return "png";
  if (starts_with(bytes, "\xff\xd8\xff"sv)) return "jpg";
  if (starts_with(bytes, "\x76\x2f\x31\x01"sv)) return "exr";
  if (starts_with(bytes, "II*\0"sv) || starts_with(bytes, "MM\0*"sv) || starts_with(bytes, "II+\0"sv) ||
      starts_with(bytes, "MM\0+"sv))
    return "tif";
  if (starts_with(bytes, "#?RADIANCE"sv) || starts_with(bytes, "#?RGBE"sv)) return "hdr";
  if (starts_with(bytes, "BM"sv)) return "bmp";
  if (starts_with(bytes, "GIF87a"sv) || starts_with(bytes, "GIF89a"sv)) return "gif";
  if (starts_with(bytes, "RIFF"sv) && bytes.size() >= 12 && bytes.substr(8, 4) == "WEBP") return "webp";
  if (starts_with(bytes, "8BPS"sv)) return "psd";
  if (starts_with(bytes, "DDS "sv)) return "dds";
  return "";
}

ImageHeader read_image_header(std::string_view bytes, const std::string& name) {
  ImageHeader header;
  decode(bytes, name, 0, false, true, header);
  return header;
}

std::shared_ptr<const LinearImage> decode_linear_image(std::string_view bytes, const std::string& name, bool srgb,
                                                       std::uint64_t max_pixels) {
  ImageHeader header;
  return decode(bytes, name, max_pixels, srgb, false, header);
}

std::shared_ptr<const LinearImage> load_image_reference(const Reference& reference, bool srgb,
                                                        const AssetPolicy& policy) {
  const std::string bytes = read_reference(reference, kMaxBinaryFileBytes, policy);
  return decode_linear_image(bytes, reference.resolved.filename().string(), srgb, policy.max_image_pixels);
}

std::shared_ptr<const LinearImage> load_image_file(const std::filesystem::path& path, bool srgb,
                                                   std::uint64_t max_pixels) {
  return decode_linear_image(read_input_file(path, kMaxBinaryFileBytes), path.filename().string(), srgb, max_pixels);
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
