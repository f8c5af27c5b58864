#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "graph/scene/primitives.h"

using namespace lamina;

namespace {

constexpr double kPi = std::numbers::pi;

double area(const TriangleMesh& m) {
  double sum = 0.0;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
    sum += glm::length(glm::cross(b - a, c - a)) / 2.0;
  }
  return sum;
}

// Per vertex: unit normal, unit tangent orthogonal to it, w = +1 (no primitive is mirrored).
void check_frames(const TriangleMesh& m) {
  REQUIRE(m.normals.size() == m.positions.size());
  REQUIRE(m.tangents.size() == m.positions.size());
  REQUIRE(m.uvs.size() == m.positions.size());
  REQUIRE(m.indices.size() % 3 == 0);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    CAPTURE(i);
    glm::dvec3 n(m.normals[i]), t(m.tangents[i]);
    CHECK(glm::length(n) == doctest::Approx(1.0).epsilon(1e-6).scale(0.0));
    CHECK(glm::length(t) == doctest::Approx(1.0).epsilon(1e-6).scale(0.0));
    CHECK(std::abs(glm::dot(n, t)) < 1e-6);
    CHECK(m.tangents[i].w == 1.0f);
    CHECK(m.uvs[i].x >= 0.0f);
    CHECK(m.uvs[i].x <= 1.0f);
    CHECK(m.uvs[i].y >= 0.0f);
    CHECK(m.uvs[i].y <= 1.0f);
  }
}

// Per triangle, finite differences of position against uv: dP/du and dP/dv solved from two edges.
// The vertex tangents must point along dP/du, the bitangent cross(n, t) * w against dP/dv (v
// grows downwards in the image), and the corners must run counter-clockwise around the normals.
void check_triangles(const TriangleMesh& m) {
  size_t checked = 0;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    CAPTURE(t / 3);
    uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
    glm::dvec3 e1(m.positions[b] - m.positions[a]), e2(m.positions[c] - m.positions[a]);
    glm::dvec2 d1(m.uvs[b] - m.uvs[a]), d2(m.uvs[c] - m.uvs[a]);
    double det = d1.x * d2.y - d2.x * d1.y;
    REQUIRE(std::abs(det) > 0.0);
    glm::dvec3 dpdu = glm::normalize((e1 * d2.y - e2 * d1.y) / det);
    glm::dvec3 dpdv = glm::normalize((e2 * d1.x - e1 * d2.x) / det);
    glm::dvec3 face = glm::cross(e1, e2);
    REQUIRE(glm::length(face) > 0.0);
    for (uint32_t v : {a, b, c}) {
      glm::dvec3 n(m.normals[v]), tangent(m.tangents[v]);
      CHECK(glm::dot(face, n) > 0.0);
      CHECK(glm::dot(dpdu, tangent) > 0.9);
      CHECK(glm::dot(dpdv, glm::cross(n, tangent) * double(m.tangents[v].w)) < -0.9);
    }
    ++checked;
  }
  CHECK(checked > 0);
}

// Welds vertices by position; a closed, consistently wound mesh uses every directed edge once
// and its reverse once.
void check_closed(const TriangleMesh& m) {
  std::map<std::tuple<long, long, long>, size_t> ids;
  auto id = [&](uint32_t v) {
    glm::vec3 p = m.positions[v];
    auto key = std::make_tuple(std::lround(p.x * 1e4), std::lround(p.y * 1e4), std::lround(p.z * 1e4));
    return ids.emplace(key, ids.size()).first->second;
  };
  std::map<std::pair<size_t, size_t>, int> edges;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++edges[{id(m.indices[t + k]), id(m.indices[t + (k + 1) % 3])}];
  size_t bad = 0;
  for (const auto& [edge, count] : edges) {
    auto reverse = edges.find({edge.second, edge.first});
    if (count != 1 || reverse == edges.end() || reverse->second != 1) ++bad;
  }
  CHECK(bad == 0);
}

}  // namespace

TEST_CASE("the sphere: outward unit normals, tangents along +u, closed, area near 4 pi r^2") {
  TriangleMesh m = sphere_mesh(1.5, 48);
  check_frames(m);
  check_triangles(m);
  check_closed(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    glm::dvec3 p(m.positions[i]);
    CHECK(glm::length(p) == doctest::Approx(1.5).epsilon(1e-6).scale(0.0));
    CHECK(glm::dot(glm::dvec3(m.normals[i]), p / 1.5) == doctest::Approx(1.0).epsilon(1e-6).scale(0.0));
  }
  // The 48 x 24 polyhedron's area, summed by an independent python script: 28.17351568746817,
  // 0.36 % under the sphere's 4 pi r^2 = 28.2743.
  CHECK(area(m) == doctest::Approx(28.17351568746817).epsilon(1e-5).scale(0.0));
  CHECK(area(m) == doctest::Approx(4.0 * kPi * 1.5 * 1.5).epsilon(0.005).scale(0.0));
  // (0, 0) is the top-left: v = 0 at the north pole, u = 0 on +z going towards +x.
  CHECK(m.positions[0].y == doctest::Approx(1.5));
  CHECK(m.positions.back().y == doctest::Approx(-1.5));
}

TEST_CASE("the plane faces +y with u along +x and v along +z") {
  TriangleMesh m = plane_mesh(glm::dvec2(3.0, 2.0));
  check_frames(m);
  check_triangles(m);
  CHECK(area(m) == doctest::Approx(6.0));
  for (size_t i = 0; i < m.positions.size(); ++i) {
    CHECK(m.normals[i] == glm::vec3(0, 1, 0));
    CHECK(m.positions[i].x == doctest::Approx((m.uvs[i].x - 0.5) * 3.0));
    CHECK(m.positions[i].z == doctest::Approx((m.uvs[i].y - 0.5) * 2.0));
  }
}

TEST_CASE("the box: six faces each with its own 0..1 uv, closed, area 2(xy + yz + zx)") {
  TriangleMesh m = box_mesh(glm::dvec3(1.0, 2.0, 3.0));
  check_frames(m);
  check_triangles(m);
  check_closed(m);
  CHECK(m.indices.size() == 36);
  CHECK(area(m) == doctest::Approx(2.0 * (1.0 * 2.0 + 2.0 * 3.0 + 3.0 * 1.0)));
  std::map<std::tuple<int, int, int>, int> faces;
  for (const auto& n : m.normals) ++faces[{int(std::lround(n.x)), int(std::lround(n.y)), int(std::lround(n.z))}];
  CHECK(faces.size() == 6);
  for (const auto& [normal, count] : faces) CHECK(count == 4);
}

TEST_CASE("the torus: around y, closed, area near 4 pi^2 R r") {
  TriangleMesh m = torus_mesh(1.0, 0.3, 64);
  check_frames(m);
  check_triangles(m);
  check_closed(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    glm::dvec3 p(m.positions[i]);
    glm::dvec3 ring = glm::normalize(glm::dvec3(p.x, 0.0, p.z));  // the tube's centre line
    CHECK(glm::length(p - ring) == doctest::Approx(0.3).epsilon(1e-5).scale(0.0));
    CHECK(glm::dot(glm::dvec3(m.normals[i]), (p - ring) / 0.3) == doctest::Approx(1.0).epsilon(1e-5).scale(0.0));
  }
  // The 64 x 32 polyhedron's area by the same python script: 11.812643502719828.
  CHECK(area(m) == doctest::Approx(11.812643502719828).epsilon(1e-5).scale(0.0));
  CHECK(area(m) == doctest::Approx(4.0 * kPi * kPi * 1.0 * 0.3).epsilon(0.005).scale(0.0));
}
