// layer: one interface over one medium over a base (course sec. 3.1). Stacks of any depth are
// layers of layers, ending at a substrate.
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// The layer's interface and medium fill its entry; its base becomes the entry below (compile.cpp
// expands every stack parameter). No medium is a clear one.
static void lower_layer(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_LAYER;
  n.lower_linked("interface");
  if (!n.lower_linked("medium")) e.medium = kernels::LAMINA_MEDIUM_CLEAR;
}

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
  d.params.push_back(
      param("base", ValueType::Stack)
          .links()
          .described("what the layer lies on: a layer, a mix or a substrate/* node; over a mix or a select, it lies "
                     "over each of their stacks (compiled as the mix of the layer over each)"));
  d.outputs.push_back({"stack", ValueType::Stack, "the stack, for a layer's base or a material's surface"});
  d.lower = lower_layer;
  return d;
}

}  // namespace lamina
