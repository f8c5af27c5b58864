// medium/clear: a layer's bulk that neither absorbs nor scatters.
#include "graph/node_decl.h"

namespace lamina {

NodeDecl declare_medium_clear() {
  NodeDecl d;
  d.type = "medium/clear";
  d.kind = NodeKind::Medium;
  d.doc = "transparent bulk with no absorption; a layer without a medium input uses it";
  d.outputs.push_back({"medium", ValueType::Medium, "the bulk, for a layer's medium input"});
  return d;
}

}  // namespace lamina
