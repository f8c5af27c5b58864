// medium/clear: a layer's bulk that neither absorbs nor scatters.
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

static void lower_clear(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.medium = kernels::LAMINA_MEDIUM_CLEAR;
  e.medium_decl = &n.decl();
  e.medium_node = n.id();
}

static Tint clear_tint(const Graph&, size_t) { return {false, "clear"}; }

NodeDecl declare_medium_clear() {
  NodeDecl d;
  d.type = "medium/clear";
  d.kind = NodeKind::Medium;
  d.doc = "transparent bulk with no absorption; a layer without a medium input uses it";
  d.outputs.push_back({"medium", ValueType::Medium, "the bulk, for a layer's medium input"});
  d.lower = lower_clear;
  d.tint = clear_tint;
  return d;
}

}  // namespace lamina
