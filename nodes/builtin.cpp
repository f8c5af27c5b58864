// Builds the registry of built-in node types from nodes/node_list.inc.
#include "graph/registry.h"

namespace lamina {

#define LAMINA_NODE(name) NodeDecl declare_##name();
#include "nodes/node_list.inc"
#undef LAMINA_NODE

const NodeRegistry& NodeRegistry::builtin() {
  static const NodeRegistry registry = [] {
    NodeRegistry r;
#define LAMINA_NODE(name) r.add(declare_##name());
#include "nodes/node_list.inc"
#undef LAMINA_NODE
    return r;
  }();
  return registry;
}

}  // namespace lamina
