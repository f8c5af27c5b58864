// substrate/oren_nayar: rough diffuse base with the inter-reflection term (course sec. 3.3.1).
#include <numbers>

#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"
#include "nodes/normal_param.h"

namespace lamina {

static void lower_oren_nayar(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_OREN_NAYAR;
  e.colour0 = n.input("albedo");
  e.scalar_x = n.input("sigma");
  lower_normal_param(n);
}

NodeDecl declare_substrate_oren_nayar() {
  NodeDecl d;
  d.type = "substrate/oren_nayar";
  d.kind = NodeKind::Substrate;
  d.doc = "rough diffuse opaque base (Oren-Nayar with the inter-reflection term); sigma 0 is Lambert";
  d.params.push_back(param("albedo", ValueType::Color)
                         .range(0.0, 1.0)
                         .links()
                         .described("diffuse reflectance per channel (linear RGB)"));
  d.params.push_back(param("sigma", ValueType::Float)
                         .range(0.0, std::numbers::pi / 2.0)
                         .in_unit("radians")
                         .or_default(0.0)
                         .links()
                         .described("standard deviation of the facet slope angle, as in the course's shader"));
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.lower = lower_oren_nayar;
  return d;
}

}  // namespace lamina
