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
ParamDecl& ParamDecl::in_unit(std::string u) {
  unit = std::move(u);
  return *this;
}
ParamDecl& ParamDecl::or_default(Value v) {
  fallback = std::move(v);
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

std::string ParamDecl::range_text() const {
  std::string out;
  if (std::isfinite(lo)) out += number_text(lo) + (lo_open ? " < " : " <= ");
  out += name;
  if (std::isfinite(hi)) out += " <= " + number_text(hi);
  return out;
}

const ParamDecl* NodeDecl::find_param(std::string_view name) const {
  for (const auto& p : params)
    if (p.name == name) return &p;
  return nullptr;
}

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

std::vector<std::string> NodeDecl::param_names() const {
  std::vector<std::string> names;
  for (const auto& p : params) names.push_back(p.name);
  return names;
}

std::vector<std::string> NodeDecl::output_names() const {
  std::vector<std::string> names;
  for (const auto& o : outputs) names.push_back(o.name);
  return names;
}

const Value* NodeCheckContext::get(std::string_view name) const { return node.find(name); }

void NodeCheckContext::error(std::string_view param_name, std::string message, std::string hint) const {
  std::string pointer = param_name.empty() ? node_pointer : pointer_append(node_pointer, param_name);
  diagnostics.error(file, std::move(pointer), std::move(message), std::move(hint));
}

}  // namespace lamina
