#include "graph/lowering.h"

#include <algorithm>
#include <stdexcept>

namespace lamina {

const std::string& NodeLowering::id() const { return graph_.node(node_).id; }

bool NodeLowering::given(std::string_view param) const { return graph_.node(node_).find(param) != nullptr; }

const Value& NodeLowering::value(std::string_view param) const {
  const Value* v = graph_.value(node_, param);
  if (!v) throw std::logic_error("compile: " + id() + " has no value for " + std::string(param));
  return *v;
}

double NodeLowering::number(std::string_view param) const { return std::get<double>(value(param)); }

glm::vec2 NodeLowering::vec2(std::string_view param) const {
  const auto& v = std::get<Vec2d>(value(param));
  return glm::vec2(float(v[0]), float(v[1]));
}

bool NodeLowering::flag(std::string_view param) const { return std::get<bool>(value(param)); }

const std::string& NodeLowering::text(std::string_view param) const { return std::get<std::string>(value(param)); }

int NodeLowering::choice(std::string_view param) const {
  const ParamDecl* p = decl().find_param(param);
  const std::string& chosen = text(param);
  const auto it = std::find(p->choices.begin(), p->choices.end(), chosen);
  if (it == p->choices.end()) throw std::logic_error("compile: " + id() + ": unknown " + std::string(param));
  return int(it - p->choices.begin());
}

StackEntry& NodeLowering::entry() const {
  if (!entry_) throw std::logic_error("compile: " + id() + " is not part of a stack");
  return *entry_;
}

bool NodeLowering::lower_linked(std::string_view param) const {
  const std::optional<size_t> j = linked(param);
  if (!j) return false;
  const NodeDecl& part = graph_.decl(*j);
  if (!part.lower) throw std::logic_error("compile: " + part.type + " has no lowering");
  NodeLowering sub(graph_, *j, file_, policy_, inputs_, &entry(), nullptr);
  part.lower(sub);
  return true;
}

TextureOp& NodeLowering::op() const {
  if (!op_) throw std::logic_error("compile: " + id() + " is not a texture or math node");
  return *op_;
}

void NodeLowering::fail(const std::string& what) const { throw IoError(file_ + ": " + what); }

}  // namespace lamina
