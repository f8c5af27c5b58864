#include "graph/cpu/image_header.h"

#include <algorithm>
#include <cstring>

#include "graph/limits.h"

namespace lamina {

namespace {

bool starts_with(std::string_view bytes, std::string_view magic) { return bytes.substr(0, magic.size()) == magic; }

std::string count_text(std::uint64_t n) { return std::to_string(n); }

// Bounds-checked reads of a header. Every read names what it wanted, so that a short or lying
// header gives a reason rather than a read past the end.
class HeaderBytes {
 public:
  HeaderBytes(std::string_view bytes, ImageFormat format, bool big_endian = false)
      : bytes_(bytes), format_(format), big_endian_(big_endian) {}

  [[noreturn]] void fail(const std::string& why) const {
    throw ImageError("not a valid " + format_name(format_) + " image: " + why);
  }

  std::uint64_t size() const { return bytes_.size(); }
  bool has(std::uint64_t at, std::uint64_t count) const { return at <= bytes_.size() && count <= bytes_.size() - at; }
  void require(std::uint64_t at, std::uint64_t count, const std::string& what) const {
    if (!has(at, count))
      fail(what + " (" + count_text(count) + " bytes at byte " + count_text(at) + ") lies beyond the end of the " +
           count_text(bytes_.size()) + "-byte file");
  }

  std::uint64_t unsigned_at(std::uint64_t at, int width, const std::string& what) const {
    require(at, static_cast<std::uint64_t>(width), what);
    std::uint64_t value = 0;
    for (int i = 0; i < width; ++i) {
      const int shift = big_endian_ ? 8 * (width - 1 - i) : 8 * i;
      value |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[at + static_cast<std::uint64_t>(i)]))
               << shift;
    }
    return value;
  }
  std::uint64_t u8(std::uint64_t at, const std::string& what) const { return unsigned_at(at, 1, what); }
  std::uint64_t u16(std::uint64_t at, const std::string& what) const { return unsigned_at(at, 2, what); }
  std::uint64_t u32(std::uint64_t at, const std::string& what) const { return unsigned_at(at, 4, what); }
  std::uint64_t u64(std::uint64_t at, const std::string& what) const { return unsigned_at(at, 8, what); }
  std::int64_t i32(std::uint64_t at, const std::string& what) const {
    const auto u = static_cast<std::uint32_t>(u32(at, what));
    std::int32_t s;
    std::memcpy(&s, &u, 4);
    return s;
  }

  // A NUL-terminated string of at most `max_length` characters starting at `at`.
  std::string_view c_string(std::uint64_t at, std::uint64_t max_length, const std::string& what) const {
    for (std::uint64_t i = 0; i <= max_length; ++i) {
      require(at + i, 1, what);
      if (bytes_[at + i] == '\0') return bytes_.substr(at, i);
    }
    fail(what + " at byte " + count_text(at) + " is longer than " + count_text(max_length) + " characters");
  }

 private:
  std::string_view bytes_;
  ImageFormat format_;
  bool big_endian_;
};

// PNG (ISO/IEC 15948 sec. 5.3 and 11.2.2): the IHDR chunk comes first, right after the signature;
// libpng allocates each chunk's declared length before reading it, so every chunk up to IEND must
// lie inside the file.
ImageHeader png_header(std::string_view bytes) {
  const HeaderBytes b(bytes, ImageFormat::Png, true);
  if (b.u32(8, "the IHDR chunk's length") != 13 || bytes.substr(12, 4) != "IHDR")
    b.fail("the file does not start with an IHDR chunk of 13 bytes");
  ImageHeader h;
  h.format = ImageFormat::Png;
  h.width = b.u32(16, "the image width");
  h.height = b.u32(20, "the image height");
  h.bits = b.u8(24, "the bit depth");
  const std::uint64_t colour = b.u8(25, "the colour type");
  // Grey, RGB (or a palette of RGB), grey with alpha, RGB with alpha (sec. 11.2.2, table 11.1).
  h.channels = colour == 0 ? 1 : colour == 2 || colour == 3 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 0;
  if (h.channels == 0) b.fail("colour type " + count_text(colour) + " is not one of PNG's");
  for (std::uint64_t p = 8;;) {
    if (!b.has(p, 8)) b.fail("the file is truncated: it ends at byte " + count_text(p) + " without an IEND chunk");
    const std::uint64_t length = b.u32(p, "a chunk length");
    const std::string_view type = bytes.substr(p + 4, 4);
    if (length > 0x7fffffffu || !b.has(p + 8, length + 4))
      b.fail("the file is truncated: chunk '" + std::string(type) + "' at byte " + count_text(p) + " declares " +
             count_text(length) + " bytes, beyond the end of the " + count_text(b.size()) + "-byte file");
    if (type == "IEND") break;
    p += 12 + length;
  }
  return h;
}

