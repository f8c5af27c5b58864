#include "graph/scene/scene_fields.h"

#include "graph/number_text.h"

// The tables below name only what differs from SceneField's defaults; the rest keeps them.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace lamina {

namespace {

SceneField name_field(const std::string& what) {
  return {.name = "name",
          .type = SceneFieldType::Text,
          .doc = "the " + what + "'s name, unique among the scene's " + what + "s",
          .required = true};
}

SceneField point3(const std::string& name, const std::string& doc, const std::string& fallback) {
  return {.name = name, .type = SceneFieldType::Vec3, .doc = doc, .default_json = fallback};
}

SceneField positive(const std::string& name, const std::string& doc, const std::string& fallback) {
  return {
      .name = name, .type = SceneFieldType::Number, .doc = doc, .lo = 0.0, .lo_open = true, .default_json = fallback};
}

SceneField color_field() {
  return {.name = "color",
          .type = SceneFieldType::Color,
          .doc = "linear RGB colour of the light",
          .lo = 0.0,
          .default_json = "[1.0, 1.0, 1.0]"};
}

SceneField intensity_field(const std::string& doc) {
  return {.name = "intensity", .type = SceneFieldType::Number, .doc = doc, .lo = 0.0, .default_json = "1.0"};
}

SceneField range_field() {
  return positive("range", "distance [scene units] beyond which the light has no effect; none: infinite", "");
}

SceneField direction_field() {
  return point3("direction", "where the light travels, any non-zero length", "[0.0, -1.0, 0.0]");
}

SceneField segments_field() {
  return {.name = "segments",
          .type = SceneFieldType::Integer,
          .doc = "tessellation: quads around the shape; the rings across are derived from it",
          .lo = kMinSegments,
          .hi = kMaxSegments,
          .default_json = "64"};
}

SceneField light_type_field() {
  return {.name = "type",
          .type = SceneFieldType::Choice,
          .doc = "point, spot and directional as KHR_lights_punctual; environment: an equirectangular image",
          .required = true,
          .choices = light_type_names()};
}

SceneField shape_field() {
  return {.name = "shape",
          .type = SceneFieldType::Choice,
          .doc = "a built-in primitive (centred on the origin, y up) or a glTF mesh file",
          .required = true,
          .choices = shape_names()};
}

std::vector<SceneField> object_common() {
  return {name_field("object"), shape_field(),
          SceneField{.name = "material",
                     .type = SceneFieldType::Text,
                     .doc = "the name of a material defined in one of the scene's material files",
                     .required = true},
          SceneField{.name = "transform",
                     .type = SceneFieldType::Object,
                     .doc = "placement of the object: scale, then rotation, then translation (glTF's order)"},
          SceneField{.name = "label",
                     .type = SceneFieldType::Text,
                     .doc = "text shown under the object in glTF viewers, on an unlit quad facing the first camera; "
                            "none: no label",
                     .max_length = kMaxLabelLength}};
}

std::vector<SceneField> with(std::vector<SceneField> fields, const std::vector<SceneField>& more) {
  fields.insert(fields.end(), more.begin(), more.end());
  return fields;
}

}  // namespace

size_t SceneField::components() const {
  switch (type) {
    case SceneFieldType::Vec2: return 2;
    case SceneFieldType::Vec3:
    case SceneFieldType::Color: return 3;
    case SceneFieldType::Quaternion: return 4;
    default: return 1;
  }
}

std::string SceneField::range_text(const std::string& label) const {
  std::string text =
      number_text(lo) + (lo_open ? " < " : " <= ") + label + (hi_open ? " < " : " <= ") + number_text(hi);
  if (min_magnitude > 0.0) text += ", |" + label + "| >= " + number_text(min_magnitude);
  return text;
}

const std::vector<std::string>& light_type_names() {
  static const std::vector<std::string> names{"point", "directional", "spot", "environment"};
  return names;
}

const std::vector<std::string>& shape_names() {
  static const std::vector<std::string> names{"sphere", "plane", "box", "torus", "mesh"};
  return names;
}

std::vector<std::string> field_names(const std::vector<SceneField>& fields) {
  std::vector<std::string> names;
  for (const auto& f : fields) names.push_back(f.name);
  return names;
}

const std::vector<SceneField>& camera_fields() {
  static const std::vector<SceneField> fields{
      name_field("camera"),
      point3("position", "where the camera is [scene units]", "[0.0, 0.0, 5.0]"),
      point3("look_at", "the point the camera looks at; must differ from position", "[0.0, 0.0, 0.0]"),
      point3("up", "the up direction; must not be parallel to the view direction", "[0.0, 1.0, 0.0]"),
      SceneField{.name = "yfov",
                 .type = SceneFieldType::Number,
                 .doc = "vertical field of view [degrees]",
                 .lo = 0.0,
                 .hi = 180.0,
                 .lo_open = true,
                 .hi_open = true,
                 .default_json = "40.0"},
      SceneField{.name = "aspect",
                 .type = SceneFieldType::Number,
                 .doc = "width / height of the image",
                 .lo = 0.0,
                 .hi = 100.0,
                 .lo_open = true,
                 .default_json = "1.5"},
      positive("znear", "distance to the near clipping plane [scene units]", "0.05"),
      positive("zfar", "distance to the far clipping plane, greater than znear; none: infinite projection", ""),
  };
  return fields;
}

