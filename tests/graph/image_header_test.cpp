// lamina reads every image header itself before a decoder sees the bytes: what it reads agrees
// with the decoders on real files, and a header that lies is refused with a reason.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "graph/cpu/image.h"
#include "graph/cpu/image_header.h"
#include "graph/limits.h"
#include "test_support.h"

using namespace lamina;
namespace fs = std::filesystem;

namespace {

std::string seed(const std::string& name) {
  return test::read_file(test::source_dir() / "tests/fuzz/seeds/image" / name);
}

// An image written by oiiotool with `options`, as bytes.
std::string made_by_oiiotool(const std::string& options, const std::string& extension) {
  test::TempDir dir;
  const fs::path out = dir.path() / ("image." + extension);
  const std::string command =
      "oiiotool --pattern fill:top=0,0,0:bottom=1,0.5,0.25 " + options + " -o '" + out.string() + "' >/dev/null 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
  return test::read_file(out);
}

void put_u32(std::string& bytes, size_t at, std::uint32_t value) { std::memcpy(bytes.data() + at, &value, 4); }

// Where the value of OpenEXR attribute `name` starts (after its name, type and size).
size_t exr_attribute_value(const std::string& exr, const std::string& name, const std::string& type) {
  const std::string field = name + std::string(1, '\0') + type + std::string(1, '\0');
  const size_t at = exr.find(field);
  REQUIRE(at != std::string::npos);
  return at + field.size() + 4;
}

// Sets tag `tag` of a little-endian TIFF's first directory to one LONG `value`.
void set_tiff_tag(std::string& tiff, std::uint16_t tag, std::uint32_t value) {
  std::uint32_t directory = 0;
  std::memcpy(&directory, tiff.data() + 4, 4);
  std::uint16_t entries = 0;
  std::memcpy(&entries, tiff.data() + directory, 2);
  bool found = false;
  for (std::uint32_t e = 0; e < entries; ++e) {
    const size_t at = directory + 2 + 12 * e;
    std::uint16_t entry_tag = 0;
    std::memcpy(&entry_tag, tiff.data() + at, 2);
    if (entry_tag != tag) continue;
    const std::uint16_t type_long = 4;
    std::memcpy(tiff.data() + at + 2, &type_long, 2);
    put_u32(tiff, at + 8, value);
    found = true;
  }
  REQUIRE(found);
}

std::string refusal(const std::string& bytes) {
  try {
    read_image_header(bytes);
  } catch (const ImageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the header lamina reads gives the size every decoder then decodes, for each format it reads") {
  struct Case {
    std::string what, bytes;
    ImageFormat format;
  };
  const Case cases[] = {
      {"8-bit RGB PNG", seed("rgb.png"), ImageFormat::Png},
      {"16-bit grey PNG", seed("grey16.png"), ImageFormat::Png},
      {"JPEG", seed("rgb.jpg"), ImageFormat::Jpeg},
      {"scanline OpenEXR", seed("float.exr"), ImageFormat::OpenExr},
      {"tiled OpenEXR", seed("tiled.exr"), ImageFormat::OpenExr},
      {"Radiance HDR", seed("radiance.hdr"), ImageFormat::RadianceHdr},
      {"TIFF", seed("float.tif"), ImageFormat::Tiff},
      {"tiled TIFF", seed("tiled.tif"), ImageFormat::Tiff},
      {"big-endian TIFF", made_by_oiiotool("5x3 3 -d uint16 --attrib tiff:bigendian 1", "tif"), ImageFormat::Tiff},
      {"BigTIFF", made_by_oiiotool("6x2 3 -d uint8 --attrib tiff:bigtiff 1", "tif"), ImageFormat::Tiff},
      {"interlaced PNG", made_by_oiiotool("7x5 4 -d uint8 --attrib png:interlace 1", "png"), ImageFormat::Png},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    const ImageHeader header = read_image_header(c.bytes);
    CHECK(header.format == c.format);
    const auto image = decode_linear_image(c.bytes, false, kDefaultMaxImagePixels);
    CHECK(header.width == static_cast<std::uint64_t>(image->width));
    CHECK(header.height == static_cast<std::uint64_t>(image->height));
    CHECK(header.width > 0);
  }
  CHECK(read_image_header(seed("tiled.exr")).chunk_width == 4);
  CHECK(read_image_header(seed("tiled.tif")).chunk_height == 16);
  CHECK(read_image_header(seed("tiled.tif")).tiled);
  CHECK(!read_image_header(seed("float.exr")).tiled);
}

TEST_CASE("formats lamina does not read are refused by their bytes, whatever the file is called") {
  for (const std::string& bytes : {std::string("BM\x36\0\0\0", 6), std::string("GIF89a\x01\0\x01\0", 10),
                                   std::string("\0\0\x02\0\0\0\0\0\0\0\0\0\x01\0\x01\0\x18\0", 18),
                                   std::string("PF\n2 1\n-1.0\n"), std::string(), std::string("8BPS")}) {
    CAPTURE(bytes);
    CHECK(refusal(bytes).find("not an image format lamina reads (PNG, JPEG, OpenEXR, Radiance HDR or TIFF") == 0);
    CHECK_THROWS_AS(decode_linear_image(bytes, false, kDefaultMaxImagePixels), ImageError);
  }
}

TEST_CASE("every prefix of every seed image is read as a header or refused, never read past its end") {
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "tests/fuzz/seeds/image")) {
    const std::string bytes = test::read_file(entry.path());
    size_t refused = 0;
    for (size_t n = 0; n <= bytes.size(); ++n) {
      const std::string prefix = bytes.substr(0, n);
      try {
        read_image_header(prefix);
      } catch (const ImageError&) {
        ++refused;
      }
      // What the header accepts, the decoders get; a cut image fails there, with lamina's error.
      try {
        decode_linear_image(prefix, false, kDefaultMaxImagePixels);
      } catch (const ImageError&) {
      }
    }
    CAPTURE(entry.path().filename().string());
    CHECK(refused > 0);
    CHECK(refused < bytes.size() + 1);
  }
}