// JPEG (ITU T.81 sec. B.1): segments until a start-of-frame marker, whose header gives the size.
ImageHeader jpeg_header(std::string_view bytes) {
  const HeaderBytes b(bytes, ImageFormat::Jpeg, true);
  std::uint64_t p = 2;
  for (;;) {
    if (b.u8(p, "a segment marker") != 0xff) b.fail("expected a segment marker at byte " + count_text(p));
    while (b.u8(p, "a segment marker") == 0xff) ++p;  // fill bytes
    const std::uint64_t marker = b.u8(p, "a segment marker");
    ++p;
    const bool standalone = marker == 0x01 || marker == 0xd8 || (marker >= 0xd0 && marker <= 0xd7);
    if (standalone) continue;
    if (marker == 0xd9 || marker == 0xda) b.fail("the image data starts before any frame header");
    const std::uint64_t length = b.u16(p, "a segment length");
    if (length < 2) b.fail("a segment at byte " + count_text(p) + " declares a length below 2");
    b.require(p, length, "a segment");
    const bool frame = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
    if (frame) {
      if (length < 8) b.fail("the frame header is shorter than 8 bytes");
      ImageHeader h;
      h.format = ImageFormat::Jpeg;
      h.bits = b.u8(p + 2, "the sample precision");
      h.height = b.u16(p + 3, "the image height");
      h.width = b.u16(p + 5, "the image width");
      h.channels = b.u8(p + 7, "the component count");
      if (h.height == 0) b.fail("the frame header leaves the height to a later DNL marker, which lamina does not read");
      return h;
    }
    p += length;
  }
}

