#include "graph/cpu/frame.h"

#include <cmath>

namespace lamina {

Frame Frame::from_normal_tangent(glm::vec3 normal, glm::vec3 tangent) {
  Frame f;
  f.normal = glm::normalize(normal);
  glm::vec3 t = tangent - f.normal * glm::dot(f.normal, tangent);
  if (glm::dot(t, t) > 1.0e-12f) {
    f.tangent = glm::normalize(t);
  } else {
    float sign = std::copysign(1.0f, f.normal.z);
    float a = -1.0f / (sign + f.normal.z);
    float b = f.normal.x * f.normal.y * a;
    f.tangent = glm::vec3(1.0f + sign * f.normal.x * f.normal.x * a, sign * b, -sign * f.normal.x);
  }
  f.bitangent = glm::cross(f.normal, f.tangent);
  return f;
}

}  // namespace lamina
