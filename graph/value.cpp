#include "graph/value.h"

namespace lamina {

namespace {

struct Numbers {
  std::vector<double> operator()(double d) const { return {d}; }
  template <size_t N>
  std::vector<double> operator()(const std::array<double, N>& a) const {
    return {a.begin(), a.end()};
  }
  template <class Other>
  std::vector<double> operator()(const Other&) const {
    return {};
  }
};

}  // namespace

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
    case ValueType::Integer: return "integer";
    case ValueType::Quaternion: return "quaternion";
    case ValueType::Object: return "object";
  }
  return "?";
}

int value_components(ValueType type) {
  switch (type) {
    case ValueType::Float:
    case ValueType::Integer: return 1;
    case ValueType::Vec2: return 2;
    case ValueType::Color:
    case ValueType::Vec3: return 3;
    case ValueType::Quaternion: return 4;
    default: return 0;
  }
}

bool is_closure(ValueType type) {
  return type == ValueType::Interface || type == ValueType::Medium || type == ValueType::Stack;
}

std::vector<double> value_numbers(const Value& v) { return std::visit(Numbers{}, v); }

std::string to_string(const Link& link) {
  return link.output.empty() ? "@" + link.node : "@" + link.node + "." + link.output;
}

}  // namespace lamina
