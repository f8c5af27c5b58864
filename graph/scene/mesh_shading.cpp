#include "graph/scene/mesh_shading.h"

#include <cmath>

namespace lamina {

namespace {

// A unit vector orthogonal to the unit vector n: the first basis vector of Duff et al., "Building
// an Orthonormal Basis, Revisited", JCGT 6(1), 2017, listing 3.
glm::vec3 any_orthogonal(glm::vec3 n) {
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float b = n.x * n.y * a;
  return glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

}  // namespace

void generate_normals(TriangleMesh& mesh) {
  std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    // The cross product's length is twice the area: larger triangles weigh more.
    glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    sum[a] += n;
    sum[b] += n;
    sum[c] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t i = 0; i < sum.size(); ++i) {
    float length = glm::length(sum[i]);
    mesh.normals[i] = length > 0.0f ? sum[i] / length : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

void generate_tangents(TriangleMesh& mesh) {
  std::vector<glm::dvec3> du_sum(mesh.positions.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> dv_sum(mesh.positions.size(), glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    glm::dvec3 e1 = glm::dvec3(mesh.positions[b] - mesh.positions[a]);
    glm::dvec3 e2 = glm::dvec3(mesh.positions[c] - mesh.positions[a]);
    glm::dvec2 d1 = glm::dvec2(mesh.uvs[b] - mesh.uvs[a]);
    glm::dvec2 d2 = glm::dvec2(mesh.uvs[c] - mesh.uvs[a]);
    // e = dP/du * du + dP/dv * dv for both edges, solved for dP/du and dP/dv (Lengyel,
    // "Mathematics for 3D Game Programming and Computer Graphics", sec. 7.8); each triangle's
    // directions count with its area, so slivers do not dominate a vertex.
    double det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < kLeastUvDeterminant) continue;
    glm::dvec3 dpdu = (e1 * d2.y - e2 * d1.y) / det;
    glm::dvec3 dpdv = (e2 * d1.x - e1 * d2.x) / det;
    double area = glm::length(glm::cross(e1, e2));
    glm::dvec3 wu = glm::length(dpdu) > 0.0 ? glm::normalize(dpdu) * area : glm::dvec3(0.0);
    glm::dvec3 wv = glm::length(dpdv) > 0.0 ? glm::normalize(dpdv) * area : glm::dvec3(0.0);
    for (uint32_t i : {a, b, c}) {
      du_sum[i] += wu;
      dv_sum[i] += wv;
    }
  }
  mesh.tangents.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    glm::dvec3 n = glm::dvec3(mesh.normals[i]);
    glm::dvec3 t = du_sum[i] - n * glm::dot(n, du_sum[i]);  // Gram-Schmidt against the normal
    if (glm::length(t) < 1e-12) {
      mesh.tangents[i] = glm::vec4(any_orthogonal(mesh.normals[i]), 1.0f);
      continue;
    }
    t = glm::normalize(t);
    // The bitangent cross(n, t) * w must point towards decreasing v.
    float w = glm::dot(glm::cross(n, t), dv_sum[i]) > 0.0 ? -1.0f : 1.0f;
    mesh.tangents[i] = glm::vec4(glm::vec3(t), w);
  }
}

}  // namespace lamina
