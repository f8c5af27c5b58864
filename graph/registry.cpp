#include "graph/registry.h"

#include <algorithm>
#include <stdexcept>

namespace lamina {

void NodeRegistry::add(NodeDecl decl) {
  if (find(decl.type)) throw std::logic_error("node type registered twice: " + decl.type);
  if (decl.outputs.empty()) throw std::logic_error("node type has no output: " + decl.type);
  auto at = std::lower_bound(decls_.begin(), decls_.end(), decl.type,
                             [](const NodeDecl& d, const std::string& t) { return d.type < t; });
  decls_.insert(at, std::move(decl));
}

const NodeDecl* NodeRegistry::find(std::string_view type) const {
  auto at = std::lower_bound(decls_.begin(), decls_.end(), type,
                             [](const NodeDecl& d, std::string_view t) { return d.type < t; });
  return (at != decls_.end() && at->type == type) ? &*at : nullptr;
}

std::vector<std::string> NodeRegistry::type_names() const {
  std::vector<std::string> names;
  for (const auto& d : decls_) names.push_back(d.type);
  return names;
}

}  // namespace lamina
