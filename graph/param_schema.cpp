#include "graph/param_schema.h"

#include <cstdint>

#include "graph/json_type.h"
#include "graph/limits.h"

namespace lamina {

namespace {

Json number_schema(const ParamDecl& p) {
  // Every number also has a magnitude of at most kMaxNodeNumber, whatever the parameter's range.
  Json n{{"type", p.type == ValueType::Integer ? "integer" : "number"}};
  if (p.lo > -kMaxNodeNumber)
    n[p.lo_open ? "exclusiveMinimum" : "minimum"] = p.lo;
  else
    n["minimum"] = -kMaxNodeNumber;
  if (p.hi < kMaxNodeNumber)
    n[p.hi_open ? "exclusiveMaximum" : "maximum"] = p.hi;
  else
    n["maximum"] = kMaxNodeNumber;
  if (p.min_magnitude > 0.0)
    n["not"] = Json{{"exclusiveMinimum", -p.min_magnitude}, {"exclusiveMaximum", p.min_magnitude}};
  return n;
}

Json array_schema(const ParamDecl& p, size_t size) {
  return Json{{"type", "array"}, {"items", number_schema(p)}, {"minItems", size}, {"maxItems", size}};
}

struct DefaultJson {
  Json operator()(double d) const { return d; }
  template <size_t N>
  Json operator()(const std::array<double, N>& a) const {
    Json out = Json::array();
    for (double c : a) out.push_back(c);
    return out;
  }
  Json operator()(bool b) const { return b; }
  Json operator()(const std::string& s) const { return s; }
  Json operator()(const Link&) const { return nullptr; }
};

Json default_json(const ParamDecl& p) {
  // A whole number's default is written as one: 64, not 64.0.
  if (p.type == ValueType::Integer) return static_cast<std::int64_t>(std::get<double>(*p.fallback));
  return std::visit(DefaultJson{}, *p.fallback);
}

std::string describe(const ParamDecl& p) {
  std::string text = p.doc;
  if (!p.unit.empty()) text += " [" + p.unit + "]";
  return text;
}

}  // namespace

Json schema_ref(const std::string& def) { return Json{{"$ref", "#/$defs/" + def}}; }

Json param_schema(const ParamDecl& p) {
  Json s;
  switch (p.type) {
    case ValueType::Float:
    case ValueType::Integer: s = number_schema(p); break;
    case ValueType::Vec2:
    case ValueType::Color:
    case ValueType::Vec3:
    case ValueType::Quaternion: s = array_schema(p, size_t(value_components(p.type))); break;
    case ValueType::Bool: s = Json{{"type", "boolean"}}; break;
    case ValueType::Enum: s = Json{{"enum", p.choices}}; break;
    case ValueType::String:
      s = Json{{"type", "string"}, {"minLength", 1}};
      if (p.max_length > 0) s["maxLength"] = p.max_length;
      break;
    case ValueType::Object: s = schema_ref(p.name); break;
    case ValueType::Interface:
    case ValueType::Medium:
    case ValueType::Stack: s = schema_ref("link"); break;
  }
  if (p.linkable && !is_closure(p.type)) s = Json{{"anyOf", Json::array({s, schema_ref("link")})}};
  s["description"] = describe(p);
  if (p.fallback && !std::holds_alternative<Link>(*p.fallback)) s["default"] = default_json(p);
  return s;
}

}  // namespace lamina
