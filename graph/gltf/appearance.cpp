#include "graph/gltf/appearance.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "nodes/kernels/kernels.h"

namespace lamina::gltf {

namespace k = kernels;

namespace {

// CIE 15 (2004) eq. 8.11's f(t): the cube root, with a line near 0.
double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

// Cosines at which the directional albedo is tabulated for the sky term, evenly from 0 to 1.
constexpr int kAlbedoNodes = 17;

}  // namespace

glm::vec3 lab_from_linear_srgb(glm::vec3 rgb) {
  const double r = rgb.x, g = rgb.y, b = rgb.z;
  // IEC 61966-2-1: linear sRGB to XYZ; its white (1, 1, 1) is D65 at Y = 1.
  const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
  const double fx = lab_f(x / 0.95047), fy = lab_f(y), fz = lab_f(z / 1.08883);
  return {float(116.0 * fy - 16.0), float(500.0 * (fx - fy)), float(200.0 * (fy - fz))};
}

float chromatic_difference(glm::vec3 lab_a, glm::vec3 lab_b) {
  return float(std::hypot(double(lab_a.y) - double(lab_b.y), double(lab_a.z) - double(lab_b.z)));
}

glm::vec3 sphere_colour(const FitTarget& material, int resolution) {
  std::vector<glm::vec3> albedo(kAlbedoNodes);
  for (int i = 0; i < kAlbedoNodes; ++i) {
    const float c = std::max(float(i) / float(kAlbedoNodes - 1), 0.01f);
    albedo[size_t(i)] = material.albedo(glm::vec3(std::sqrt(1.0f - c * c), 0.0f, c));
  }
  const glm::vec3 sky(k::LAMINA_PREVIEW_AMBIENT);
  glm::dvec3 sum(0.0);
  long points = 0;
  for (int row = 0; row < resolution; ++row)
    for (int col = 0; col < resolution; ++col) {
      const glm::vec2 q =
          k::lamina_preview_disk(glm::vec2(float(col) + 0.5f, float(row) + 0.5f), glm::vec2(float(resolution)));
      if (!k::lamina_preview_on_sphere(q)) continue;
      const glm::vec3 n = k::lamina_preview_normal(q);
      const glm::vec3 wo = k::lamina_preview_local(k::LAMINA_PREVIEW_VIEW, n);
      const glm::vec3 wi = k::lamina_preview_local(k::LAMINA_PREVIEW_LIGHT, n);
      glm::vec3 radiance(0.0f);
      if (wi.z > 0.0f && wo.z > 0.0f) radiance = k::lamina_preview_light(material.eval(wi, wo), wi);
      const float t = std::clamp(wo.z, 0.0f, 1.0f) * float(kAlbedoNodes - 1);
      const int i = std::min(int(t), kAlbedoNodes - 2);
      radiance += sky * glm::mix(albedo[size_t(i)], albedo[size_t(i) + 1], t - float(i));
      sum += glm::dvec3(k::lamina_preview_display(radiance));
      ++points;
    }
  return points > 0 ? glm::vec3(sum / double(points)) : glm::vec3(0.0f);
}

}  // namespace lamina::gltf
