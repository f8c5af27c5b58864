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
