// math/mix: a linear blend of two colours, (1 - factor) a + factor b, e.g. the tarnish tint of
// copper under patina (Elek sec. 4.2) or a cell colour between two pigments.
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// Inputs: a, b, factor.
static void lower_math_mix(NodeLowering& n) { n.op().inputs = {n.input("a"), n.input("b"), n.input("factor")}; }

static void run_math_mix(const TextureOp& op, const ShadingContext&, float* r) {
  write_vec3(r, op.outputs[0],
             glm::mix(read_vec3(op.inputs[0], r), read_vec3(op.inputs[1], r), read_float(op.inputs[2], r)));
}

static void emit_math_mix(const TextureOp& op, glsl::OpWriter& w) {
  w.output(op, 0, "mix(" + w.input(op, 0) + ", " + w.input(op, 1) + ", " + w.input(op, 2) + ")");
}

NodeDecl declare_math_mix() {
  NodeDecl d;
  d.type = "math/mix";
  d.kind = NodeKind::Math;
  d.doc = "(1 - factor) a + factor b, per colour channel";
  d.params.push_back(param("a", ValueType::Color)
                         .range(0.0, 1000.0)
                         .or_default(Vec3d{0.0, 0.0, 0.0})
                         .links()
                         .described("the colour where factor is 0 (any non-negative triple: also a conductor's n "
                                    "or k, up to 1000 as theirs)"));
  d.params.push_back(param("b", ValueType::Color)
                         .range(0.0, 1000.0)
                         .or_default(Vec3d{1.0, 1.0, 1.0})
                         .links()
                         .described("the colour where factor is 1"));
  d.params.push_back(
      param("factor", ValueType::Float).range(0.0, 1.0).links().described("blend factor: 0 gives a, 1 gives b"));
  d.outputs.push_back({"color", ValueType::Color, "the blend"});
  d.lower = lower_math_mix;
  d.run = run_math_mix;
  d.emit_glsl = emit_math_mix;
  return d;
}

}  // namespace lamina
