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

struct SceneField {
  std::string name;
  SceneFieldType type = SceneFieldType::Number;
  std::string doc;
  bool required = false;
  // Bounds of the number or of each component; open bounds exclude the value itself.
  double lo = -kSceneNumberLimit, hi = kSceneNumberLimit;
  bool lo_open = false, hi_open = false;
  bool nonzero = false;  // each component must differ from 0 (scale)
  std::vector<std::string> choices;
  std::string default_json;  // the default as JSON text, "" when none

  size_t components() const;
  // "0.0 < radius <= 1000000000.0" style text for messages.
  std::string range_text(const std::string& label) const;
};

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