// OpenEXR (the file layout of openexr.com's "OpenEXR File Layout"): magic, version and flags, then
// attributes (name, type, size, value) up to an empty name.
ImageHeader openexr_header(std::string_view bytes) {
  const HeaderBytes b(bytes, ImageFormat::OpenExr);
  const std::uint64_t version = b.u32(4, "the version field");
  constexpr std::uint64_t kTiled = 0x200, kLongNames = 0x400, kDeep = 0x800, kMultiPart = 0x1000;
  if ((version & 0xff) != 2) b.fail("file format version " + count_text(version & 0xff) + " (lamina reads version 2)");
  if (version & ~std::uint64_t{0xff | kTiled | kLongNames | kDeep | kMultiPart})
    b.fail("unknown flags in the version field");
  if (version & kMultiPart) b.fail("a multi-part file; lamina reads single-part images (write one part)");
  if (version & kDeep) b.fail("a deep image, which is no texture");
  const std::uint64_t max_name = (version & kLongNames) ? 255 : 31;

  ImageHeader h;
  h.format = ImageFormat::OpenExr;
  bool data_window = false, channels = false;
  std::uint64_t compression = 0;
  std::uint64_t p = 8;
  for (;;) {
    const std::string_view name = b.c_string(p, max_name, "an attribute name");
    p += name.size() + 1;
    if (name.empty()) break;
    const std::string attribute = "attribute '" + std::string(name) + "'";
    const std::string_view type = b.c_string(p, max_name, "the type of " + attribute);
    p += type.size() + 1;
    const std::int64_t size = b.i32(p, "the size of " + attribute);
    p += 4;
    if (size < 0) b.fail(attribute + " declares a negative size");
    const auto length = static_cast<std::uint64_t>(size);
    b.require(p, length, "the value of " + attribute);
    if (type == "box2i" && name == "dataWindow") {
      if (length != 16) b.fail("the dataWindow is not 16 bytes");
      const std::int64_t x_min = b.i32(p, "dataWindow"), y_min = b.i32(p + 4, "dataWindow");
      const std::int64_t x_max = b.i32(p + 8, "dataWindow"), y_max = b.i32(p + 12, "dataWindow");
      if (x_max < x_min || y_max < y_min) b.fail("the dataWindow is empty");
      h.width = static_cast<std::uint64_t>(x_max - x_min + 1);
      h.height = static_cast<std::uint64_t>(y_max - y_min + 1);
      data_window = true;
    } else if (type == "chlist") {
      // Channels: a name, then 16 bytes (pixel type, linearity, reserved, sampling), up to an
      // empty name; all inside the attribute.
      const HeaderBytes value(bytes.substr(0, p + length), ImageFormat::OpenExr);
      std::uint64_t q = p;
      for (;;) {
        const std::string_view channel = value.c_string(q, max_name, "a channel name");
        q += channel.size() + 1;
        if (channel.empty()) break;
        const std::string what = "the description of channel '" + std::string(channel) + "'";
        value.require(q, 16, what);
        // Pixel type 0 (uint), 1 (half), 2 (float).
        const std::uint64_t type_code = value.u32(q, what);
        if (type_code > 2) b.fail("channel '" + std::string(channel) + "' has an unknown pixel type");
        h.bits = std::max<std::uint64_t>(h.bits, type_code == 1 ? 16 : 32);
        ++h.channels;
        q += 16;
        channels = true;
      }
    } else if (type == "tiledesc" && name == "tiles") {
      if (length != 9) b.fail("the tile description is not 9 bytes");
      h.chunk_width = b.u32(p, "the tile width");
      h.chunk_height = b.u32(p + 4, "the tile height");
      if (h.chunk_width == 0 || h.chunk_height == 0) b.fail("a tile size of 0");
      h.tiled = true;
    } else if (type == "compression" && name == "compression") {
      if (length != 1) b.fail("the compression is not 1 byte");
      compression = b.u8(p, "the compression");
      if (compression > 9) b.fail("unknown compression " + count_text(compression));
    } else if (type == "preview") {
      // Width and height, then 4 bytes a pixel: the decoder allocates what they declare.
      if (length < 8) b.fail("the preview image is shorter than its own size fields");
      const std::uint64_t w = b.u32(p, "the preview width"), ht = b.u32(p + 4, "the preview height");
      if ((length - 8) % 4 != 0 || w * ht != (length - 8) / 4)  // w * ht < 2^64
        b.fail("the preview image declares " + count_text(w) + " x " + count_text(ht) + " pixels, which its " +
               count_text(length) + " bytes do not hold");
    } else if (type == "stringvector") {
      // Strings, each a 4-byte length and its bytes, filling the attribute.
      for (std::uint64_t q = p; q < p + length;) {
        if (p + length - q < 4) b.fail("a string of " + attribute + " runs past the attribute's end");
        const std::int64_t n = b.i32(q, "a string of " + attribute);
        if (n < 0 || static_cast<std::uint64_t>(n) > p + length - q - 4)
          b.fail("a string of " + attribute + " runs past the attribute's end");
        q += 4 + static_cast<std::uint64_t>(n);
      }
    }
    p += length;
  }
  if (!data_window) b.fail("the header has no dataWindow");
  if (!channels) b.fail("the header names no channel");
  if ((version & kTiled) && !h.tiled) b.fail("a tiled file without a tile description");
  if (!h.tiled) {
    // Scanlines come in blocks whose height the compression sets: none, RLE and ZIPS 1, ZIP and
    // PXR24 16, PIZ, B44, B44A and DWAA 32, DWAB 256.
    constexpr std::uint64_t kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    h.chunk_width = h.width;
    h.chunk_height = kLines[compression];
  }
  return h;
}

// Radiance HDR (Ward, "The RADIANCE Picture File Format"): text lines up to an empty one, then the
// resolution line, e.g. "-Y 512 +X 768".
ImageHeader radiance_header(std::string_view bytes) {
  const HeaderBytes b(bytes, ImageFormat::RadianceHdr);
  constexpr std::uint64_t kMaxHeaderBytes = 1 << 16;
  std::uint64_t p = 0;
  for (;;) {
    const size_t end = bytes.find('\n', p);
    if (end == std::string_view::npos || end > kMaxHeaderBytes)
      b.fail("the header does not end with an empty line within its first " + count_text(kMaxHeaderBytes) + " bytes");
    const bool empty = end == p;
    p = end + 1;
    if (empty) break;
  }
  const size_t end = bytes.find('\n', p);
  const std::string_view line = bytes.substr(p, end == std::string_view::npos ? 64 : end - p);
  // Two (sign, axis, count) triples naming X and Y once each.
  std::uint64_t counts[2] = {0, 0};
  char axes[2] = {0, 0};
  size_t i = 0;
  for (int k = 0; k < 2; ++k) {
    while (i < line.size() && line[i] == ' ') ++i;
    if (i + 1 >= line.size() || (line[i] != '+' && line[i] != '-') || (line[i + 1] != 'X' && line[i + 1] != 'Y'))
      b.fail("the resolution line is not of the form '-Y height +X width'");
    axes[k] = line[i + 1];
    i += 2;
    while (i < line.size() && line[i] == ' ') ++i;
    size_t digits = 0;
    for (; i < line.size() && line[i] >= '0' && line[i] <= '9'; ++i, ++digits) {
      if (digits == 10) b.fail("the resolution line gives a size of more than 10 digits");
      counts[k] = counts[k] * 10 + static_cast<std::uint64_t>(line[i] - '0');
    }
    if (digits == 0) b.fail("the resolution line is not of the form '-Y height +X width'");
  }
  if (axes[0] == axes[1]) b.fail("the resolution line names the same axis twice");
  ImageHeader h;
  h.format = ImageFormat::RadianceHdr;
  h.width = axes[0] == 'X' ? counts[0] : counts[1];
  h.height = axes[0] == 'Y' ? counts[0] : counts[1];
  h.channels = 3;  // RGBE or XYZE: a shared exponent, decoded to three floats
  h.bits = 32;
  return h;
}

