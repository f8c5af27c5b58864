#include "graph/node_decl.h"

#include <cmath>

#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/number_text.h"

namespace lamina {

std::string_view kind_name(NodeKind kind) {
  switch (kind) {
    case NodeKind::Interface: return "interface";
    case NodeKind::Medium: return "medium";
    case NodeKind::Substrate: return "substrate";
    case NodeKind::Layer: return "layer";
    case NodeKind::Mix: return "mix";
    case NodeKind::Select: return "select";
    case NodeKind::Texture: return "texture";
    case NodeKind::Math: return "math";
  }
  return "?";
}

ParamDecl param(std::string name, ValueType type) {
  ParamDecl p;
  p.name = std::move(name);
  p.type = type;
  return p;
}

ParamDecl& ParamDecl::range(double low, double high) {
  lo = low;
  hi = high;
  return *this;
}
ParamDecl& ParamDecl::above(double low) {
  lo = low;
  lo_open = true;
  return *this;
}
ParamDecl& ParamDecl::at_least(double low) {
  lo = low;
  return *this;
}
ParamDecl& ParamDecl::at_most(double high) {
  hi = high;
  return *this;
}
ParamDecl& ParamDecl::below(double high) {
  hi = high;
  hi_open = true;
  return *this;
}
ParamDecl& ParamDecl::magnitude_at_least(double m) {
  min_magnitude = m;
  return *this;
}
ParamDecl& ParamDecl::at_most_characters(size_t n) {
  max_length = n;
  return *this;
}
ParamDecl& ParamDecl::in_unit(std::string u) {
  unit = std::move(u);
  return *this;
}
ParamDecl& ParamDecl::or_default(Value v) {
  fallback = std::move(v);
  return *this;
}
ParamDecl& ParamDecl::optional() {
  omissible = true;
  return *this;
}
ParamDecl& ParamDecl::one_of(std::vector<std::string> options) {
  choices = std::move(options);
  return *this;
}
ParamDecl& ParamDecl::one_of_described(std::vector<std::pair<std::string, std::string>> options) {
  choices.clear();
  choice_docs.clear();
  for (auto& [value, line] : options) {
    choices.push_back(std::move(value));
    choice_docs.push_back(std::move(line));
  }
  return *this;
}
ParamDecl& ParamDecl::links() {
  linkable = true;
  return *this;
}
ParamDecl& ParamDecl::described(std::string text) {
  doc = std::move(text);
  return *this;
}

bool ParamDecl::has_range() const { return std::isfinite(lo) || std::isfinite(hi); }

bool ParamDecl::in_range(double v) const {
  const bool below = lo_open ? !(v > lo) : v < lo;
  const bool above = hi_open ? !(v < hi) : v > hi;
  return !below && !above && std::abs(v) >= min_magnitude;
}

std::string ParamDecl::range_text() const { return range_text(name); }

std::string ParamDecl::range_text(std::string_view label) const {
  std::string out;
  if (std::isfinite(lo)) out += number_text(lo) + (lo_open ? " < " : " <= ");
  out += label;
  if (std::isfinite(hi)) out += (hi_open ? " < " : " <= ") + number_text(hi);
  if (min_magnitude > 0.0) out += ", |" + std::string(label) + "| >= " + number_text(min_magnitude);
  return out;
}

std::string ParamDecl::expected_text() const {
  switch (type) {
    case ValueType::Float: return "a number";
    case ValueType::Integer: return "a whole number";
    case ValueType::Color: return "an RGB colour [r, g, b]";
    case ValueType::Vec2: return "an array [u, v]";
    case ValueType::Vec3: return "an array [x, y, z]";
    case ValueType::Quaternion: return "a quaternion [x, y, z, w]";
    case ValueType::Bool: return "true or false";
    case ValueType::Enum: return "one of " + join_alternatives(choices);
    case ValueType::String: return "a string";
    case ValueType::Object: return "an object";
    case ValueType::Interface:
    case ValueType::Medium:
    case ValueType::Stack: return "a link to " + std::string(type_name(type)) + " node such as \"@id\"";
  }
  return "?";
}

const ParamDecl* find_param(const std::vector<ParamDecl>& params, std::string_view name) {
  for (const auto& p : params)
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<std::string> param_names(const std::vector<ParamDecl>& params) {
  std::vector<std::string> names;
  for (const auto& p : params) names.push_back(p.name);
  return names;
}

const ParamDecl* NodeDecl::find_param(std::string_view name) const { return lamina::find_param(params, name); }

const OutputDecl* NodeDecl::find_output(std::string_view name) const {
  if (outputs.empty()) return nullptr;
  if (name.empty()) return &outputs.front();
  for (const auto& o : outputs)
    if (o.name == name) return &o;
  return nullptr;
}

bool NodeDecl::in_alternative(std::string_view name) const {
  for (const auto& alt : alternatives)
    for (const auto& set : alt.sets)
      for (const auto& member : set)
        if (member == name) return true;
  return false;
}

std::vector<std::string> NodeDecl::param_names() const { return lamina::param_names(params); }

std::vector<std::string> NodeDecl::output_names() const {
  std::vector<std::string> names;
  for (const auto& o : outputs) names.push_back(o.name);
  return names;
}

const Value* NodeCheckContext::get(std::string_view name) const { return node.find(name); }

std::optional<double> NodeCheckContext::constant_channel(std::string_view name, int channel, double fallback) const {
  const Value* v = get(name);
  if (!v) return fallback;
  if (std::holds_alternative<Link>(*v)) return std::nullopt;
  const std::vector<double> numbers = value_numbers(*v);
  if (numbers.size() == 1) return numbers[0];
  if (numbers.size() == 3) return numbers[size_t(channel)];
  return std::nullopt;
}

void NodeCheckContext::error(std::string_view param_name, std::string message, std::string hint) const {
  std::string pointer = param_name.empty() ? node_pointer : pointer_append(node_pointer, param_name);
  diagnostics.error(file, std::move(pointer), std::move(message), std::move(hint));
}

}  // namespace lamina
