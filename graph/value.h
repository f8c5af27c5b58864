// Value types of the material graph (what a parameter holds and what a node outputs) and of the
// keys of a scene file, which are declared with the same ParamDecl (graph/scene/scene_fields.h).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace lamina {

// Data types carry numbers or text; closure types (interface, medium, stack) are the
// structural outputs of interface/medium/substrate/layer/mix nodes.
enum class ValueType {
  Float,
  Color,  // linear RGB
  Vec2,
  Vec3,
  Bool,
  Enum,    // a string from a declared list
  String,  // free text, e.g. a file path
  Interface,
  Medium,
  Stack,  // something a layer can sit on: a layer, a mix or a substrate
  // Only in scene files (tests/nodes/registry_test.cpp keeps them out of node declarations):
  Integer,     // a whole number
  Quaternion,  // [x, y, z, w], glTF's order
  Object,      // a nested object with declarations of its own; its schema is the $defs entry of its name
};

std::string_view type_name(ValueType type);
bool is_closure(ValueType type);
// How many numbers a value of the type holds: 1 for a number (a float in a texture register, 1 to
// 3 for the node types), 2 to 4 for the arrays; 0 for the others.
int value_components(ValueType type);

// A reference to another node's output, written "@node" or "@node.output" in JSON.
struct Link {
  std::string node;
  std::string output;  // empty: the node's first (default) output
  bool operator==(const Link&) const = default;
};

std::string to_string(const Link& link);

using Vec2d = std::array<double, 2>;
using Vec3d = std::array<double, 3>;
using Vec4d = std::array<double, 4>;

// A parameter's value as written in the file. Colours and vec3 share Vec3d; the declared
// ValueType tells them apart. Enums and strings share std::string; floats and integers double.
using Value = std::variant<double, Vec2d, Vec3d, Vec4d, bool, std::string, Link>;

// The numbers of a number or an array of them, in order; empty for the other values.
std::vector<double> value_numbers(const Value& v);

}  // namespace lamina
