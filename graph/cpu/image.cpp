#include "graph/cpu/image.h"

#include <OpenImageIO/imageio.h>

#include <cmath>

#include "graph/json_read.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

std::shared_ptr<const LinearImage> load_linear_image(const std::filesystem::path& path, bool srgb) {
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) throw IoError(path.string() + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  int channels = spec.nchannels;
  std::vector<float> pixels(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) *
                            static_cast<size_t>(channels));
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw IoError(path.string() + ": cannot read image: " + input->geterror());
  input->close();

  auto image = std::make_shared<LinearImage>();
  image->width = spec.width;
  image->height = spec.height;
  image->texels.resize(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height));
  for (size_t i = 0; i < image->texels.size(); ++i) {
    const float* p = &pixels[i * static_cast<size_t>(channels)];
    glm::vec3 rgb = channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
    float alpha = channels == 2 ? p[1] : channels >= 4 ? p[3] : 1.0f;
    if (srgb) rgb = kernels::srgb_to_linear(rgb);
    image->texels[i] = glm::vec4(rgb, alpha);
  }
  return image;
}

namespace {

int wrap_index(int i, int size, Wrap wrap) {
  switch (wrap) {
    case Wrap::Clamp: return std::clamp(i, 0, size - 1);
    case Wrap::Mirror: {
      int period = 2 * size;
      int j = ((i % period) + period) % period;
      return j < size ? j : period - 1 - j;
    }
    case Wrap::Repeat:
    default: return ((i % size) + size) % size;
  }
}

}  // namespace

glm::vec4 sample_bilinear(const LinearImage& image, glm::vec2 uv, Wrap wrap) {
  if (image.width <= 0 || image.height <= 0) return glm::vec4(0.0f);
  float x = uv.x * float(image.width) - 0.5f;
  float y = uv.y * float(image.height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return glm::vec4(0.0f);
  // Keep the integer part representable; repeat and mirror are periodic anyway.
  x = std::clamp(x, -1.0e6f, 1.0e6f);
  y = std::clamp(y, -1.0e6f, 1.0e6f);
  float fx = std::floor(x), fy = std::floor(y);
  float tx = x - fx, ty = y - fy;
  int x0 = int(fx), y0 = int(fy);
  auto texel = [&](int i, int j) {
    int xi = wrap_index(i, image.width, wrap);
    int yj = wrap_index(j, image.height, wrap);
    return image.texels[static_cast<size_t>(yj) * static_cast<size_t>(image.width) + static_cast<size_t>(xi)];
  };
  glm::vec4 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), tx);
  glm::vec4 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), tx);
  return glm::mix(top, bottom, ty);
}

}  // namespace lamina