TEST_CASE("an OpenEXR attribute that declares more bytes than the file holds is refused before OpenEXR allocates") {
  // A fuzzer found that OpenEXR allocates a string attribute's declared size (1.9 GB from a
  // 601-byte file) before reading it.
  std::string exr = seed("float.exr");
  put_u32(exr, exr_attribute_value(exr, "Software", "string") - 4, 1929405792u);
  CHECK(refusal(exr).find("the value of attribute 'Software' (1929405792 bytes at byte") != std::string::npos);
  CHECK(refusal(exr).find("lies beyond the end of the 601-byte file") != std::string::npos);
  std::string negative = seed("float.exr");
  put_u32(negative, exr_attribute_value(negative, "Software", "string") - 4, 0xfffffff0u);
  CHECK(refusal(negative).find("attribute 'Software' declares a negative size") != std::string::npos);
}

TEST_CASE("an OpenEXR header is refused when it is multi-part, deep, without a data window or with a lying preview") {
  const std::string exr = seed("float.exr");
  auto with_flags = [&](std::uint32_t flags) {
    std::string bytes = exr;
    put_u32(bytes, 4, 2u | flags);
    return refusal(bytes);
  };
  CHECK(with_flags(0x1000).find("multi-part") != std::string::npos);
  CHECK(with_flags(0x800).find("a deep image") != std::string::npos);
  CHECK(with_flags(0x200).find("a tiled file without a tile description") != std::string::npos);
  CHECK(with_flags(0x4000).find("unknown flags") != std::string::npos);
  std::string renamed = exr;
  renamed.replace(renamed.find("dataWindow"), 10, "dataWindoX");
  CHECK(refusal(renamed).find("the header has no dataWindow") != std::string::npos);
  std::string empty_window = exr;
  const size_t window = exr_attribute_value(exr, "dataWindow", "box2i");
  put_u32(empty_window, window + 8, static_cast<std::uint32_t>(-5));
  CHECK(refusal(empty_window).find("the dataWindow is empty") != std::string::npos);
  // A preview attribute declaring 65535 x 65535 pixels in 8 bytes: OpenEXR would allocate 16 GB.
  std::string preview = exr;
  const std::string software = std::string("Software\0string\0", 16);
  const size_t at = preview.find(software);
  REQUIRE(at != std::string::npos);
  std::string attribute = std::string("preview\0preview\0", 16);
  const std::uint32_t fields[3] = {8, 65535, 65535};
  attribute.append(reinterpret_cast<const char*>(fields), 12);
  preview.insert(at, attribute);
  CHECK(refusal(preview).find("the preview image declares 65535 x 65535 pixels, which its 8 bytes do not hold") !=
        std::string::npos);
}

