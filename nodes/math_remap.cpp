// math/remap: maps [in_min, in_max] linearly onto [out_min, out_max], optionally clamped.
#include "graph/diagnostics.h"
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

static void check_remap(const NodeCheckContext& ctx) {
  const Value* lo = ctx.get("in_min");
  const Value* hi = ctx.get("in_max");
  double in_min = lo && std::holds_alternative<double>(*lo) ? std::get<double>(*lo) : 0.0;
  double in_max = hi && std::holds_alternative<double>(*hi) ? std::get<double>(*hi) : 1.0;
  if (in_min == in_max)
    ctx.error(hi ? "in_max" : "in_min", "in_min and in_max are equal, so the input range is empty",
              "make in_max differ from in_min");
}

// Inputs: value, in_min, in_max, out_min, out_max. Choices: clamp (1 or 0).
static void lower_remap(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("value"), n.input("in_min"), n.input("in_max"), n.input("out_min"), n.input("out_max")};
  op.choices = {n.flag("clamp") ? 1 : 0};
}

static void run_remap(const TextureOp& op, const ShadingContext&, float* r) {
  write_float(
      r, op.outputs[0],
      kernels::remap_value(read_float(op.inputs[0], r), read_float(op.inputs[1], r), read_float(op.inputs[2], r),
                           read_float(op.inputs[3], r), read_float(op.inputs[4], r), op.choices[0] != 0));
}

static void emit_remap(const TextureOp& op, glsl::OpWriter& w) {
  w.output(op, 0,
           "remap_value(" + w.input(op, 0) + ", " + w.input(op, 1) + ", " + w.input(op, 2) + ", " + w.input(op, 3) +
               ", " + w.input(op, 4) + ", " + (op.choices[0] ? "true" : "false") + ")");
}

NodeDecl declare_math_remap() {
  NodeDecl d;
  d.type = "math/remap";
  d.kind = NodeKind::Math;
  d.doc = "out_min + (value - in_min) / (in_max - in_min) * (out_max - out_min)";
  d.params.push_back(param("value", ValueType::Float).links().described("the input"));
  d.params.push_back(param("in_min", ValueType::Float).or_default(0.0).described("input mapped to out_min"));
  d.params.push_back(param("in_max", ValueType::Float).or_default(1.0).described("input mapped to out_max"));
  d.params.push_back(param("out_min", ValueType::Float).or_default(0.0).described("output at in_min"));
  d.params.push_back(param("out_max", ValueType::Float).or_default(1.0).described("output at in_max"));
  d.params.push_back(param("clamp", ValueType::Bool)
                         .or_default(true)
                         .described("clamp the output to [min(out_min, out_max), max(out_min, out_max)]"));
  d.outputs.push_back({"value", ValueType::Float, "the remapped value"});
  d.check = check_remap;
  d.lower = lower_remap;
  d.run = run_remap;
  d.emit_glsl = emit_remap;
  return d;
}

}  // namespace lamina
