// The node types lamina knows. The built-in set is listed in nodes/node_list.inc, one line each.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "graph/node_decl.h"

namespace lamina {

class NodeRegistry {
 public:
  static const NodeRegistry& builtin();

  void add(NodeDecl decl);  // a duplicate type is a programming error and throws
  const NodeDecl* find(std::string_view type) const;
  const std::vector<NodeDecl>& all() const { return decls_; }  // sorted by type
  std::vector<std::string> type_names() const;

 private:
  std::vector<NodeDecl> decls_;
};

}  // namespace lamina