TEST_CASE("a huge OpenEXR data window or tile is refused by the budget before decoding") {
  std::string exr = seed("float.exr");
  const size_t window = exr_attribute_value(exr, "dataWindow", "box2i");
  put_u32(exr, window + 8, 99999);
  put_u32(exr, window + 12, 99999);
  const ImageHeader header = read_image_header(exr);
  CHECK(header.width == 100000);
  CHECK(image_budget_problem(header, kDefaultMaxImagePixels) ==
        "the image is 100000 x 100000 pixels, more than the budget of 67108864 pixels (raise it with "
        "--max-image-pixels)");
  CHECK_THROWS_WITH_AS(decode_linear_image(exr, false, kDefaultMaxImagePixels),
                       doctest::Contains("100000 x 100000 pixels"), ImageError);
  std::string tiled = seed("tiled.exr");
  const size_t tiles = exr_attribute_value(tiled, "tiles", "tiledesc");
  put_u32(tiled, tiles, 1u << 20);
  put_u32(tiled, tiles + 4, 1u << 20);
  CHECK(image_budget_problem(read_image_header(tiled), kDefaultMaxImagePixels)
            .find("stored in tiles of 1048576 x 1048576 pixels") != std::string::npos);
  ImageHeader wide;
  wide.width = kMaxImageSide + 1;
  wide.height = 1;
  CHECK(image_budget_problem(wide, ~std::uint64_t{0}).find("which lamina never decodes") != std::string::npos);
}

TEST_CASE("TIFF, JPEG and Radiance headers that lie about their structure are refused with a reason") {
  std::string tiff = seed("float.tif");
  put_u32(tiff, 4, 1u << 30);  // little-endian: the first directory far beyond the end
  CHECK(refusal(tiff).find("the directory's entry count") != std::string::npos);
  std::string entries = seed("float.tif");
  std::uint32_t directory = 0;
  std::memcpy(&directory, entries.data() + 4, 4);
  entries[directory] = '\xff';
  entries[directory + 1] = '\xff';
  CHECK(refusal(entries).find("more entries than the file holds") != std::string::npos);

  const std::string jpeg = seed("rgb.jpg");
  CHECK(refusal("\xff\xd8\xff\xd9").find("the image data starts before any frame header") != std::string::npos);
  std::string no_height = jpeg;
  const size_t frame = no_height.find("\xff\xc0");
  REQUIRE(frame != std::string::npos);
  no_height[frame + 5] = 0;
  no_height[frame + 6] = 0;
  CHECK(refusal(no_height).find("DNL") != std::string::npos);

  CHECK(read_image_header("#?RADIANCE\n\n+X 5 -Y 3\n").width == 5);
  CHECK(read_image_header("#?RADIANCE\n\n+X 5 -Y 3\n").height == 3);
  CHECK(refusal("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n").find("does not end with an empty line") != std::string::npos);
  CHECK(refusal("#?RADIANCE\n\n-Y 3 -Y 3\n").find("names the same axis twice") != std::string::npos);
  CHECK(refusal("#?RADIANCE\n\n-Y 12345678901 +X 3\n").find("more than 10 digits") != std::string::npos);
}

TEST_CASE("a tiled image decodes to the same texels as the same image stored by rows") {
  for (const std::string& extension : {std::string("exr"), std::string("tif")}) {
    CAPTURE(extension);
    // 37 x 23 with 16 x 16 tiles: the last row and column of tiles stick out of the image.
    const auto rows =
        decode_linear_image(made_by_oiiotool("37x23 4 -d half", extension), false, kDefaultMaxImagePixels);
    const auto tiles =
        decode_linear_image(made_by_oiiotool("37x23 4 -d half --tile 16 16", extension), false, kDefaultMaxImagePixels);
    REQUIRE(tiles->texels.size() == rows->texels.size());
    CHECK(tiles->texels == rows->texels);
    CHECK(tiles->texels.back().r > 0.9f);  // the bottom row is the fill's bottom colour
  }
}

