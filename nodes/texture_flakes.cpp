// texture/flakes: Elek's metal flake normals (Elek 2010, sec. 4.1), for a metallic paint's base:
// one random normal per cell of a fine grid, fading towards +z with the viewer's distance. Link
// its normal to the conductor's `normal`, under the coat, so that only the lower layer sparkles.
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"
#include "nodes/procedural_params.h"

namespace lamina {

// Inputs: scale. Choices: space, seed. Output: normal.
static void lower_flakes(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("scale")};
  op.choices = {n.choice("space"), static_cast<int>(n.number("seed"))};
}

static void run_flakes(const TextureOp& op, const ShadingContext& ctx, float* r) {
  const glm::vec3 p = kernels::lamina_space_point(ctx.uv, ctx.position, op.choices[0], read_float(op.inputs[0], r));
  write_vec3(r, op.outputs[0],
             kernels::lamina_flake_normal(p, static_cast<unsigned>(op.choices[1]), ctx.view_distance));
}

static void emit_flakes(const TextureOp& op, glsl::OpWriter& w) {
  const std::string p = "lamina_space_point(" + w.context("uv") + ", " + w.context("position") + ", " +
                        std::to_string(op.choices[0]) + ", " + w.input(op, 0) + ")";
  w.output(op, 0,
           "lamina_flake_normal(" + p + ", " + seed_literal(op.choices[1]) + ", " + w.context("view_distance") + ")");
}

NodeDecl declare_texture_flakes() {
  NodeDecl d;
  d.type = "texture/flakes";
  d.kind = NodeKind::Texture;
  d.doc =
      "Elek's metal flakes: per cell a random colour c, read unfiltered; normal = normalize(max(view distance, 1) "
      "(0, 0, 1) + 2 c - 1)";
  add_space_params(d, 1000.0);
  add_seed_param(d);
  d.outputs.push_back({"normal", ValueType::Vec3, "the flake's unit normal in tangent space, for a base's normal"});
  d.lower = lower_flakes;
  d.run = run_flakes;
  d.emit_glsl = emit_flakes;
  d.uv_detail = space_uv_detail;  // flakes per uv unit
  d.varies = true;
  return d;
}

}  // namespace lamina
