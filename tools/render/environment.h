// The light that reaches a scene from infinitely far away: a uniform sky, or an equirectangular
// image importance-sampled by its luminance (a piecewise-constant density over the image's texels,
// weighted by the solid angle each covers, as pbrt's image infinite light samples its map).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "graph/cpu/image.h"

namespace lamina::render {

// Rec. 709 luminance, by which environment texels and emitters are chosen: positive weights, so it
// is 0 only where every channel is.
inline float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Where a world direction lands in an equirectangular image: u = 0.5 + atan2(z, x) / 2 pi (the
// image's centre column looks along +x, as three.js maps one), v = acos(y) / pi (row 0 is straight up,
// +y), and the inverse.
glm::vec2 equirect_uv(glm::vec3 direction);
glm::vec3 equirect_direction(glm::vec2 uv);

struct EnvironmentSample {
  glm::vec3 wi{0.0f};
  glm::vec3 radiance{0.0f};
  float pdf = 0.0f;  // solid-angle density; 0: nothing drawn
};

class Environment {
 public:
  // Nothing: the scene has no environment (black, never sampled).
  Environment() = default;
  // A uniform sky of `radiance`.
  explicit Environment(glm::vec3 radiance);
  // An image, scaled by `scale`, looked up without filtering (each texel is one constant patch,
  // which is what the sampling density assumes).
  Environment(std::shared_ptr<const LinearImage> image, glm::vec3 scale);

  // Turns the image about +y by `degrees` (right-handed: 90 moves what it shows along +x to -z).
  void set_rotation(float degrees);

  bool present() const { return present_; }
  glm::vec3 radiance(glm::vec3 direction) const;
  float pdf(glm::vec3 direction) const;
  // u: two uniform numbers.
  EnvironmentSample sample(glm::vec2 u) const;
  // The radiance averaged over the sphere (a white furnace's expected answer).
  glm::vec3 mean_radiance() const;

 private:
  int texel_index(glm::vec2 uv) const;
  // radiance and pdf of a direction in the image's own frame.
  glm::vec3 image_radiance(glm::vec3 local) const;
  float image_pdf(glm::vec3 local) const;

  bool present_ = false;
  glm::vec3 uniform_{0.0f};
  std::shared_ptr<const LinearImage> image_;
  glm::vec3 scale_{1.0f};
  glm::mat3 to_world_{1.0f};  // the rotation, and its inverse (the transpose)
  glm::mat3 to_image_{1.0f};
  // Texel selection: a cumulative distribution over rows, then over the texels of each row.
  std::vector<float> row_cdf_;       // height + 1
  std::vector<float> column_cdf_;    // height * (width + 1)
  std::vector<float> texel_weight_;  // width * height: the probability of each texel
};

}  // namespace lamina::render
