// math/smoothstep: a smooth 0-to-1 transition of a float between two edges (the grey-map threshold
// of Elek's patina, sec. 4.2, is 1 - smoothstep(extent - transition, extent + transition, p)).
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// Inputs: value, edge0, edge1.
static void lower_smoothstep(NodeLowering& n) {
  n.op().inputs = {n.input("value"), n.input("edge0"), n.input("edge1")};
}

static void run_smoothstep(const TextureOp& op, const ShadingContext&, float* r) {
  write_float(
      r, op.outputs[0],
      kernels::smoothstep_value(read_float(op.inputs[0], r), read_float(op.inputs[1], r), read_float(op.inputs[2], r)));
}

static void emit_smoothstep(const TextureOp& op, glsl::OpWriter& w) {
  w.output(op, 0, "smoothstep_value(" + w.input(op, 0) + ", " + w.input(op, 1) + ", " + w.input(op, 2) + ")");
}

NodeDecl declare_math_smoothstep() {
  NodeDecl d;
  d.type = "math/smoothstep";
  d.kind = NodeKind::Math;
  d.doc = "t^2 (3 - 2t) with t = clamp((value - edge0) / (edge1 - edge0), 0, 1)";
  d.params.push_back(param("value", ValueType::Float).links().described("the input"));
  d.params.push_back(param("edge0", ValueType::Float)
                         .links()
                         .or_default(0.0)
                         .described("where the output leaves 0 (above edge1: the curve falls instead)"));
  d.params.push_back(param("edge1", ValueType::Float)
                         .links()
                         .or_default(1.0)
                         .described("where the output reaches 1 (equal to edge0: a step at edge0)"));
  d.outputs.push_back({"value", ValueType::Float, "the smoothed value, in [0, 1]"});
  d.lower = lower_smoothstep;
  d.run = run_smoothstep;
  d.emit_glsl = emit_smoothstep;
  return d;
}

}  // namespace lamina
