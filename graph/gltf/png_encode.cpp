#include "graph/gltf/png_encode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <stdexcept>
#include <string>

namespace lamina::gltf {

std::vector<unsigned char> encode_png(int width, int height, int channels, std::span<const uint8_t> pixels) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      pixels.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels))
    throw std::invalid_argument("encode_png: pixel count does not match the image size");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto output = OIIO::ImageOutput::create("image.png", &proxy);
  if (!output) throw std::runtime_error("cannot create a PNG writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  if (!output->open("image.png", spec) || !output->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
      !output->close())
    throw std::runtime_error("cannot encode a PNG image: " + output->geterror());
  return bytes;
}

}  // namespace lamina::gltf