// TIFF 6.0 (sec. 2 and 8) and BigTIFF: the first image file directory gives width, length and,
// for tiled files, the tile size.
ImageHeader tiff_header(std::string_view bytes) {
  const HeaderBytes b(bytes, ImageFormat::Tiff, bytes[0] == 'M');
  const bool big = b.u16(2, "the version") == 43;
  std::uint64_t directory = 0;
  if (big) {
    if (b.u16(4, "the offset size") != 8) b.fail("a BigTIFF header with offsets that are not 8 bytes");
    directory = b.u64(8, "the first directory's offset");
  } else {
    directory = b.u32(4, "the first directory's offset");
  }
  const std::uint64_t count =
      big ? b.u64(directory, "the directory's entry count") : b.u16(directory, "the directory's entry count");
  const std::uint64_t first = directory + (big ? 8 : 2), entry_size = big ? 20 : 12;
  if (count > (b.size() / entry_size)) b.fail("the first directory declares more entries than the file holds");
  b.require(first, count * entry_size, "the first directory");
  ImageHeader h;
  h.format = ImageFormat::Tiff;
  h.channels = 1;  // TIFF's defaults: one sample of one bit
  h.bits = 1;
  std::uint64_t bits_entry = 0, rows_per_strip = 0xffffffffu;  // TIFF's default: one strip
  for (std::uint64_t e = 0; e < count; ++e) {
    const std::uint64_t at = first + e * entry_size;
    const std::uint64_t tag = b.u16(at, "a tag");
    const bool size_tag = tag == 256 || tag == 257 || tag == 322 || tag == 323 || tag == 277 || tag == 278;
    if (tag == 258) bits_entry = at;
    if (!size_tag) continue;
    const std::uint64_t type = b.u16(at + 2, "a tag's type");
    const std::uint64_t values = big ? b.u64(at + 4, "a tag's count") : b.u32(at + 4, "a tag's count");
    const std::uint64_t field = at + (big ? 12 : 8);
    // SHORT, LONG or LONG8, one value, held in the entry itself.
    std::uint64_t value = 0;
    if (values == 1 && type == 3)
      value = b.u16(field, "a size tag");
    else if (values == 1 && type == 4)
      value = b.u32(field, "a size tag");
    else if (values == 1 && type == 16 && big)
      value = b.u64(field, "a size tag");
    else
      b.fail("tag " + count_text(tag) + " is not one SHORT or LONG value");
    (tag == 256   ? h.width
     : tag == 257 ? h.height
     : tag == 322 ? h.chunk_width
     : tag == 323 ? h.chunk_height
     : tag == 277 ? h.channels
                  : rows_per_strip) = value;
  }
  if (bits_entry) {
    // BitsPerSample: a SHORT per sample, in the entry when they fit, else at the offset it holds.
    if (b.u16(bits_entry + 2, "the type of BitsPerSample") != 3) b.fail("BitsPerSample is not of type SHORT");
    const std::uint64_t values =
        big ? b.u64(bits_entry + 4, "BitsPerSample's count") : b.u32(bits_entry + 4, "BitsPerSample's count");
    if (values == 0 || values > h.channels) b.fail("BitsPerSample gives " + count_text(values) + " values");
    const std::uint64_t field = bits_entry + (big ? 12 : 8);
    const std::uint64_t inline_bytes = big ? 8 : 4;
    const std::uint64_t at = values * 2 <= inline_bytes ? field
                             : big                      ? b.u64(field, "BitsPerSample's offset")
                                                        : b.u32(field, "BitsPerSample's offset");
    h.bits = 0;
    for (std::uint64_t i = 0; i < values; ++i) h.bits = std::max(h.bits, b.u16(at + 2 * i, "a BitsPerSample value"));
  }
  if (h.width == 0 || h.height == 0) b.fail("the first directory gives no image width and length");
  if ((h.chunk_width == 0) != (h.chunk_height == 0))
    b.fail("the first directory gives only one of tile width and length");
  h.tiled = h.chunk_width > 0;
  if (!h.tiled) {
    // OpenImageIO 2.4 allocates RowsPerStrip rows for a strip, even beyond the image's height;
    // only TIFF's "one strip" value, 2^32 - 1, stands for the image's height.
    h.chunk_width = h.width;
    h.chunk_height = rows_per_strip == 0xffffffffu ? h.height : rows_per_strip;
    if (h.chunk_height == 0) b.fail("RowsPerStrip is 0");
  }
  return h;
}

}  // namespace

