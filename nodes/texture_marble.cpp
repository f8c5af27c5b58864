// texture/marble: Perlin's marble, stripes displaced by turbulence ("An Image Synthesizer", SIGGRAPH
// 1985, sec. 5); the course's aventurescent stones switch between surface maps with it (course
// sec. 5.2.1).
#include <algorithm>
#include <cmath>

#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"
#include "nodes/procedural_params.h"

namespace lamina {

// Inputs: scale, direction, stripes, strength, lacunarity, gain. Choices: space, octaves, seed.
static void lower_marble(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("scale"),    n.input("direction"),  n.input("stripes"),
               n.input("strength"), n.input("lacunarity"), n.input("gain")};
  op.choices = {n.choice("space"), static_cast<int>(n.number("octaves")), static_cast<int>(n.number("seed"))};
}

static void run_marble(const TextureOp& op, const ShadingContext& ctx, float* r) {
  const glm::vec3 p = kernels::lamina_space_point(ctx.uv, ctx.position, op.choices[0], 1.0f);
  write_float(r, op.outputs[0],
              kernels::lamina_marble_value(
                  p, read_float(op.inputs[0], r), read_vec3(op.inputs[1], r), read_float(op.inputs[2], r),
                  read_float(op.inputs[3], r), op.choices[1], read_float(op.inputs[4], r), read_float(op.inputs[5], r),
                  static_cast<unsigned>(op.choices[2]), kernels::lamina_space_footprint(ctx.footprint, op.choices[0])));
}

static void emit_marble(const TextureOp& op, glsl::OpWriter& w) {
  const std::string p = w.local(op, "p", "vec3",
                                "lamina_space_point(" + w.context("uv") + ", " + w.context("position") + ", " +
                                    std::to_string(op.choices[0]) + ", 1.0f)");
  w.output(op, 0,
           "lamina_marble_value(" + p + ", " + w.input(op, 0) + ", " + w.input(op, 1) + ", " + w.input(op, 2) + ", " +
               w.input(op, 3) + ", " + std::to_string(op.choices[1]) + ", " + w.input(op, 4) + ", " + w.input(op, 5) +
               ", " + seed_literal(op.choices[2]) + ", " + space_footprint(op.choices[0], w) + ")");
}

// The finer of the turbulence's highest octave (scale lacunarity^(octaves - 1) cells per uv unit)
// and the stripes along u or v (stripes times the direction's component).
static float uv_detail_marble(const TextureOp& op) {
  if (op.choices[0] != 0) return 0.0f;
  const float turbulence = space_uv_detail(op) * std::pow(op.inputs[4].largest(), float(op.choices[1] - 1));
  const glm::vec3 direction = op.inputs[1].linked() ? glm::vec3(1.0f) : glm::abs(op.inputs[1].constant);
  return std::max(turbulence, op.inputs[2].largest() * std::max(direction.x, direction.y));
}

NodeDecl declare_texture_marble() {
  NodeDecl d;
  d.type = "texture/marble";
  d.kind = NodeKind::Texture;
  d.doc =
      "Perlin's marble: 0.5 + 0.5 sin(2 pi (stripes dot(p, direction) + strength turbulence(scale p))), "
      "in [0, 1]";
  add_space_params(d, 4.0);
  d.params.push_back(param("direction", ValueType::Vec3)
                         .range(-1.0, 1.0)
                         .or_default(Vec3d{1.0, 0.0, 0.0})
                         .described("the stripes run across this vector; its length multiplies stripes (uv space "
                                    "reads x and y)"));
  d.params.push_back(param("stripes", ValueType::Float)
                         .range(0.0, 1.0e6)
                         .or_default(2.0)
                         .described("stripes per unit of uv or of position along direction"));
  d.params.push_back(param("strength", ValueType::Float)
                         .range(0.0, 100.0)
                         .or_default(1.0)
                         .described("how far the turbulence (in [0, 1]) displaces the stripes, in stripe periods"));
  add_fractal_params(d);
  add_seed_param(d);
  d.outputs.push_back({"value", ValueType::Float, "the marble in [0, 1]"});
  d.lower = lower_marble;
  d.run = run_marble;
  d.emit_glsl = emit_marble;
  d.uv_detail = uv_detail_marble;
  d.varies = true;
  return d;
}

}  // namespace lamina
