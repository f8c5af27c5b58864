#include "graph/gltf/png_encode.h"

#include <stdexcept>
#include <string>

#include "graph/png_trap.h"

namespace lamina::gltf {

namespace {

// Where the writer writes, and libpng's error trap.
struct PngWriteState : PngTrap {
  std::vector<unsigned char>* bytes = nullptr;
};

void png_write_bytes(png_structp png, png_bytep data, size_t count) {
  auto* state = static_cast<PngWriteState*>(png_get_io_ptr(png));
  state->bytes->insert(state->bytes->end(), data, data + count);
}

void png_flush_nothing(png_structp) {}

// Writes every row; false (state.error says why) when libpng fails. Kept apart from encode_png so
// that no object with a destructor lives across the setjmp.
bool write_rows(png_structp png, png_infop info, PngWriteState& state, int width, int height, int channels,
                const uint8_t* pixels) {
  if (setjmp(state.jump)) return false;
  static constexpr int kColourType[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                        PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_write_fn(png, &state, png_write_bytes, png_flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               kColourType[channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const size_t row_bytes = static_cast<size_t>(width) * static_cast<size_t>(channels);
  for (int y = 0; y < height; ++y)
    png_write_row(png, const_cast<png_bytep>(pixels + static_cast<size_t>(y) * row_bytes));
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

std::vector<unsigned char> encode_png(int width, int height, int channels, std::span<const uint8_t> pixels) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      pixels.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels))
    throw std::invalid_argument("encode_png: pixel count does not match the image size");
  std::vector<unsigned char> bytes;
  PngWriteState state;
  state.bytes = &bytes;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, static_cast<PngTrap*>(&state), png_trap_error, png_drop_warning);
  if (png == nullptr) throw std::runtime_error("cannot create a PNG writer");
  png_infop info = png_create_info_struct(png);
  const bool ok = info != nullptr && write_rows(png, info, state, width, height, channels, pixels.data());
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error("cannot encode a PNG image: " + (state.error.empty() ? "no memory" : state.error));
  return bytes;
}

}  // namespace lamina::gltf
