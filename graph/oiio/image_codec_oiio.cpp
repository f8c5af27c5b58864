// The image module: lamina's ImageCodec on OpenImageIO. Built as its own shared object
// (lamina_oiio) that liblamina loads on first use; see graph/image_codec.h.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>

#include "graph/image_codec.h"

namespace lamina {

namespace {

// OpenImageIO keeps errors per thread until they are retrieved; one left behind is printed when
// the program ends, so every failure takes it, and the caller gets one line.
std::string oiio_error(std::string why) {
  const std::string global = OIIO::geterror();
  if (why.empty()) why = global;
  while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
  for (char& c : why)
    if (c == '\n') c = ';';
  return why.empty() ? "OpenImageIO gave no reason" : why;
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

OIIO::ImageSpec float_spec(const FloatPixels& pixels) {
  return OIIO::ImageSpec(pixels.width, pixels.height, pixels.channels, OIIO::TypeDesc::FLOAT);
}

class OiioCodec final : public ImageCodec {
 public:
  std::string version() const override { return OIIO_VERSION_STRING; }

  std::string decode(const char* reader, std::string_view bytes, DecodeSink& sink) const override {
    auto input = OIIO::ImageInput::create(reader);
    if (!input) return "cannot start the decoder: " + oiio_error({});
    MemoryReader proxy(bytes);
    if (!input->set_ioproxy(&proxy)) return "cannot start the decoder: " + oiio_error(input->geterror());
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as texture/image outputs it
    OIIO::ImageSpec spec;
    // The name is never opened: the reader reads the proxy.
    if (!input->open("image", spec, config)) return "not a readable image: " + oiio_error(input->geterror());
    if (std::string why = sink.start(spec.width, spec.height, spec.depth, spec.nchannels); !why.empty()) {
      oiio_error(input->geterror());  // taken, so that nothing is printed at exit
      return why;
    }
    const int channels = std::min(spec.nchannels, 4);
    // A band of rows at a time: the only copy of the whole image is the caller's. A tiled image
    // is read a row of tiles at a time (OpenImageIO 2.4's read_scanlines divides by zero on tiled
    // files); bands of scanlines hold up to 64 rows and about a million pixels.
    const bool tiled = spec.tile_width > 0 && spec.tile_height > 0;
    const int band_rows = std::min(spec.height, tiled ? spec.tile_height : std::clamp((1 << 20) / spec.width, 1, 64));
    std::vector<float> band(static_cast<size_t>(spec.width) * static_cast<size_t>(band_rows) *
                            static_cast<size_t>(channels));
    for (int y = 0; y < spec.height; y += band_rows) {
      const int end = std::min(spec.height, y + band_rows);
      const bool read = tiled ? input->read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y, spec.y + end, spec.z,
                                                  spec.z + 1, 0, channels, OIIO::TypeDesc::FLOAT, band.data())
                              : input->read_scanlines(0, 0, spec.y + y, spec.y + end, spec.z, 0, channels,
                                                      OIIO::TypeDesc::FLOAT, band.data());
      // Some decoders (TIFF) report a damaged band and still return rows: stop at the first such
      // band, or a file that declares thousands of missing strips is decoded (and its errors
      // gathered) to the end.
      if (!read || input->has_error()) return "cannot decode the image: " + oiio_error(input->geterror());
      sink.rows(y, end, band.data());
    }
    input->close();
    return {};
  }

  bool writes(const std::string& format) const override {
    const bool ok = OIIO::ImageOutput::create(format) != nullptr;
    if (!ok) oiio_error({});
    return ok;
  }

  std::string encode(const std::string& format, const FloatPixels& pixels,
                     const std::vector<std::pair<std::string, std::string>>& metadata,
                     std::vector<unsigned char>& encoded) const override {
    OIIO::Filesystem::IOVecOutput proxy(encoded);
    const std::string name = "image." + format;  // never opened: the writer writes the proxy
    auto output = OIIO::ImageOutput::create(name, &proxy);
    if (!output) return "no writer for ." + format + ": " + oiio_error({});
    OIIO::ImageSpec spec(pixels.width, pixels.height, pixels.channels, OIIO::TypeDesc::UINT8);
    for (const auto& [key, value] : metadata) spec.attribute(key, value);
    if (!output->open(name, spec) || !output->write_image(OIIO::TypeDesc::FLOAT, pixels.data) || !output->close())
      return oiio_error(output->geterror());
    return {};
  }

  std::string encode_linear(const std::string& format, const FloatPixels& pixels,
                            const std::vector<std::string>& channel_names,
                            const std::vector<std::pair<std::string, std::string>>& metadata,
                            std::vector<unsigned char>& encoded) const override {
    if (channel_names.size() != size_t(pixels.channels)) return "one channel name per channel is needed";
    OIIO::Filesystem::IOVecOutput proxy(encoded);
    const std::string name = "image." + format;
    auto output = OIIO::ImageOutput::create(name, &proxy);
    if (!output) return "no writer for ." + format + ": " + oiio_error({});
    if (!output->supports("ioproxy")) return "OpenImageIO's ." + format + " writer cannot write to memory";
    OIIO::ImageSpec spec(pixels.width, pixels.height, pixels.channels, OIIO::TypeDesc::HALF);
    spec.channelnames = channel_names;
    for (const auto& [key, value] : metadata) spec.attribute(key, value);
    if (!output->open(name, spec) || !output->write_image(OIIO::TypeDesc::FLOAT, pixels.data) || !output->close())
      return oiio_error(output->geterror());
    return {};
  }

  std::optional<TextBox> text_box(const std::string& text, int size, const std::string& font) const override {
    const OIIO::ROI roi = OIIO::ImageBufAlgo::text_size(text, size, font);
    if (!roi.defined()) {
      oiio_error({});
      return std::nullopt;
    }
    return TextBox{roi.xbegin, roi.ybegin, roi.xend, roi.yend};
  }

  std::string draw_text(const FloatPixels& pixels, int x, int y, const std::string& text, int size,
                        const std::string& font, const float* colour, int align) const override {
    OIIO::ImageBuf image(float_spec(pixels), pixels.data);  // draws in place
    const auto align_x = align < 0    ? OIIO::ImageBufAlgo::TextAlignX::Left
                         : align == 0 ? OIIO::ImageBufAlgo::TextAlignX::Center
                                      : OIIO::ImageBufAlgo::TextAlignX::Right;
    if (!OIIO::ImageBufAlgo::render_text(image, x, y, text, size, font,
                                         OIIO::cspan<float>(colour, static_cast<size_t>(pixels.channels)), align_x,
                                         OIIO::ImageBufAlgo::TextAlignY::Baseline))
      return oiio_error(image.geterror());
    return {};
  }
};

// One thread for OpenImageIO's image operations and OpenEXR's decoding: lamina's images are small
// (labels, figures, textures read once), and a module loaded at run time would otherwise leave
// worker pools running for the rest of the program.
OiioCodec make_codec() {
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", -1);
  return OiioCodec();
}

}  // namespace

}  // namespace lamina

extern "C" __attribute__((visibility("default"))) const lamina::ImageCodec* lamina_image_codec() {
  static const lamina::OiioCodec codec = lamina::make_codec();
  return &codec;
}
