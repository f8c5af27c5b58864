// medium/absorbing: Bouguer-Lambert-Beer absorption in a layer (course sec. 3.1, Elek sec. 2.2).
#include "graph/node_decl.h"

namespace lamina {

NodeDecl declare_medium_absorbing() {
  NodeDecl d;
  d.type = "medium/absorbing";
  d.kind = NodeKind::Medium;
  d.doc = "tinted bulk: transmittance exp(-absorption * thickness * (1/cos_in + 1/cos_out))";
  d.params.push_back(param("thickness", ValueType::Float)
                         .range(0.0, 1.0e4)
                         .in_unit("micrometres")
                         .links()
                         .described("layer thickness"));
  d.params.push_back(
      param("absorption", ValueType::Color)
          .range(0.0, 1.0e3)
          .in_unit("1/micrometre")
          .links()
          .described("absorption coefficient per channel: an inverse colour (red varnish absorbs green and blue)"));
  d.outputs.push_back({"medium", ValueType::Medium, "the bulk, for a layer's medium input"});
  return d;
}

}  // namespace lamina
