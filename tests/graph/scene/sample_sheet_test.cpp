#include <doctest/doctest.h>

#include "graph/scene/scene.h"

using namespace lamina;

TEST_CASE("a sample sheet puts one unit sphere per material on a grid, framed by its camera") {
  Document doc;
  for (const char* name : {"a", "b", "c", "d", "e"}) {
    Material m;
    m.name = name;
    doc.materials.push_back(m);
  }
  Scene s = sample_sheet(doc, "dir/five.json", 4);
  REQUIRE(s.objects.size() == 5);
  REQUIRE(s.material_files.size() == 1);
  CHECK(s.material_files[0].resolved == std::filesystem::path("dir/five.json"));
  const char* names[] = {"a", "b", "c", "d", "e"};
  for (size_t i = 0; i < 5; ++i) {
    CAPTURE(i);
    CHECK(s.objects[i].name == names[i]);
    CHECK(s.objects[i].material == names[i]);
    CHECK(s.objects[i].shape == ShapeType::Sphere);
    CHECK(s.objects[i].radius == 1.0);
    CHECK(s.find_material(names[i]) != nullptr);
  }
  // Two rows of up to 4, 2.5 apart, centred: x = -3.75, -1.25, 1.25, 3.75; y = 1.25, then -1.25.
  CHECK(s.objects[0].transform.translation == glm::dvec3(-3.75, 1.25, 0));
  CHECK(s.objects[3].transform.translation == glm::dvec3(3.75, 1.25, 0));
  CHECK(s.objects[4].transform.translation == glm::dvec3(-3.75, -1.25, 0));

  REQUIRE(s.cameras.size() == 1);
  const Camera& c = s.cameras[0];
  glm::dvec3 forward = glm::normalize(c.look_at - c.position);
  glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
  glm::dvec3 up = glm::cross(right, forward);
  double tan_half = std::tan(glm::radians(c.yfov_deg) / 2.0);
  for (const auto& o : s.objects) {
    // Every sphere's silhouette extremes project inside the image.
    for (glm::dvec3 offset : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0)}) {
      glm::dvec3 d = o.transform.translation + offset - c.position;
      double depth = glm::dot(d, forward);
      CHECK(depth > c.znear);
      CHECK(std::abs(glm::dot(d, right) / depth) < tan_half * c.aspect);
      CHECK(std::abs(glm::dot(d, up) / depth) < tan_half);
    }
  }
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].type == LightType::Point);
  CHECK(s.lights[1].type == LightType::Directional);
  CHECK(s.lights[0].name != s.lights[1].name);
}

TEST_CASE("a sample sheet of fewer materials than columns is one centred row, labelled with the material") {
  Document doc;
  doc.materials.emplace_back();
  doc.materials.back().name = "only";
  Scene s = sample_sheet(doc, "one.json");
  REQUIRE(s.objects.size() == 1);
  CHECK(s.objects[0].transform.translation == glm::dvec3(0.0));
  CHECK(s.objects[0].label == "only");
}
