#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "graph/scene/scene.h"
#include "test_support.h"

using namespace lamina;

namespace {

// A scene "written" in a folder examples/scenes, with the repository as its asset root.
Scene read_inline(const std::string& text, Diagnostics& d) {
  return read_scene(text, (test::source_dir() / "examples/scenes/inline.json").string(), d, test::repository_policy());
}

std::string all_problems(const Diagnostics& d) {
  std::string out;
  for (const auto& e : d.errors()) out += format(e) + "\n";
  for (const auto& w : d.warnings()) out += format(w) + "\n";
  return out;
}

}  // namespace

TEST_CASE("a scene reads with its values, and what it leaves out takes the documented defaults") {
  Diagnostics d;
  Scene s = read_inline(R"({
    "format": 1,
    "materials": ["../materials/brass.json", "../materials/car_paint.json"],
    "cameras": [{"name": "main", "position": [0, 1, 6], "yfov": 35, "zfar": 50}],
    "lights": [{"name": "key", "type": "point", "position": [3, 4, 5], "intensity": 60, "range": 20},
               {"name": "spot", "type": "spot", "direction": [0, -2, 0], "inner_cone": 10, "outer_cone": 25}],
    "objects": [{"name": "ball", "shape": "sphere", "radius": 0.5, "segments": 16, "material": "car_paint",
                 "transform": {"translation": [1, 2, 3], "rotation_deg": [90, 0, 90], "scale": [2, 2, 2]}},
                {"name": "crate", "shape": "box", "size": [1, 2, 3], "material": "brass",
                 "transform": {"rotation": [0, 0, 0, 2]}},
                {"name": "quad", "shape": "mesh", "file": "../../tests/data/scenes/quad.gltf", "material": "brass"}]
  })",
                        d);
  INFO(all_problems(d));
  REQUIRE(d.ok());
  REQUIRE(d.warnings().size() == 1);  // the quaternion of length 2
  CHECK(d.warnings()[0].pointer == "/objects/1/transform/rotation");

  REQUIRE(s.material_files.size() == 2);
  CHECK(s.material_files[0].path == "../materials/brass.json");
  CHECK(s.material_files[0].resolved == (test::source_dir() / "examples/materials/brass.json").lexically_normal());
  const MaterialFileRef* file = nullptr;
  CHECK(s.find_material("car_paint", &file) != nullptr);
  CHECK(file == &s.material_files[1]);
  CHECK(s.find_material("nothing") == nullptr);

  REQUIRE(s.cameras.size() == 1);
  const Camera& c = s.cameras[0];
  CHECK(c.position == glm::dvec3(0, 1, 6));
  CHECK(c.look_at == glm::dvec3(0));
  CHECK(c.up == glm::dvec3(0, 1, 0));
  CHECK(c.yfov_deg == 35.0);
  CHECK(c.aspect == 1.5);
  CHECK(c.znear == 0.05);
  CHECK(c.zfar == 50.0);

  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].type == LightType::Point);
  CHECK(s.lights[0].intensity == 60.0);
  CHECK(s.lights[0].range == 20.0);
  CHECK(s.lights[0].color == glm::dvec3(1.0));
  CHECK(s.lights[1].type == LightType::Spot);
  CHECK(s.lights[1].direction == glm::dvec3(0, -1, 0));  // normalised
  CHECK(s.lights[1].inner_cone_deg == 10.0);
  CHECK(s.lights[1].outer_cone_deg == 25.0);
  CHECK(s.lights[1].intensity == 1.0);

  REQUIRE(s.objects.size() == 3);
  const SceneObject& ball = s.objects[0];
  CHECK(ball.shape == ShapeType::Sphere);
  CHECK(ball.radius == 0.5);
  CHECK(ball.segments == 16);
  CHECK(ball.transform.translation == glm::dvec3(1, 2, 3));
  CHECK(ball.transform.scale == glm::dvec3(2));
  // R = Rz(90) Rx(90): q = (cos45 + k sin45)(cos45 + i sin45) = 0.5 + 0.5i + 0.5j + 0.5k, by hand.
  CHECK(ball.transform.rotation.w == doctest::Approx(0.5));
  CHECK(ball.transform.rotation.x == doctest::Approx(0.5));
  CHECK(ball.transform.rotation.y == doctest::Approx(0.5));
  CHECK(ball.transform.rotation.z == doctest::Approx(0.5));
  const SceneObject& crate = s.objects[1];
  CHECK(crate.box_size == glm::dvec3(1, 2, 3));
  CHECK(crate.segments == 64);
  CHECK(crate.transform.rotation.w == 1.0);  // [0, 0, 0, 2] normalised to the identity
  CHECK(crate.transform.translation == glm::dvec3(0));
  CHECK(s.objects[2].resolved_mesh_file == (test::source_dir() / "tests/data/scenes/quad.gltf").lexically_normal());
}

TEST_CASE("every broken scene of the corpus gives its error at the expected file and pointer") {
  auto dir = test::source_dir() / "tests/data/bad_scenes";
  auto cases = nlohmann::json::parse(test::read_file(dir / "cases.json"));
  CHECK(cases.size() >= 40);
  for (const auto& c : cases) {
    std::string name = c.at("file");
    CAPTURE(name);
    auto path = dir / name;
    std::string expected_file =
        c.contains("in") ? (dir / c.at("in").get<std::string>()).lexically_normal().string() : path.string();
    Diagnostics d;
    std::string text = test::read_file(path);
    CHECK(looks_like_scene(text));
    read_scene_file(path, d);
    INFO(all_problems(d));
    CHECK_FALSE(d.ok());
    bool found = false;
    for (const auto& e : d.errors())
      found = found || (e.file == expected_file && e.pointer == c.at("pointer").get<std::string>() &&
                        (e.message + " " + e.hint).find(c.at("message").get<std::string>()) != std::string::npos);
    CHECK(found);
  }
}

