// Value types of the material graph: what a parameter holds and what a node outputs.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <variant>

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
};

std::string_view type_name(ValueType type);
bool is_closure(ValueType type);
// How many floats a value of the type takes in a texture register: 1 to 3 for the numeric types,
// 0 for the others.
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

// A parameter's value as written in the file. Colours and vec3 share Vec3d; the declared
// ValueType tells them apart. Enums and strings share std::string.
using Value = std::variant<double, Vec2d, Vec3d, bool, std::string, Link>;

}  // namespace lamina
