// substrate/lambert: an ideal diffuse opaque base, f = albedo / pi.
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"
#include "nodes/normal_param.h"

namespace lamina {

static void lower_lambert(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_LAMBERT;
  e.colour0 = n.input("albedo");
  lower_normal_param(n);
}

NodeDecl declare_substrate_lambert() {
  NodeDecl d;
  d.type = "substrate/lambert";
  d.kind = NodeKind::Substrate;
  d.doc = "ideal diffuse opaque base";
  d.params.push_back(param("albedo", ValueType::Color)
                         .range(0.0, 1.0)
                         .links()
                         .described("diffuse reflectance per channel (linear RGB)"));
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.lower = lower_lambert;
  return d;
}

}  // namespace lamina
