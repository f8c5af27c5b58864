// texture/noise: gradient noise and its fractal sums (fBm, turbulence) over uv or position, for
// grey maps such as where patina grows (Elek sec. 4.2).
#include <algorithm>
#include <cmath>

#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"
#include "nodes/procedural_params.h"

namespace lamina {

// Inputs: scale, lacunarity, gain. Choices: space (uv 0, position 1), octaves, seed, turbulence
// (1 or 0).
static void lower_noise(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("scale"), n.input("lacunarity"), n.input("gain")};
  op.choices = {n.choice("space"), static_cast<int>(n.number("octaves")), static_cast<int>(n.number("seed")),
                n.text("mode") == "turbulence" ? 1 : 0};
}

static void run_noise(const TextureOp& op, const ShadingContext& ctx, float* r) {
  const float scale = read_float(op.inputs[0], r);
  const glm::vec3 p = kernels::lamina_space_point(ctx.uv, ctx.position, op.choices[0], scale);
  const float footprint = kernels::lamina_space_footprint(ctx.footprint, op.choices[0]) * scale;
  write_float(r, op.outputs[0],
              kernels::lamina_noise_value(p, op.choices[1], read_float(op.inputs[1], r), read_float(op.inputs[2], r),
                                          static_cast<unsigned>(op.choices[2]), op.choices[3] != 0, footprint));
}

static void emit_noise(const TextureOp& op, glsl::OpWriter& w) {
  const std::string p = w.local(op, "p", "vec3",
                                "lamina_space_point(" + w.context("uv") + ", " + w.context("position") + ", " +
                                    std::to_string(op.choices[0]) + ", " + w.input(op, 0) + ")");
  w.output(op, 0,
           "lamina_noise_value(" + p + ", " + std::to_string(op.choices[1]) + ", " + w.input(op, 1) + ", " +
               w.input(op, 2) + ", " + seed_literal(op.choices[2]) + ", " + (op.choices[3] ? "true" : "false") + ", " +
               space_footprint(op.choices[0], w) + " * " + w.input(op, 0) + ")");
}

// The highest octave's cells per uv unit: scale lacunarity^(octaves - 1).
static float uv_detail_noise(const TextureOp& op) {
  return space_uv_detail(op) * std::pow(op.inputs[1].largest(), float(op.choices[1] - 1));
}

NodeDecl declare_texture_noise() {
  NodeDecl d;
  d.type = "texture/noise";
  d.kind = NodeKind::Texture;
  d.doc =
      "gradient (Perlin) noise summed over octaves: fBm, 0.5 + 0.5 sum / sum of amplitudes, or turbulence, "
      "the sum of |noise|; deterministic integer hashing, the same on every back end";
  add_space_params(d, 4.0);
  d.params.push_back(
      param("mode", ValueType::Enum)
          .one_of_described({{"fbm", "fractional Brownian motion: smooth clouds around 0.5"},
                             {"turbulence", "the sum of |noise|: creased veins, dark along the creases"}})
          .or_default(std::string("fbm"))
          .described("which fractal sum"));
  add_fractal_params(d);
  add_seed_param(d);
  d.outputs.push_back({"value", ValueType::Float, "the noise in [0, 1]"});
  d.lower = lower_noise;
  d.run = run_noise;
  d.emit_glsl = emit_noise;
  d.uv_detail = uv_detail_noise;
  d.varies = true;
  return d;
}

}  // namespace lamina
