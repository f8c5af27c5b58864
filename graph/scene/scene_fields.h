// The keys of a scene file declared once, as data: the reader checks values against these
// declarations and the scene JSON Schema is generated from them, so the two cannot drift apart.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "graph/scene/scene.h"

namespace lamina {

enum class SceneFieldType {
  Number,      // one number
  Integer,     // a whole number
  Vec2,        // [a, b]
  Vec3,        // [x, y, z]
  Color,       // [r, g, b], linear
  Quaternion,  // [x, y, z, w], glTF's order
  Text,        // a non-empty string
  Choice,      // one of `choices`
  Object,      // a nested object (the transform); read by its own table
};

// Scene coordinates, sizes and intensities beyond this are surely a mistake, and would overflow
// or lose all precision in the single-precision meshes and renderers downstream.
inline constexpr double kSceneNumberLimit = 1e9;
// The smallest scale magnitude, and the largest ratio of two scale components: a float has 24 bits
// (about 7 digits), so beyond these a transform's inverse (which gives the normals) is lost in
// rounding, or its determinant underflows.
inline constexpr double kMinScale = 1e-6;
inline constexpr double kMaxScaleRatio = 1e6;

struct SceneField {
  std::string name;
  SceneFieldType type = SceneFieldType::Number;
  std::string doc;
  bool required = false;
  // Bounds of the number or of each component; open bounds exclude the value itself.
  double lo = -kSceneNumberLimit, hi = kSceneNumberLimit;
  bool lo_open = false, hi_open = false;
  // Each component's magnitude must be at least this (0: no such bound). The scale uses it to keep
  // transforms invertible in the single precision viewers compute in.
  double min_magnitude = 0.0;
  size_t max_length = 0;  // Text: at most this many characters (Unicode code points); 0: any
  std::vector<std::string> choices;
  std::string default_json;  // the default as JSON text, "" when none

  size_t components() const;
  // "0.0 < radius <= 1000000000.0" style text for messages.
  std::string range_text(const std::string& label) const;
};

inline constexpr size_t kMaxLabelLength = 64;

inline constexpr int kMinSegments = 4;
inline constexpr int kMaxSegments = 1024;

const std::vector<SceneField>& camera_fields();
const std::vector<SceneField>& light_fields(LightType type);
const std::vector<SceneField>& object_fields(ShapeType shape);
const std::vector<SceneField>& transform_fields();

const std::vector<std::string>& light_type_names();  // indexed by LightType
const std::vector<std::string>& shape_names();       // indexed by ShapeType

std::vector<std::string> field_names(const std::vector<SceneField>& fields);

}  // namespace lamina
