// texture/patina: Elek's patina weight (sec. 4.2), where a grey map says how early patina develops
// and `extent` how far it has grown: k = 1 - smoothstep(extent - transition, extent + transition, p).
// The rest of Elek's patina is built from other nodes (README, Procedural textures): a mix by k of
// the bare and the patinated stack, math/remap of k for the lower roughness and the coat's index,
// math/mix for the tarnish tint.
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// Inputs: map, extent, transition.
static void lower_patina(NodeLowering& n) {
  n.op().inputs = {n.input("map"), n.input("extent"), n.input("transition")};
}

static void run_patina(const TextureOp& op, const ShadingContext&, float* r) {
  write_float(r, op.outputs[0],
              kernels::lamina_patina_weight(read_float(op.inputs[0], r), read_float(op.inputs[1], r),
                                            read_float(op.inputs[2], r)));
}

static void emit_patina(const TextureOp& op, glsl::OpWriter& w) {
  w.output(op, 0, "lamina_patina_weight(" + w.input(op, 0) + ", " + w.input(op, 1) + ", " + w.input(op, 2) + ")");
}

NodeDecl declare_texture_patina() {
  NodeDecl d;
  d.type = "texture/patina";
  d.kind = NodeKind::Texture;
  d.doc =
      "Elek's patina weight (sec. 4.2): 1 - smoothstep(extent - transition, extent + transition, map); 1 is "
      "patina, 0 the bare material";
  d.params.push_back(param("map", ValueType::Float)
                         .range(0.0, 1.0)
                         .links()
                         .described("grey map of where patina develops first (dark) and last (light): an image's "
                                    "value, a noise, ..."));
  d.params.push_back(param("extent", ValueType::Float)
                         .range(-1.0, 2.0)
                         .or_default(0.5)
                         .links()
                         .described("how far the patina has grown: map values below it are patina; from "
                                    "-transition (none) to 1 + transition (all)"));
  d.params.push_back(param("transition", ValueType::Float)
                         .range(0.0, 1.0)
                         .or_default(0.1)
                         .links()
                         .described("half the width of the soft edge, in map units; 0 is a hard edge"));
  d.outputs.push_back({"weight", ValueType::Float, "the patina weight k in [0, 1]"});
  d.lower = lower_patina;
  d.run = run_patina;
  d.emit_glsl = emit_patina;
  return d;
}

}  // namespace lamina
