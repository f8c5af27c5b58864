// substrate/conductor: a rough metal, Torrance-Sparrow with the conductor Fresnel term (exact by
// default; course sec. 2.1). Metals are opaque, so a conductor is always the bottom of a stack.
#include "graph/lowering.h"
#include "nodes/kernels/kernels.h"
#include "nodes/metals.h"
#include "nodes/microfacet_params.h"
#include "nodes/normal_param.h"

namespace lamina {

static void lower_conductor(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_CONDUCTOR;
  lower_metal_params(n);
  lower_microfacet_params(n);
  lower_normal_param(n);
}

NodeDecl declare_substrate_conductor() {
  NodeDecl d;
  d.type = "substrate/conductor";
  d.kind = NodeKind::Substrate;
  d.doc = "rough metal base: a named metal or its complex index of refraction n + ik per channel";
  add_metal_params(d);
  add_microfacet_params(d);
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.lower = lower_conductor;
  d.metal = true;
  return d;
}

}  // namespace lamina
