#include "graph/scene/scene_fields.h"

namespace lamina {

namespace {

// A scene key; its numbers stay within +-kSceneNumberLimit unless declared narrower.
ParamDecl field(std::string name, ValueType type, std::string doc) {
  return param(std::move(name), type).range(-kSceneNumberLimit, kSceneNumberLimit).described(std::move(doc));
}

ParamDecl name_field(const std::string& what) {
  return field("name", ValueType::String, "the " + what + "'s name, unique among the scene's " + what + "s");
}

ParamDecl point3(std::string name, std::string doc, Vec3d fallback) {
  return field(std::move(name), ValueType::Vec3, std::move(doc)).or_default(fallback);
}

ParamDecl positive(std::string name, std::string doc) {
  return field(std::move(name), ValueType::Float, std::move(doc)).above(0.0);
}

ParamDecl color_field() {
  return field("color", ValueType::Color, "linear RGB colour of the light")
      .at_least(0.0)
      .or_default(Vec3d{1.0, 1.0, 1.0});
}

ParamDecl intensity_field(std::string doc) {
  return field("intensity", ValueType::Float, std::move(doc)).at_least(0.0).or_default(1.0);
}

ParamDecl range_field() {
  return positive("range", "distance [scene units] beyond which the light has no effect; none: infinite").optional();
}

ParamDecl direction_field() {
  return point3("direction", "where the light travels, any non-zero length", Vec3d{0.0, -1.0, 0.0});
}

ParamDecl segments_field() {
  return field("segments", ValueType::Integer,
               "tessellation: quads around the shape; the rings across are derived from it")
      .range(kMinSegments, kMaxSegments)
      .or_default(64.0);
}

std::vector<ParamDecl> object_common() {
  return {name_field("object"),
          shape_field(),
          field("material", ValueType::String, "the name of a material defined in one of the scene's material files"),
          field("transform", ValueType::Object,
                "placement of the object: scale, then rotation, then translation (glTF's order)")
              .optional(),
          field("label", ValueType::String,
                "text shown under the object in glTF viewers, on an unlit quad facing the first camera; none: no "
                "label")
              .optional()
              .at_most_characters(kMaxLabelLength),
          field("emission", ValueType::Color,
                "radiance its front faces emit [cd/m^2], linear RGB: lamina render lights the scene with it; none: "
                "no emission")
              .at_least(0.0)
              .optional()};
}

std::vector<ParamDecl> with(std::vector<ParamDecl> fields, const std::vector<ParamDecl>& more) {
  fields.insert(fields.end(), more.begin(), more.end());
  return fields;
}

}  // namespace

const std::vector<std::string>& light_type_names() {
  static const std::vector<std::string> names{"point", "directional", "spot", "environment"};
  return names;
}

const std::vector<std::string>& shape_names() {
  static const std::vector<std::string> names{"sphere", "plane", "box", "torus", "mesh"};
  return names;
}

const ParamDecl& light_type_field() {
  static const ParamDecl type =
      field("type", ValueType::Enum,
            "point, spot and directional as KHR_lights_punctual; environment: an equirectangular image")
          .one_of(light_type_names());
  return type;
}

const ParamDecl& shape_field() {
  static const ParamDecl shape =
      field("shape", ValueType::Enum, "a built-in primitive (centred on the origin, y up) or a glTF mesh file")
          .one_of(shape_names());
  return shape;
}

const std::vector<ParamDecl>& camera_fields() {
  static const std::vector<ParamDecl> fields{
      name_field("camera"),
      point3("position", "where the camera is [scene units]", Vec3d{0.0, 0.0, 5.0}),
      point3("look_at", "the point the camera looks at; must differ from position", Vec3d{0.0, 0.0, 0.0}),
      point3("up", "the up direction; must not be parallel to the view direction", Vec3d{0.0, 1.0, 0.0}),
      field("yfov", ValueType::Float, "vertical field of view [degrees]").above(0.0).below(180.0).or_default(40.0),
      field("aspect", ValueType::Float, "width / height of the image").above(0.0).at_most(100.0).or_default(1.5),
      positive("znear", "distance to the near clipping plane [scene units]").or_default(0.05),
      positive("zfar", "distance to the far clipping plane, greater than znear; none: infinite projection").optional(),
      field("exposure", ValueType::Float,
            "stops: lamina render multiplies the image's radiance by 2^exposure (and --exposure adds to it)")
          .range(-64.0, 64.0)
          .or_default(0.0),
      field("aperture_radius", ValueType::Float,
            "the radius of a thin lens [scene units]: points off the plane in focus blur into disks, as a real "
            "lens shows them (depth of field); 0: a pinhole, everything sharp. lamina render only; glTF has no "
            "counterpart")
          .at_least(0.0)
          .at_most(1e6)
          .or_default(0.0),
      positive("focus_distance",
               "distance from the camera to the plane in focus, along the view direction [scene units]; none: the "
               "distance to look_at")
          .optional(),
  };
  return fields;
}

const std::vector<ParamDecl>& light_fields(LightType type) {
  static const std::vector<ParamDecl> common{name_field("light"), light_type_field(), color_field()};
  static const std::vector<ParamDecl> point =
      with(common, {intensity_field("luminous intensity [candela] (KHR_lights_punctual)"),
                    point3("position", "where the light is [scene units]", Vec3d{0.0, 0.0, 0.0}), range_field()});
  static const std::vector<ParamDecl> directional =
      with(common, {intensity_field("illuminance [lux] (KHR_lights_punctual)"), direction_field(),
                    field("angular_radius", ValueType::Float,
                          "the source's apparent radius [degrees] (the sun: 0.27); 0: a point at infinity with sharp "
                          "shadows. lamina render only; glTF has no counterpart")
                        .at_least(0.0)
                        .at_most(45.0)
                        .or_default(0.0)});
  static const std::vector<ParamDecl> spot =
      with(common, {intensity_field("luminous intensity [candela] (KHR_lights_punctual)"),
                    point3("position", "where the light is [scene units]", Vec3d{0.0, 0.0, 0.0}), direction_field(),
                    field("inner_cone", ValueType::Float,
                          "angle from the axis where the falloff starts [degrees], less than outer_cone")
                        .at_least(0.0)
                        .below(90.0)
                        .or_default(0.0),
                    field("outer_cone", ValueType::Float, "angle from the axis where the light ends [degrees]")
                        .above(0.0)
                        .at_most(90.0)
                        .or_default(45.0),
                    range_field()});
  static const std::vector<ParamDecl> environment =
      with(common, {intensity_field("multiplier of the image's radiance (of the colour's, for a uniform sky)"),
                    field("file", ValueType::String,
                          "an equirectangular image, relative to the scene file; none: a uniform sky of radiance "
                          "color times intensity")
                        .optional(),
                    field("rotation", ValueType::Float,
                          "the image turned about the up axis +y [degrees], counter-clockwise seen from above: 90 "
                          "moves what the image shows along +x to -z")
                        .range(-360.0, 360.0)
                        .or_default(0.0)});
  switch (type) {
    case LightType::Point: return point;
    case LightType::Directional: return directional;
    case LightType::Spot: return spot;
    case LightType::Environment: return environment;
  }
  return point;
}

const std::vector<ParamDecl>& object_fields(ShapeType shape) {
  static const std::vector<ParamDecl> sphere =
      with(object_common(), {positive("radius", "radius [scene units]").or_default(1.0), segments_field()});
  static const std::vector<ParamDecl> plane =
      with(object_common(), {field("size", ValueType::Vec2, "extent along x and z [scene units]; the plane faces +y")
                                 .above(0.0)
                                 .or_default(Vec2d{1.0, 1.0})});
  static const std::vector<ParamDecl> box =
      with(object_common(), {field("size", ValueType::Vec3, "extent along x, y and z [scene units]")
                                 .above(0.0)
                                 .or_default(Vec3d{1.0, 1.0, 1.0})});
  static const std::vector<ParamDecl> torus =
      with(object_common(),
           {positive("major_radius", "distance from the centre to the tube's centre [scene units]; the axis is y")
                .or_default(1.0),
            positive("minor_radius", "radius of the tube [scene units], less than major_radius").or_default(0.25),
            segments_field()});
  static const std::vector<ParamDecl> mesh =
      with(object_common(), {field("file", ValueType::String,
                                   "a .gltf or .glb file relative to the scene file: every triangle primitive of its "
                                   "default scene, node transforms applied")});
  switch (shape) {
    case ShapeType::Sphere: return sphere;
    case ShapeType::Plane: return plane;
    case ShapeType::Box: return box;
    case ShapeType::Torus: return torus;
    case ShapeType::Mesh: return mesh;
  }
  return sphere;
}

const std::vector<ParamDecl>& transform_fields() {
  static const std::vector<ParamDecl> fields{
      point3("translation", "offset [scene units]", Vec3d{0.0, 0.0, 0.0}),
      field("rotation", ValueType::Quaternion, "unit quaternion [x, y, z, w] (glTF's order); not with rotation_deg")
          .or_default(Vec4d{0.0, 0.0, 0.0, 1.0}),
      field("rotation_deg", ValueType::Vec3,
            "Euler angles [degrees] about x, then y, then z (fixed axes: R = Rz Ry Rx); not with rotation")
          .optional(),
      field("scale", ValueType::Vec3,
            "scale along the object's axes; negative mirrors; each magnitude at least 1e-6 and at most 1e6 times "
            "the smallest, so that the transform stays invertible in single precision")
          .magnitude_at_least(kMinScale)
          .or_default(Vec3d{1.0, 1.0, 1.0}),
  };
  return fields;
}

}  // namespace lamina
