#include "graph/value.h"

namespace lamina {

std::string_view type_name(ValueType type) {
  switch (type) {
    case ValueType::Float: return "float";
    case ValueType::Color: return "color";
    case ValueType::Vec2: return "vec2";
    case ValueType::Vec3: return "vec3";
    case ValueType::Bool: return "bool";
    case ValueType::Enum: return "enum";
    case ValueType::String: return "string";
    case ValueType::Interface: return "interface";
    case ValueType::Medium: return "medium";
    case ValueType::Stack: return "stack";
  }
  return "?";
}

int value_components(ValueType type) {
  switch (type) {
    case ValueType::Float: return 1;
    case ValueType::Vec2: return 2;
    case ValueType::Color:
    case ValueType::Vec3: return 3;
    default: return 0;
  }
}

bool is_closure(ValueType type) {
  return type == ValueType::Interface || type == ValueType::Medium || type == ValueType::Stack;
}

std::string to_string(const Link& link) {
  return link.output.empty() ? "@" + link.node : "@" + link.node + "." + link.output;
}

}  // namespace lamina
