#include "graph/cpu/frame.h"

#include <cmath>
#include <numbers>

namespace lamina {

Frame Frame::from_normal_tangent(glm::vec3 normal, glm::vec3 tangent) {
  Frame f;
  f.normal = glm::normalize(normal);
  // Gram-Schmidt, applied twice: for a tangent close to the normal one pass in float leaves t.n
  // off by about one ulp / sin(angle between them); a second pass brings it back to an ulp
  // (Kahan's "twice is enough", in Parlett, The Symmetric Eigenvalue Problem, 1980, sec. 6-9).
  glm::vec3 t = tangent - f.normal * glm::dot(f.normal, tangent);
  t -= f.normal * glm::dot(f.normal, t);
  // A tangent within about 1e-6 rad of the normal (or zero) gives no direction: pick one.
  if (glm::dot(t, t) > 1.0e-12f * glm::dot(tangent, tangent) && glm::dot(t, t) > 0.0f) {
    f.tangent = glm::normalize(t);
  } else {
    // Duff et al. 2017, "Building an orthonormal basis, revisited".
    float sign = std::copysign(1.0f, f.normal.z);
    float a = -1.0f / (sign + f.normal.z);
    float b = f.normal.x * f.normal.y * a;
    f.tangent = glm::vec3(1.0f + sign * f.normal.x * f.normal.x * a, sign * b, -sign * f.normal.x);
  }
  f.bitangent = glm::cross(f.normal, f.tangent);
  return f;
}

glm::vec3 direction_in_plane(double theta_deg) {
  const double t = theta_deg * std::numbers::pi / 180.0;
  return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

}  // namespace lamina