TEST_CASE("mistakes name what was expected: the closest key, shape or material, and resolved paths") {
  auto dir = test::source_dir() / "tests/data/bad_scenes";
  Diagnostics d;
  read_scene_file(dir / "unknown_material_name.json", d);
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].hint.find("brass or car_paint") != std::string::npos);

  Diagnostics missing;
  read_scene_file(dir / "missing_material_file.json", missing);
  REQUIRE(missing.errors().size() == 1);  // no knock-on "unknown material" errors
  CHECK(missing.errors()[0].message.find((dir / "materials/no_such_file.json").lexically_normal().string()) !=
        std::string::npos);

  Diagnostics malformed;
  read_scene_file(dir / "malformed_trailing_comma.json", malformed);
  REQUIRE(malformed.errors().size() == 1);
  CHECK(malformed.errors()[0].message.find("line 48, column") != std::string::npos);
}

TEST_CASE("the showcase reads with no error and no warning, one sphere per example material") {
  Diagnostics d;
  Scene s = read_scene_file(test::source_dir() / "examples/showcase.json", d);
  INFO(all_problems(d));
  CHECK(d.ok());
  CHECK(d.warnings().empty());
  CHECK(s.material_files.size() == test::example_files().size());
  CHECK(s.objects.size() == test::example_files().size() + 1);  // and the floor
  for (const auto& f : test::example_files()) {
    std::string name = f.stem().string();
    CAPTURE(name);
    auto it = std::find_if(s.objects.begin(), s.objects.end(), [&](const SceneObject& o) { return o.name == name; });
    REQUIRE(it != s.objects.end());
    CHECK(it->material == name);
    CHECK(it->shape == ShapeType::Sphere);
  }
  CHECK(s.cameras.size() == 1);
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].type == LightType::Point);
  CHECK(s.lights[1].type == LightType::Directional);
}

TEST_CASE("scene files are told from material files by their objects") {
  CHECK(looks_like_scene(R"({"format": 1, "materials": ["a.json"], "objects": []})"));
  CHECK_FALSE(looks_like_scene(R"({"format": 1, "materials": [{"name": "a"}]})"));
  CHECK(looks_like_scene(R"({"format": 1, "objects": [,]})"));  // malformed, still a scene
  CHECK_FALSE(looks_like_scene(""));
}

TEST_CASE("an object's optional label is read as written, and the showcase labels every sphere with its name") {
  Diagnostics d;
  Scene s = read_inline(R"json({"format": 1, "materials": ["../materials/brass.json"],
    "objects": [{"name": "a", "shape": "sphere", "material": "brass", "label": "Brass, polished (ü)"},
                {"name": "b", "shape": "box", "material": "brass"}]})json",
                        d);
  INFO(all_problems(d));
  REQUIRE(d.ok());
  CHECK(s.objects[0].label == "Brass, polished (\xc3\xbc)");
  CHECK(s.objects[1].label.empty());

  // 64 characters are allowed (the two bytes of U+00FC count as one), 65 are not.
  auto with_label = [](const std::string& label) {
    Diagnostics out;
    read_inline(R"({"format": 1, "materials": ["../materials/brass.json"],
      "objects": [{"name": "a", "shape": "sphere", "material": "brass", "label": ")" +
                    label + "\"}]}",
                out);
    return out;
  };
  CHECK(with_label(std::string(63, 'x') + "\xc3\xbc").ok());
  Diagnostics too_long = with_label(std::string(64, 'x') + "\xc3\xbc");
  REQUIRE(too_long.errors().size() == 1);
  CHECK(too_long.errors()[0].pointer == "/objects/0/label");

  Diagnostics showcase;
  Scene s2 = read_scene_file(test::source_dir() / "examples/showcase.json", showcase);
  size_t labelled = 0;
  for (const auto& o : s2.objects)
    if (o.shape == ShapeType::Sphere) {
      CHECK(o.label == o.name);
      ++labelled;
    }
  CHECK(labelled == test::example_files().size());  // one sphere per example
}

TEST_CASE("a transform is practically singular when its scale's magnitudes differ by more than 1e6") {
  auto scene_with_scale = [](const std::string& scale) {
    Diagnostics d;
    read_inline(R"({"format": 1, "materials": ["../materials/brass.json"],
      "objects": [{"name": "a", "shape": "sphere", "material": "brass", "transform": {"scale": )" +
                    scale + "}}]}",
                d);
    return d;
  };
  CHECK(scene_with_scale("[1e-3, 1e3, -1]").ok());  // a ratio of exactly 1e6, mirrored
  CHECK(scene_with_scale("[1e-6, 1e-6, 1e-6]").ok());
  Diagnostics ratio = scene_with_scale("[1e-3, 1.001e3, 1]");
  REQUIRE(ratio.errors().size() == 1);
  CHECK(ratio.errors()[0].pointer == "/objects/0/transform/scale");
  Diagnostics tiny = scene_with_scale("[1, 9.99e-7, 1]");
  REQUIRE(tiny.errors().size() == 1);
  CHECK(tiny.errors()[0].pointer == "/objects/0/transform/scale/1");
}
