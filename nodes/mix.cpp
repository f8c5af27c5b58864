// mix: a linear blend of two stacks by a (usually textured) weight, for heterogeneous surfaces
// such as patina (Elek sec. 4.2) and Voronoi surface maps (course sec. 5.2.1).
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// Its stacks a and b become the entries below it, first and second (compile.cpp).
static void lower_mix(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_MIX;
  e.scalar_x = n.input("weight");
}

NodeDecl declare_mix() {
  NodeDecl d;
  d.type = "mix";
  d.kind = NodeKind::Mix;
  d.doc = "blend of two stacks: (1 - weight) * a + weight * b";
  d.params.push_back(
      param("weight", ValueType::Float).range(0.0, 1.0).links().described("blend factor: 0 shows a, 1 shows b"));
  d.params.push_back(param("a", ValueType::Stack).links().described("the stack where weight is 0"));
  d.params.push_back(param("b", ValueType::Stack).links().described("the stack where weight is 1"));
  d.outputs.push_back({"stack", ValueType::Stack, "the blended stack"});
  d.lower = lower_mix;
  return d;
}

}  // namespace lamina
