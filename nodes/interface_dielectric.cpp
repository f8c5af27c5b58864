// interface/dielectric: a rough or smooth boundary into a transparent layer (course sec. 2.1).
#include "nodes/kernels/kernels.h"
#include "nodes/microfacet_params.h"
#include "nodes/normal_param.h"

namespace lamina {

static void lower_dielectric(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.model = kernels::LAMINA_INTERFACE_DIELECTRIC;
  e.interface_decl = &n.decl();
  e.interface_node = n.id();
  e.scalar_x = n.input("ior");
  lower_microfacet_params(n);
  lower_normal_param(n);
}

NodeDecl declare_interface_dielectric() {
  NodeDecl d;
  d.type = "interface/dielectric";
  d.kind = NodeKind::Interface;
  d.doc = "Torrance-Sparrow boundary between the medium above and a transparent layer below";
  d.params.push_back(param("ior", ValueType::Float)
                         .range(1.0, 4.0)
                         .links()
                         .described("absolute index of refraction of the layer below the boundary"));
  add_microfacet_params(d);
  add_normal_param(d);
  d.outputs.push_back({"interface", ValueType::Interface, "the boundary, for a layer's interface input"});
  d.lower = lower_dielectric;
  return d;
}

}  // namespace lamina
