#include <doctest/doctest.h>

#include "graph/scene/scene.h"
#include "graph/scene/scene_fields.h"
#include "test_support.h"

using namespace lamina;

namespace {

std::vector<const std::vector<ParamDecl>*> every_field_list() {
  std::vector<const std::vector<ParamDecl>*> lists{&camera_fields(), &transform_fields()};
  for (size_t t = 0; t < light_type_names().size(); ++t) lists.push_back(&light_fields(static_cast<LightType>(t)));
  for (size_t s = 0; s < shape_names().size(); ++s) lists.push_back(&object_fields(static_cast<ShapeType>(s)));
  return lists;
}

}  // namespace

TEST_CASE("every scene key's default has its declared type and obeys its declared range") {
  for (const auto* fields : every_field_list()) {
    for (const ParamDecl& f : *fields) {
      CAPTURE(f.name);
      CHECK_FALSE(f.doc.empty());
      if (f.omissible) CHECK_FALSE(f.fallback.has_value());
      if (!f.fallback) continue;
      const std::vector<double> numbers = value_numbers(*f.fallback);
      switch (f.type) {
        case ValueType::Float:
        case ValueType::Integer: CHECK(numbers.size() == 1); break;
        case ValueType::Vec2: CHECK(std::holds_alternative<Vec2d>(*f.fallback)); break;
        case ValueType::Vec3:
        case ValueType::Color: CHECK(std::holds_alternative<Vec3d>(*f.fallback)); break;
        case ValueType::Quaternion: CHECK(std::holds_alternative<Vec4d>(*f.fallback)); break;
        default: CHECK(std::holds_alternative<std::string>(*f.fallback)); break;
      }
      for (double v : numbers) CHECK(f.in_range(v));
    }
  }
}

// Scenes built in code (the sample sheet) start from the structs' initialisers, scene files from
// the declared defaults: the two must be the same numbers.
TEST_CASE("what a scene file leaves out reads as the initialisers of the scene structs") {
  Diagnostics d;
  Scene s = read_scene(R"({
    "format": 1,
    "materials": ["../materials/brass.json"],
    "cameras": [{"name": "c"}],
    "lights": [{"name": "p", "type": "point"}, {"name": "d", "type": "directional"}, {"name": "s", "type": "spot"},
               {"name": "e", "type": "environment", "file": "../materials/textures/patina_mask.png"}],
    "objects": [{"name": "sphere", "shape": "sphere", "material": "brass"},
                {"name": "plane", "shape": "plane", "material": "brass"},
                {"name": "box", "shape": "box", "material": "brass"},
                {"name": "torus", "shape": "torus", "material": "brass"}]
  })",
                       (test::source_dir() / "examples/scenes/inline.json").string(), d, test::repository_policy());
  REQUIRE(d.ok());
  REQUIRE(s.cameras.size() == 1);
  const Camera camera;
  CHECK(s.cameras[0].position == camera.position);
  CHECK(s.cameras[0].look_at == camera.look_at);
  CHECK(s.cameras[0].up == camera.up);
  CHECK(s.cameras[0].yfov_deg == camera.yfov_deg);
  CHECK(s.cameras[0].aspect == camera.aspect);
  CHECK(s.cameras[0].znear == camera.znear);
  CHECK(s.cameras[0].zfar == camera.zfar);
  CHECK(s.cameras[0].exposure == camera.exposure);
  CHECK(s.cameras[0].aperture_radius == camera.aperture_radius);
  CHECK(s.cameras[0].focus_distance == camera.focus_distance);

  REQUIRE(s.lights.size() == 4);
  const Light light;
  for (const Light& l : s.lights) {
    CAPTURE(l.name);
    CHECK(l.color == light.color);
    CHECK(l.intensity == light.intensity);
    CHECK(l.position == light.position);
    CHECK(l.direction == light.direction);
    CHECK(l.inner_cone_deg == light.inner_cone_deg);
    CHECK(l.outer_cone_deg == light.outer_cone_deg);
    CHECK(l.range == light.range);
    CHECK(l.rotation_deg == light.rotation_deg);
    CHECK(l.angular_radius_deg == light.angular_radius_deg);
  }

  REQUIRE(s.objects.size() == 4);
  const SceneObject object;
  for (const SceneObject& o : s.objects) {
    CAPTURE(o.name);
    CHECK(o.radius == object.radius);
    CHECK(o.segments == object.segments);
    CHECK(o.plane_size == object.plane_size);
    CHECK(o.box_size == object.box_size);
    CHECK(o.major_radius == object.major_radius);
    CHECK(o.minor_radius == object.minor_radius);
    CHECK(o.label == object.label);
    CHECK(o.emission == object.emission);
    CHECK(o.transform.translation == object.transform.translation);
    CHECK(o.transform.rotation == object.transform.rotation);
    CHECK(o.transform.scale == object.transform.scale);
  }
}