const std::vector<SceneField>& light_fields(LightType type) {
  static const std::vector<SceneField> common{name_field("light"), light_type_field(), color_field()};
  static const std::vector<SceneField> point =
      with(common, {intensity_field("luminous intensity [candela] (KHR_lights_punctual)"),
                    point3("position", "where the light is [scene units]", "[0.0, 0.0, 0.0]"), range_field()});
  static const std::vector<SceneField> directional =
      with(common, {intensity_field("illuminance [lux] (KHR_lights_punctual)"), direction_field()});
  static const std::vector<SceneField> spot =
      with(common, {intensity_field("luminous intensity [candela] (KHR_lights_punctual)"),
                    point3("position", "where the light is [scene units]", "[0.0, 0.0, 0.0]"), direction_field(),
                    SceneField{.name = "inner_cone",
                               .type = SceneFieldType::Number,
                               .doc = "angle from the axis where the falloff starts [degrees], less than outer_cone",
                               .lo = 0.0,
                               .hi = 90.0,
                               .hi_open = true,
                               .default_json = "0.0"},
                    SceneField{.name = "outer_cone",
                               .type = SceneFieldType::Number,
                               .doc = "angle from the axis where the light ends [degrees]",
                               .lo = 0.0,
                               .hi = 90.0,
                               .lo_open = true,
                               .default_json = "45.0"},
                    range_field()});
  static const std::vector<SceneField> environment =
      with(common, {intensity_field("multiplier of the image's radiance"),
                    SceneField{.name = "file",
                               .type = SceneFieldType::Text,
                               .doc = "an equirectangular image, relative to the scene file",
                               .required = true}});
  switch (type) {
    case LightType::Point: return point;
    case LightType::Directional: return directional;
    case LightType::Spot: return spot;
    case LightType::Environment: return environment;
  }
  return point;
}

const std::vector<SceneField>& object_fields(ShapeType shape) {
  static const std::vector<SceneField> sphere =
      with(object_common(), {positive("radius", "radius [scene units]", "1.0"), segments_field()});
  static const std::vector<SceneField> plane =
      with(object_common(), {SceneField{.name = "size",
                                        .type = SceneFieldType::Vec2,
                                        .doc = "extent along x and z [scene units]; the plane faces +y",
                                        .lo = 0.0,
                                        .lo_open = true,
                                        .default_json = "[1.0, 1.0]"}});
  static const std::vector<SceneField> box =
      with(object_common(), {SceneField{.name = "size",
                                        .type = SceneFieldType::Vec3,
                                        .doc = "extent along x, y and z [scene units]",
                                        .lo = 0.0,
                                        .lo_open = true,
                                        .default_json = "[1.0, 1.0, 1.0]"}});
  static const std::vector<SceneField> torus = with(
      object_common(),
      {positive("major_radius", "distance from the centre to the tube's centre [scene units]; the axis is y", "1.0"),
       positive("minor_radius", "radius of the tube [scene units], less than major_radius", "0.25"), segments_field()});
  static const std::vector<SceneField> mesh = with(
      object_common(), {SceneField{.name = "file",
                                   .type = SceneFieldType::Text,
                                   .doc = "a .gltf or .glb file relative to the scene file: every triangle primitive "
                                          "of its default scene, node transforms applied",
                                   .required = true}});
  switch (shape) {
    case ShapeType::Sphere: return sphere;
    case ShapeType::Plane: return plane;
    case ShapeType::Box: return box;
    case ShapeType::Torus: return torus;
    case ShapeType::Mesh: return mesh;
  }
  return sphere;
}

const std::vector<SceneField>& transform_fields() {
  static const std::vector<SceneField> fields{
      point3("translation", "offset [scene units]", "[0.0, 0.0, 0.0]"),
      SceneField{.name = "rotation",
                 .type = SceneFieldType::Quaternion,
                 .doc = "unit quaternion [x, y, z, w] (glTF's order); not with rotation_deg",
                 .default_json = "[0.0, 0.0, 0.0, 1.0]"},
      SceneField{.name = "rotation_deg",
                 .type = SceneFieldType::Vec3,
                 .doc = "Euler angles [degrees] about x, then y, then z (fixed axes: R = Rz Ry Rx); not with rotation"},
      SceneField{.name = "scale",
                 .type = SceneFieldType::Vec3,
                 .doc = "scale along the object's axes; negative mirrors; each magnitude at least 1e-6 and at "
                        "most 1e6 times the smallest, so that the transform stays invertible in single precision",
                 .min_magnitude = kMinScale,
                 .default_json = "[1.0, 1.0, 1.0]"},
  };
  return fields;
}

}  // namespace lamina
