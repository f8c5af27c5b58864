#include <doctest/doctest.h>

#include "graph/json_read.h"
#include "graph/scene/mesh_file.h"
#include "test_support.h"

using namespace lamina;

namespace {

std::filesystem::path data(const char* name) { return test::source_dir() / "tests/data/scenes" / name; }

}  // namespace

TEST_CASE("a glTF quad without normals loads with its node transform, generated normals and tangents") {
  // quad.gltf: corners (+-0.5, +-0.5, 0) with uv (0, 0) at the top-left, CCW towards +z; its node
  // scales by 2 and moves by +1 along x.
  TriangleMesh m = load_mesh_file(data("quad.gltf"));
  REQUIRE(m.positions.size() == 4);
  REQUIRE(m.indices.size() == 6);
  CHECK(m.positions[0] == glm::vec3(0, -1, 0));
  CHECK(m.positions[2] == glm::vec3(2, 1, 0));
  CHECK(m.uvs[0] == glm::vec2(0, 1));
  for (size_t i = 0; i < 4; ++i) {
    CHECK(m.normals[i].z == doctest::Approx(1.0));
    CHECK(m.tangents[i].x == doctest::Approx(1.0));  // u grows along +x
    CHECK(m.tangents[i].w == 1.0f);                  // cross(n, t) = +y, up in the image
  }
  glm::vec3 face = glm::cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                              m.positions[m.indices[2]] - m.positions[m.indices[0]]);
  CHECK(face.z > 0.0f);
}

TEST_CASE("a mirroring node transform keeps triangles counter-clockwise and flips the tangent sign") {
  // quad_mirrored.gltf: the same quad under scale (-1, 1, 1).
  TriangleMesh m = load_mesh_file(data("quad_mirrored.gltf"));
  REQUIRE(m.positions.size() == 4);
  CHECK(m.positions[0] == glm::vec3(0.5, -0.5, 0));
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    glm::vec3 face = glm::cross(m.positions[m.indices[t + 1]] - m.positions[m.indices[t]],
                                m.positions[m.indices[t + 2]] - m.positions[m.indices[t]]);
    CHECK(face.z > 0.0f);
  }
  for (size_t i = 0; i < 4; ++i) {
    CHECK(m.normals[i].z == doctest::Approx(1.0));
    CHECK(m.tangents[i].x == doctest::Approx(-1.0));  // u now grows along -x
    CHECK(m.tangents[i].w == -1.0f);                  // the image is mirrored
  }
}

TEST_CASE("a glTF file without triangles or that does not exist throws IoError naming the file") {
  CHECK_THROWS_WITH_AS(load_mesh_file(data("points.gltf")), doctest::Contains("points.gltf: holds no triangles"),
                       IoError);
  CHECK_THROWS_AS(load_mesh_file(data("no_such.gltf")), IoError);
  CHECK_THROWS_WITH_AS(load_mesh_file(test::source_dir() / "tests/data/bad_scenes/cases.json"),
                       doctest::Contains("cannot read glTF"), IoError);
}
