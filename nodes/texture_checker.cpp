// texture/checker: alternating squares in uv, the classic test pattern.
#include <algorithm>
#include <cmath>

#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// Inputs: color_a, color_b, scale. Outputs: color, value (the declaration's order).
static void lower_checker(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("color_a"), n.input("color_b"), n.input("scale")};
}

static void run_checker(const TextureOp& op, const ShadingContext& ctx, float* r) {
  const float v = kernels::checker_value(ctx.uv, read_vec2(op.inputs[2], r));
  write_vec3(r, op.outputs[0], glm::mix(read_vec3(op.inputs[0], r), read_vec3(op.inputs[1], r), v));
  write_float(r, op.outputs[1], v);
}

static void emit_checker(const TextureOp& op, glsl::OpWriter& w) {
  const std::string v = w.local(op, "v", "float", "checker_value(" + w.context("uv") + ", " + w.input(op, 2) + ")");
  w.output(op, 0, "mix(" + w.input(op, 0) + ", " + w.input(op, 1) + ", " + v + ")");
  w.output(op, 1, v);
}

// Checks per uv unit along the finer axis.
static float uv_detail_checker(const TextureOp& op) { return op.inputs[2].largest(); }

NodeDecl declare_texture_checker() {
  NodeDecl d;
  d.type = "texture/checker";
  d.kind = NodeKind::Texture;
  d.doc = "checkerboard in uv: color_a where floor(u*sx) + floor(v*sy) is even, color_b elsewhere";
  d.params.push_back(param("color_a", ValueType::Color)
                         .range(0.0, 1.0)
                         .or_default(Vec3d{0.0, 0.0, 0.0})
                         .links()
                         .described("colour of the squares that contain uv (0, 0)"));
  d.params.push_back(param("color_b", ValueType::Color)
                         .range(0.0, 1.0)
                         .or_default(Vec3d{1.0, 1.0, 1.0})
                         .links()
                         .described("colour of the other squares"));
  d.params.push_back(param("scale", ValueType::Vec2)
                         .above(0.0)
                         .or_default(Vec2d{8.0, 8.0})
                         .described("squares per unit of u and of v"));
  d.outputs.push_back({"color", ValueType::Color, "color_a or color_b"});
  d.outputs.push_back({"value", ValueType::Float, "0 on color_a squares, 1 on color_b squares"});
  d.lower = lower_checker;
  d.run = run_checker;
  d.emit_glsl = emit_checker;
  d.uv_detail = uv_detail_checker;
  d.varies = true;
  return d;
}

}  // namespace lamina
