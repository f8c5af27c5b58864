// The local shading frame: z along the normal, x along the tangent. wi and wo point away from the
// surface; the evaluators work in this frame, where cos_theta(w) = w.z.
#pragma once

#include <glm/glm.hpp>

namespace lamina {

struct Frame {
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};
  glm::vec3 bitangent{0.0f, 1.0f, 0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};

  // The frame of a surface with world-space `normal` and `tangent` (neither need be unit length):
  // the tangent orthonormalised against the normal (Gram-Schmidt), bitangent = normal x tangent
  // (right-handed). When the tangent is missing or within about 1e-6 rad of the normal, picks one
  // (Duff et al. 2017, "Building an orthonormal basis, revisited").
  static Frame from_normal_tangent(glm::vec3 normal, glm::vec3 tangent);

  glm::vec3 to_local(glm::vec3 w) const { return {glm::dot(w, tangent), glm::dot(w, bitangent), glm::dot(w, normal)}; }
  glm::vec3 to_world(glm::vec3 w) const { return w.x * tangent + w.y * bitangent + w.z * normal; }
};

// The local direction theta degrees from the normal in the plane of incidence (x, z):
// (sin theta, 0, cos theta); negative angles lie on the -x side. The views of `lamina albedo`,
// `plot` and `compare`, and their slices' lights.
glm::vec3 direction_in_plane(double theta_deg);

}  // namespace lamina
