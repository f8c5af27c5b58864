// The keys of a scene file declared once, as data, with the ParamDecl of node parameters
// (graph/node_decl.h): the reader checks values against these declarations and takes their
// defaults, and the scene JSON Schema is generated from them, so the three cannot drift apart.
// Every number of a scene is also within +-kSceneNumberLimit.
#pragma once

#include <string>
#include <vector>

#include "graph/node_decl.h"
#include "graph/scene/scene.h"

namespace lamina {

// Scene coordinates, sizes and intensities beyond this are surely a mistake, and would overflow
// or lose all precision in the single-precision meshes and renderers downstream.
inline constexpr double kSceneNumberLimit = 1e9;
// The smallest scale magnitude, and the largest ratio of two scale components: a float has 24 bits
// (about 7 digits), so beyond these a transform's inverse (which gives the normals) is lost in
// rounding, or its determinant underflows.
inline constexpr double kMinScale = 1e-6;
inline constexpr double kMaxScaleRatio = 1e6;

inline constexpr size_t kMaxLabelLength = 64;

inline constexpr int kMinSegments = 4;
inline constexpr int kMaxSegments = 1024;

const std::vector<ParamDecl>& camera_fields();
const std::vector<ParamDecl>& light_fields(LightType type);
const std::vector<ParamDecl>& object_fields(ShapeType shape);
const std::vector<ParamDecl>& transform_fields();

// The keys that choose which of the lists above applies: a light's "type", an object's "shape".
const ParamDecl& light_type_field();
const ParamDecl& shape_field();

const std::vector<std::string>& light_type_names();  // indexed by LightType
const std::vector<std::string>& shape_names();       // indexed by ShapeType

}  // namespace lamina
