// medium/absorbing: Bouguer-Lambert-Beer absorption in a layer (course sec. 3.1, Elek sec. 2.2).
#include <cmath>

#include "graph/classify.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/number_text.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

static void lower_absorbing(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.medium = kernels::LAMINA_MEDIUM_ABSORBING;
  e.medium_decl = &n.decl();
  e.medium_node = n.id();
  e.colour2 = n.input("absorption");
  e.scalar_z = n.input("thickness");
}

// Tinted when the round trip at normal incidence, exp(-2 a d), absorbs more than kTintedAbsorbs in
// some channel (README, "Classification"); textured absorption counts as tinted.
static Tint absorbing_tint(const Graph& g, size_t medium) {
  const Value* thickness = g.value(medium, "thickness");
  const Value* absorption = g.value(medium, "absorption");
  const double* d = thickness ? std::get_if<double>(thickness) : nullptr;
  const Vec3d* a = absorption ? std::get_if<Vec3d>(absorption) : nullptr;
  if (!d || !a) return {true, "textured absorption, taken as tinted"};
  double absorbed = 0.0;
  for (double c : *a) absorbed = std::max(absorbed, 1.0 - std::exp(-2.0 * c * *d));
  const bool tinted = absorbed > kTintedAbsorbs;
  return {tinted, std::string(tinted ? "tinted" : "clear") + " (absorbs up to " +
                      number_text(std::round(absorbed * 1000) / 10) + "% at normal incidence)"};
}

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
  d.lower = lower_absorbing;
  d.tint = absorbing_tint;
  return d;
}

}  // namespace lamina
