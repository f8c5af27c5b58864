// substrate/lambert: an ideal diffuse opaque base, f = albedo / pi.
#include "graph/node_decl.h"

namespace lamina {

NodeDecl declare_substrate_lambert() {
  NodeDecl d;
  d.type = "substrate/lambert";
  d.kind = NodeKind::Substrate;
  d.doc = "ideal diffuse opaque base";
  d.params.push_back(param("albedo", ValueType::Color)
                         .range(0.0, 1.0)
                         .links()
                         .described("diffuse reflectance per channel (linear RGB)"));
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  return d;
}

}  // namespace lamina