bool image_format_of(std::string_view bytes, ImageFormat& format) {
  using namespace std::string_view_literals;
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n"sv))
    format = ImageFormat::Png;
  else if (starts_with(bytes, "\xff\xd8\xff"sv))
    format = ImageFormat::Jpeg;
  else if (starts_with(bytes, "\x76\x2f\x31\x01"sv))
    format = ImageFormat::OpenExr;
  else if (starts_with(bytes, "#?RADIANCE"sv) || starts_with(bytes, "#?RGBE"sv))
    format = ImageFormat::RadianceHdr;
  else if (starts_with(bytes, "II*\0"sv) || starts_with(bytes, "MM\0*"sv) || starts_with(bytes, "II+\0"sv) ||
           starts_with(bytes, "MM\0+"sv))
    format = ImageFormat::Tiff;
  else
    return false;
  return true;
}

std::string format_name(ImageFormat format) {
  switch (format) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::OpenExr: return "OpenEXR";
    case ImageFormat::RadianceHdr: return "Radiance HDR";
    case ImageFormat::Tiff: return "TIFF";
  }
  return "image";
}

namespace {

ImageHeader header_of(std::string_view bytes) {
  ImageFormat format;
  if (!image_format_of(bytes, format))
    throw ImageError(
        "not an image format lamina reads (PNG, JPEG, OpenEXR, Radiance HDR or TIFF, told by the file's first bytes)");
  switch (format) {
    case ImageFormat::Png: return png_header(bytes);
    case ImageFormat::Jpeg: return jpeg_header(bytes);
    case ImageFormat::OpenExr: return openexr_header(bytes);
    case ImageFormat::RadianceHdr: return radiance_header(bytes);
    case ImageFormat::Tiff: return tiff_header(bytes);
  }
  throw ImageError("not an image format lamina reads");
}

}  // namespace

ImageHeader read_image_header(std::string_view bytes) {
  ImageHeader h = header_of(bytes);
  // A decoder's buffers hold the file's own pixels, all channels of them: no more than the 4
  // floats a texel has, so that decoding never needs more than a few times the decoded image.
  if (h.channels < 1 || h.channels > kMaxImageChannels)
    throw ImageError("the image has " + count_text(h.channels) + " channels; lamina reads images of 1 to " +
                     count_text(kMaxImageChannels) +
                     " (keep the ones a texture needs, e.g. with oiiotool --ch R,G,B,A)");
  if (h.bits < 1 || h.bits > kMaxImageSampleBits)
    throw ImageError("the image has samples of " + count_text(h.bits) + " bits; lamina reads samples of at most " +
                     count_text(kMaxImageSampleBits));
  return h;
}

std::string image_budget_problem(const ImageHeader& header, std::uint64_t max_pixels) {
  const std::string size = count_text(header.width) + " x " + count_text(header.height) + " pixels";
  if (header.width == 0 || header.height == 0) return "the image has no pixels (" + size + ")";
  if (header.width > kMaxImageSide || header.height > kMaxImageSide)
    return "the image is " + size + ", wider or taller than " + count_text(kMaxImageSide) +
           " pixels, which lamina never decodes";
  if (header.width * header.height > max_pixels)
    return "the image is " + size + ", more than the budget of " + count_text(max_pixels) +
           " pixels (raise it with --max-image-pixels)";
  if (header.chunk_width > kMaxImageSide || header.chunk_height > kMaxImageSide ||
      header.chunk_width * header.chunk_height > max_pixels)
    return "the image is stored in " + std::string(header.tiled ? "tiles" : "blocks of rows") + " of " +
           count_text(header.chunk_width) + " x " + count_text(header.chunk_height) +
           " pixels, more than the budget of " + count_text(max_pixels) + " pixels (raise it with --max-image-pixels)";
  return "";
}

}  // namespace lamina
