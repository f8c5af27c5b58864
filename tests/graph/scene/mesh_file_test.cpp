#include <doctest/doctest.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

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

TEST_CASE("a glTF file without triangles or that is no glTF is a lamina::Error, one that does not exist an IoError") {
  try {
    load_mesh_file(data("points.gltf"));
    FAIL("loaded");
  } catch (const Error& e) {
    CHECK(e.first().file == data("points.gltf").string());
    CHECK(e.first().pointer == "");
    CHECK(e.first().message == "holds no triangles");
  }
  CHECK_THROWS_AS(load_mesh_file(data("no_such.gltf")), IoError);
  CHECK_THROWS_WITH_AS(load_mesh_file(test::source_dir() / "tests/data/bad_scenes/cases.json"),
                       doctest::Contains("cases.json:: expected a glTF object, found an array"), Error);
}

namespace {

// The broken mesh files of the scene corpus whose problem is a value in the mesh file: each with
// the glTF pointer cases.json expects there.
struct MeshCase {
  std::filesystem::path file;
  std::string pointer, message;
};

std::vector<MeshCase> broken_mesh_cases() {
  const auto dir = test::source_dir() / "tests/data/bad_scenes";
  std::vector<MeshCase> out;
  for (const auto& c : nlohmann::json::parse(test::read_file(dir / "cases.json")))
    if (c.contains("in") && c["in"].get<std::string>().rfind("meshes/", 0) == 0)
      out.push_back({dir / c["in"].get<std::string>(), c["pointer"], c["message"]});
  return out;
}

// A glTF of one triangle primitive (POSITION only, zeros: no buffer view), with `nodes` and
// `scene_nodes` as given, written to `dir`/`name`.
std::filesystem::path write_gltf(const std::filesystem::path& dir, const std::string& name, size_t vertex_count,
                                 const nlohmann::json& nodes, const nlohmann::json& scene_nodes,
                                 nlohmann::json primitive = nlohmann::json::object()) {
  primitive["attributes"] = {{"POSITION", 0}};
  nlohmann::json g{
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", scene_nodes}}}},
      {"nodes", nodes},
      {"meshes", {{{"primitives", {primitive}}}}},
      {"accessors",
       {{{"componentType", 5126}, {"count", vertex_count}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {0, 0, 0}}}}}};
  const auto path = dir / name;
  std::ofstream(path) << g.dump();
  return path;
}

std::string pointer_of(const std::function<void()>& load) {
  try {
    load();
  } catch (const Error& e) {
    return e.first().pointer;
  }
  return "(no lamina::Error)";
}

}  // namespace

TEST_CASE("every broken mesh file of the corpus throws lamina::Error at its glTF pointer, never another exception") {
  const auto cases = broken_mesh_cases();
  CHECK(cases.size() >= 14);
  for (const auto& c : cases) {
    CAPTURE(c.file);
    try {
      load_mesh_file(c.file);
      FAIL("loaded");
    } catch (const Error& e) {
      REQUIRE(e.diagnostics().size() == 1);
      CHECK(e.first().file == c.file.string());
      CHECK(e.first().pointer == c.pointer);
      CHECK((e.first().message + " " + e.first().hint).find(c.message) != std::string::npos);
    }
  }
}

TEST_CASE("a node hierarchy thousands of levels deep loads: the walk is not recursive") {
  // 5000 nested nodes, each moving its child by 0.001 along x: the quad ends 5 units along.
  test::TempDir dir;
  auto g = nlohmann::json::parse(test::read_file(data("quad.gltf")));
  nlohmann::json nodes = nlohmann::json::array();
  for (int i = 0; i < 5000; ++i) {
    nlohmann::json node{{"translation", {0.001, 0, 0}}};
    if (i + 1 < 5000)
      node["children"] = {i + 1};
    else
      node["mesh"] = 0;
    nodes.push_back(node);
  }
  g["nodes"] = nodes;
  std::ofstream(dir.path() / "deep.gltf") << g.dump();
  TriangleMesh m = load_mesh_file(dir.path() / "deep.gltf");
  REQUIRE(m.positions.size() == 4);
  CHECK(m.positions[0].x == doctest::Approx(5.0 - 0.5).epsilon(1e-9).scale(0.0));  // corner (-0.5, -0.5, 0)
  CHECK(m.positions[2].x == doctest::Approx(5.0 + 0.5).epsilon(1e-9).scale(0.0));
}

TEST_CASE("glTF nodes must form strict trees: a root that is also a child is reported where it is reached again") {
  test::TempDir dir;
  auto path = write_gltf(dir.path(), "twice.gltf", 3, {{{"children", {1}}}, {{"mesh", 0}}}, {0, 1});
  try {
    load_mesh_file(path);
    FAIL("loaded");
  } catch (const Error& e) {
    CHECK(e.first().pointer == "/scenes/0/nodes/1");
    CHECK(e.first().message.find("node 1 is reached a second time (it is already a child of node 0)") !=
          std::string::npos);
  }
}

TEST_CASE("the limits on vertices, triangles and primitive instances hold over every instance of a mesh") {
  test::TempDir dir;
  // Two instances of 2,200,000 vertices: each alone is within 4,194,304, together they are not;
  // the second instance is blamed.
  CHECK(kMaxMeshVertices == 4194304);
  auto vertices = write_gltf(dir.path(), "vertices.gltf", 2200000, {{{"mesh", 0}}, {{"mesh", 0}}}, {0, 1});
  CHECK(pointer_of([&] { load_mesh_file(vertices); }) == "/nodes/1/mesh");
  // A triangle strip of 8,388,611 byte indices (zeros, in a .bin next to the file) makes
  // 8,388,609 triangles, one beyond the limit: the count is blamed before anything is read.
  CHECK(kMaxMeshTriangles == 8388608);
  const size_t strip = kMaxMeshTriangles + 3;
  std::ofstream(dir.path() / "strip.bin", std::ios::binary) << std::string(strip, '\0');
  auto g = nlohmann::json::parse(test::read_file(write_gltf(dir.path(), "t.gltf", 3, {{{"mesh", 0}}}, {0})));
  g["buffers"] = {{{"uri", "strip.bin"}, {"byteLength", strip}}};
  g["bufferViews"] = {{{"buffer", 0}, {"byteLength", strip}}};
  g["accessors"].push_back({{"bufferView", 0}, {"componentType", 5121}, {"count", strip}, {"type", "SCALAR"}});
  g["meshes"][0]["primitives"][0]["indices"] = 1;
  g["meshes"][0]["primitives"][0]["mode"] = 5;
  std::ofstream(dir.path() / "triangles.gltf") << g.dump();
  CHECK(pointer_of([&] { load_mesh_file(dir.path() / "triangles.gltf"); }) == "/accessors/1/count");
  // 65,537 instances of a one-triangle mesh: one more than 65,536 primitive instances.
  CHECK(kMaxMeshPrimitives == 65536);
  nlohmann::json nodes = nlohmann::json::array(), roots = nlohmann::json::array();
  for (int i = 0; i < 65537; ++i) {
    nodes.push_back({{"mesh", 0}, {"translation", {i, 0, 0}}});
    roots.push_back(i);
  }
  auto primitives = write_gltf(dir.path(), "primitives.gltf", 3, nodes, roots);
  CHECK(pointer_of([&] { load_mesh_file(primitives); }) == "/nodes/65536/mesh");
}
