#include "tools/render/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lamina::render {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The first index i in [0, n) with cdf[i + 1] > x, for a non-decreasing cdf of n + 1 values from 0
// to 1 (x in [0, 1)): that of a zero-width interval is never returned.
int find_interval(const float* cdf, int n, float x) {
  const float* end = cdf + n + 1;
  const float* it = std::upper_bound(cdf + 1, end, x);
  return std::clamp(int(it - cdf) - 1, 0, n - 1);
}

}  // namespace

glm::vec2 equirect_uv(glm::vec3 d) {
  float u = 0.5f + std::atan2(d.z, d.x) / (2.0f * kPi);
  float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  return {u - std::floor(u), v};
}

glm::vec3 equirect_direction(glm::vec2 uv) {
  const float phi = (uv.x - 0.5f) * 2.0f * kPi, theta = uv.y * kPi;
  const float s = std::sin(theta);
  return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

Environment::Environment(glm::vec3 radiance) : present_(true), uniform_(radiance) {}

Environment::Environment(std::shared_ptr<const LinearImage> image, glm::vec3 scale)
    : present_(true), image_(std::move(image)), scale_(scale) {
  const int w = image_->width, h = image_->height;
  texel_weight_.assign(size_t(w) * size_t(h), 0.0f);
  column_cdf_.assign(size_t(h) * size_t(w + 1), 0.0f);
  row_cdf_.assign(size_t(h) + 1, 0.0f);
  // Doubles for the sums: a 16k x 8k map adds 10^8 terms.
  std::vector<double> row_sum(size_t(h), 0.0);
  double total = 0.0;
  for (int y = 0; y < h; ++y) {
    const double sin_theta = std::sin((double(y) + 0.5) / double(h) * std::numbers::pi);
    double sum = 0.0;
    float* cdf = &column_cdf_[size_t(y) * size_t(w + 1)];
    std::vector<double> running(size_t(w) + 1, 0.0);
    for (int x = 0; x < w; ++x) {
      const glm::vec4 t = image_->texels[size_t(y) * size_t(w) + size_t(x)];
      const double weight = double(luminance(glm::vec3(t) * scale_)) * sin_theta;
      texel_weight_[size_t(y) * size_t(w) + size_t(x)] = float(weight);
      sum += weight;
      running[size_t(x) + 1] = sum;
    }
    for (int x = 0; x <= w; ++x) cdf[x] = sum > 0.0 ? float(running[size_t(x)] / sum) : float(x) / float(w);
    cdf[w] = 1.0f;
    row_sum[size_t(y)] = sum;
    total += sum;
  }
  double running = 0.0;
  for (int y = 0; y < h; ++y) {
    running += row_sum[size_t(y)];
    row_cdf_[size_t(y) + 1] = total > 0.0 ? float(running / total) : float(y + 1) / float(h);
  }
  row_cdf_[size_t(h)] = 1.0f;
  for (float& t : texel_weight_) t = total > 0.0 ? float(double(t) / total) : 0.0f;
  if (!(total > 0.0)) present_ = false;  // a black image lights nothing
}

int Environment::texel_index(glm::vec2 uv) const {
  const int x = std::clamp(int(uv.x * float(image_->width)), 0, image_->width - 1);
  const int y = std::clamp(int(uv.y * float(image_->height)), 0, image_->height - 1);
  return y * image_->width + x;
}

void Environment::set_rotation(float degrees) {
  const float a = degrees * kPi / 180.0f, c = std::cos(a), s = std::sin(a);
  // Columns: where x, y and z go.
  to_world_ = glm::mat3(glm::vec3(c, 0.0f, -s), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(s, 0.0f, c));
  to_image_ = glm::transpose(to_world_);
}

glm::vec3 Environment::radiance(glm::vec3 direction) const {
  if (!present_) return glm::vec3(0.0f);
  if (!image_) return uniform_;
  return image_radiance(to_image_ * direction);
}

float Environment::pdf(glm::vec3 direction) const {
  if (!present_) return 0.0f;
  if (!image_) return 1.0f / (4.0f * kPi);
  return image_pdf(to_image_ * direction);
}

glm::vec3 Environment::image_radiance(glm::vec3 local) const {
  return glm::vec3(image_->texels[size_t(texel_index(equirect_uv(local)))]) * scale_;
}

float Environment::image_pdf(glm::vec3 local) const {
  const glm::vec2 uv = equirect_uv(local);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - local.y * local.y));
  if (!(sin_theta > 0.0f)) return 0.0f;
  // dw = 2 pi^2 sin(theta) du dv, and a texel spans 1 / (width height) of the uv square.
  const float texels = float(image_->width) * float(image_->height);
  return texel_weight_[size_t(texel_index(uv))] * texels / (2.0f * kPi * kPi * sin_theta);
}

EnvironmentSample Environment::sample(glm::vec2 u) const {
  EnvironmentSample s;
  if (!present_) return s;
  if (!image_) {
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPi * u.y;
    s.wi = {r * std::cos(phi), r * std::sin(phi), z};
    s.radiance = uniform_;
    s.pdf = 1.0f / (4.0f * kPi);
    return s;
  }
  const int w = image_->width, h = image_->height;
  const int y = find_interval(row_cdf_.data(), h, u.y);
  // The row's share of u.y, stretched back to [0, 1), chooses the texel and then where in it.
  const float row_lo = row_cdf_[size_t(y)], row_hi = row_cdf_[size_t(y) + 1];
  const float in_row = std::clamp((u.y - row_lo) / std::max(row_hi - row_lo, 1e-30f), 0.0f, 0.99999994f);
  const float* cdf = &column_cdf_[size_t(y) * size_t(w + 1)];
  const int x = find_interval(cdf, w, u.x);
  const float in_texel = std::clamp((u.x - cdf[x]) / std::max(cdf[x + 1] - cdf[x], 1e-30f), 0.0f, 0.99999994f);
  const glm::vec2 uv((float(x) + in_texel) / float(w), (float(y) + in_row) / float(h));
  const glm::vec3 local = equirect_direction(uv);
  s.pdf = image_pdf(local);
  if (!(s.pdf > 0.0f)) return {};
  s.wi = to_world_ * local;
  s.radiance = image_radiance(local);
  return s;
}

glm::vec3 Environment::mean_radiance() const {
  if (!present_) return glm::vec3(0.0f);
  if (!image_) return uniform_;
  const int w = image_->width, h = image_->height;
  glm::dvec3 sum(0.0);
  for (int y = 0; y < h; ++y) {
    // The texel row's solid angle over the sphere's 4 pi: (cos theta0 - cos theta1) / 2 / width.
    const double share = (std::cos(double(y) / h * std::numbers::pi) - std::cos(double(y + 1) / h * std::numbers::pi)) /
                         (2.0 * double(w));
    for (int x = 0; x < w; ++x) sum += glm::dvec3(glm::vec3(image_->texels[size_t(y) * size_t(w) + size_t(x)])) * share;
  }
  return glm::vec3(sum) * scale_;
}

}  // namespace lamina::render