TEST_CASE("a PNG chunk that declares more bytes than the file holds is refused before libpng allocates it") {
  // A fuzzer found libpng allocating a chunk's declared 2 GB in png_read_info.
  std::string png = seed("rgb.png");
  const size_t idat = png.find("IDAT");
  REQUIRE(idat != std::string::npos);
  const std::string text = std::string("\x7f\x00\x00\x64tEXt", 8) + "comment";
  png.insert(idat - 4, text);
  CHECK(refusal(png).find("the file is truncated: chunk 'tEXt' at byte") != std::string::npos);
  CHECK(refusal(png).find("declares 2130706532 bytes, beyond the end of the") != std::string::npos);
  const std::string cut = refusal(seed("rgb.png").substr(0, 60));
  CHECK(cut.find("not a valid PNG image: the file is truncated") == 0);
}

TEST_CASE("a stored pixel holds at most the 4 channels of 32 bits a decoded texel has") {
  // A decoder's buffers hold every channel of the file: a 64-channel EXR would make them 16 times
  // the texels. The message says how to keep the channels a texture needs.
  const std::string five = made_by_oiiotool("4x4 5 -d half", "exr");
  CHECK(refusal(five).find("the image has 5 channels; lamina reads images of 1 to 4") == 0);
  CHECK(refusal(five).find("oiiotool --ch R,G,B,A") != std::string::npos);
  const std::string doubles = made_by_oiiotool("4x4 3 -d double", "tif");
  CHECK(refusal(doubles).find("the image has samples of 64 bits; lamina reads samples of at most 32") == 0);
  CHECK(read_image_header(made_by_oiiotool("4x4 4 -d float", "exr")).channels == 4);
}

TEST_CASE("a TIFF strip or an OpenEXR block of rows larger than the budget is refused before it is allocated") {
  // A fuzzer found OpenImageIO allocating RowsPerStrip rows (385,876,256 of them: 20 TB) for a
  // strip of a 10-row TIFF.
  std::string tiff = seed("float.tif");
  set_tiff_tag(tiff, 278, 385876256u);  // RowsPerStrip
  const ImageHeader header = read_image_header(tiff);
  CHECK(header.chunk_height == 385876256u);
  CHECK(image_budget_problem(header, kDefaultMaxImagePixels).find("stored in blocks of rows of 2 x 385876256") !=
        std::string::npos);
  // The usual strip heights pass: OpenImageIO writes 32-row strips even for a 2-row image.
  CHECK(image_budget_problem(read_image_header(seed("float.tif")), kDefaultMaxImagePixels).empty());
  // A DWAB-compressed OpenEXR (compression 9) decodes 256 rows at a time, however few it has.
  std::string exr = seed("float.exr");
  exr[exr_attribute_value(exr, "compression", "compression")] = 9;
  CHECK(read_image_header(exr).chunk_height == 256);
  CHECK(image_budget_problem(read_image_header(exr), 1000).find("blocks of rows of 4 x 256") != std::string::npos);
}

TEST_CASE("decoding stops at the first damaged band of a TIFF instead of gathering an error per strip") {
  // A fuzzer found a 2-pixel-wide TIFF declaring 25,090 rows in 32-row strips, with one strip
  // stored: the decoder reported each of the 784 missing strips and went on, 44 s under ASan.
  std::string tiff = seed("float.tif");
  set_tiff_tag(tiff, 257, 25090u);  // ImageLength
  std::string message;
  try {
    decode_linear_image(tiff, false, kDefaultMaxImagePixels);
  } catch (const ImageError& e) {
    message = e.what();
  }
  CHECK(message.find("cannot decode the image") != std::string::npos);
  CHECK(message.find("strip 1") != std::string::npos);
  CHECK(message.find("strip 3") == std::string::npos);
}
