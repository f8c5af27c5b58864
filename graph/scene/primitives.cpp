#include "graph/scene/primitives.h"

#include <algorithm>
#include <numbers>

namespace lamina {

namespace {

// A (columns + 1) x (rows + 1) vertex grid over uv, filled by `vertex(u, v, position, normal,
// tangent)`; two triangles per cell, CCW seen from the normal's side.
template <class Vertex>
TriangleMesh uv_grid(int columns, int rows, Vertex vertex, bool collapsed_poles) {
  TriangleMesh mesh;
  for (int i = 0; i <= rows; ++i) {
    for (int j = 0; j <= columns; ++j) {
      float u = static_cast<float>(j) / static_cast<float>(columns);
      float v = static_cast<float>(i) / static_cast<float>(rows);
      // At a pole every column meets in one point, the apex of one triangle per cell: its u is
      // the cell's middle so that the pole triangles' uv stay symmetric.
      if (collapsed_poles && i == 0 && j < columns) u += 0.5f / static_cast<float>(columns);
      if (collapsed_poles && i == rows && j > 0) u -= 0.5f / static_cast<float>(columns);
      glm::dvec3 p, n, t;
      vertex(static_cast<double>(u), static_cast<double>(v), p, n, t);
      mesh.positions.emplace_back(p);
      mesh.normals.emplace_back(n);
      mesh.tangents.emplace_back(glm::vec3(t), 1.0f);
      mesh.uvs.emplace_back(u, v);
    }
  }
  auto index = [&](int i, int j) { return static_cast<uint32_t>(i * (columns + 1) + j); };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      // v grows along the first edge, u along the second: cross(dP/dv, dP/du) is outward.
      if (!(collapsed_poles && i == rows - 1))
        mesh.indices.insert(mesh.indices.end(), {index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      if (!(collapsed_poles && i == 0))
        mesh.indices.insert(mesh.indices.end(), {index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  return mesh;
}

void append(TriangleMesh& to, const TriangleMesh& from) {
  auto base = static_cast<uint32_t>(to.positions.size());
  to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
  to.normals.insert(to.normals.end(), from.normals.begin(), from.normals.end());
  to.tangents.insert(to.tangents.end(), from.tangents.begin(), from.tangents.end());
  to.uvs.insert(to.uvs.end(), from.uvs.begin(), from.uvs.end());
  for (uint32_t i : from.indices) to.indices.push_back(base + i);
}

// One flat rectangle centred on `centre` with normal n = cross(down, right): u runs along
// `right` (half-extent `half_u`), v along `down` (half-extent `half_v`).
TriangleMesh quad(glm::dvec3 centre, glm::dvec3 right, glm::dvec3 down, double half_u, double half_v) {
  glm::dvec3 normal = glm::cross(down, right);
  return uv_grid(
      1, 1,
      [&](double u, double v, glm::dvec3& p, glm::dvec3& n, glm::dvec3& t) {
        p = centre + (2.0 * u - 1.0) * half_u * right + (2.0 * v - 1.0) * half_v * down;
        n = normal;
        t = right;
      },
      false);
}

}  // namespace

int sphere_rings(int segments) { return std::max(2, segments / 2); }
int torus_rings(int segments) { return std::max(4, segments / 2); }

size_t shape_vertices(const SceneObject& object) {
  // uv_grid: (columns + 1) x (rows + 1); quad: 4 per face.
  auto grid = [](int columns, int rows) { return size_t(columns + 1) * size_t(rows + 1); };
  switch (object.shape) {
    case ShapeType::Sphere: return grid(object.segments, sphere_rings(object.segments));
    case ShapeType::Torus: return grid(object.segments, torus_rings(object.segments));
    case ShapeType::Plane: return 4;
    case ShapeType::Box: return 24;
    case ShapeType::Mesh: return 0;
  }
  return 0;
}

TriangleMesh sphere_mesh(double radius, int segments) {
  const double pi = std::numbers::pi;
  return uv_grid(
      segments, sphere_rings(segments),
      [&](double u, double v, glm::dvec3& p, glm::dvec3& n, glm::dvec3& t) {
        double phi = 2.0 * pi * u, theta = pi * v;
        n = glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
        p = radius * n;
        // The direction of dP/dphi, which is defined at the poles too.
        t = glm::dvec3(std::cos(phi), 0.0, -std::sin(phi));
      },
      true);
}

TriangleMesh plane_mesh(glm::dvec2 size) {
  return quad(glm::dvec3(0.0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), size.x / 2.0, size.y / 2.0);
}

TriangleMesh box_mesh(glm::dvec3 size) {
  glm::dvec3 h = size / 2.0;
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  // Side faces keep the image upright (v down = -y); top and bottom run u along +x.
  TriangleMesh mesh;
  append(mesh, quad(h.z * z, x, -y, h.x, h.y));    // +z
  append(mesh, quad(-h.z * z, -x, -y, h.x, h.y));  // -z
  append(mesh, quad(h.x * x, -z, -y, h.z, h.y));   // +x
  append(mesh, quad(-h.x * x, z, -y, h.z, h.y));   // -x
  append(mesh, quad(h.y * y, x, z, h.x, h.z));     // +y
  append(mesh, quad(-h.y * y, x, -z, h.x, h.z));   // -y
  return mesh;
}

TriangleMesh torus_mesh(double major_radius, double minor_radius, int segments) {
  const double pi = std::numbers::pi;
  return uv_grid(
      segments, torus_rings(segments),
      [&](double u, double v, glm::dvec3& p, glm::dvec3& n, glm::dvec3& t) {
        double phi = 2.0 * pi * u, psi = 2.0 * pi * v;
        // psi = 0 is the outer equator; the tube is walked downwards there so that v runs down.
        glm::dvec3 radial(std::sin(phi), 0.0, std::cos(phi));
        n = std::cos(psi) * radial - std::sin(psi) * glm::dvec3(0, 1, 0);
        p = major_radius * radial + minor_radius * n;
        t = glm::dvec3(std::cos(phi), 0.0, -std::sin(phi));
      },
      false);
}

}  // namespace lamina
