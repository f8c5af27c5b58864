// layer: one interface over one medium over a base (course sec. 3.1). Stacks of any depth are
// layers of layers, ending at a substrate.
#include "graph/node_decl.h"

namespace lamina {

NodeDecl declare_layer() {
  NodeDecl d;
  d.type = "layer";
  d.kind = NodeKind::Layer;
  d.doc = "an interface over a medium over a base (another layer, a mix or a substrate)";
  d.params.push_back(param("interface", ValueType::Interface)
                         .links()
                         .described("the boundary on top of this layer (an interface/* node)"));
  d.params.push_back(param("medium", ValueType::Medium)
                         .links()
                         .or_default(Link{})
                         .described("the layer's bulk (a medium/* node); omitted: medium/clear"));
  d.params.push_back(param("base", ValueType::Stack)
                         .links()
                         .described("what the layer lies on: a layer, a mix or a substrate/* node"));
  d.outputs.push_back({"stack", ValueType::Stack, "the stack, for a layer's base or a material's surface"});
  return d;
}

}  // namespace lamina
