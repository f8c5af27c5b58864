// What lamina reads of an encoded image before any decoder sees it. Decoders allocate from what a
// header declares (OpenEXR sizes a string attribute, libtiff and OpenImageIO size their buffers),
// so a 600-byte file could make them allocate gigabytes. lamina therefore reads the header of each
// format it accepts itself, checks that every length it declares lies inside the bytes, and hands
// the image to a decoder only once its size fits the pixel budget.
//
// The formats are recognised by their signature, never by a file name: PNG, JPEG, OpenEXR
// (single-part, scanline or tiled), Radiance HDR and TIFF. Every other format is refused, so that no
// input reaches the dozens of other decoders OpenImageIO carries.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace lamina {

// Bytes that are not an image lamina can decode, or one beyond the pixel budget; the message is
// lamina's own words with the decoder's reason, never the decoder's output on the terminal.
class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ImageFormat { Png, Jpeg, OpenExr, RadianceHdr, Tiff };

struct ImageHeader {
  ImageFormat format = ImageFormat::Png;
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  // The block a decoder reads and allocates at once, whatever the image's size: a tile, a TIFF
  // strip, an OpenEXR block of scanlines. 0 x 0 for images decoded row by row (PNG, JPEG, HDR).
  std::uint64_t chunk_width = 0;
  std::uint64_t chunk_height = 0;
  bool tiled = false;
  // What a stored pixel holds: channels (all of them, also those lamina does not use) and the
  // largest sample size in bits.
  std::uint64_t channels = 0;
  std::uint64_t bits = 0;
};

// The format the bytes' signature names, or false when it is none of lamina's.
bool image_format_of(std::string_view bytes, ImageFormat& format);

// "PNG", "JPEG", "OpenEXR", "Radiance HDR", "TIFF".
std::string format_name(ImageFormat format);

// The header of an encoded image, read without decoding a pixel and without trusting any length
// it declares. Throws ImageError for an unknown format, a malformed header, or pixels of more than
// kMaxImageChannels channels or samples of more than kMaxImageSampleBits bits.
ImageHeader read_image_header(std::string_view bytes);

// Why the image is refused under `max_pixels` (its size, a side beyond kMaxImageSide, or chunks
// larger than the budget), or "" when it fits.
std::string image_budget_problem(const ImageHeader& header, std::uint64_t max_pixels);

}  // namespace lamina
