// texture/voronoi: Worley's cellular texture ("A Cellular Texture Basis Function", SIGGRAPH 1996) on
// a jittered grid, with per-cell random values, colours and tilted normals: the surface and glitter
// maps of the course's aventurescent stones (course sec. 5.2.1, fig. 5.2).
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"
#include "nodes/procedural_params.h"

namespace lamina {

// Inputs: scale, jitter, tilt_deg. Choices: space, seed, tilt distribution (0 Beckmann, 2 GGX).
// Outputs: value, color, f1, f2, edge, normal, coverage.
static void lower_voronoi(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("scale"), n.input("jitter"), n.input("tilt_deg")};
  op.choices = {n.choice("space"), static_cast<int>(n.number("seed")), n.text("tilt_distribution") == "ggx" ? 2 : 0};
}

static void run_voronoi(const TextureOp& op, const ShadingContext& ctx, float* r) {
  const float scale = read_float(op.inputs[0], r);
  const glm::vec3 p = kernels::lamina_space_point(ctx.uv, ctx.position, op.choices[0], scale);
  const float footprint = kernels::lamina_space_footprint(ctx.footprint, op.choices[0]) * scale;
  const kernels::LaminaVoronoi v = kernels::lamina_voronoi_cell(p, op.choices[0] == 1, read_float(op.inputs[1], r),
                                                                static_cast<unsigned>(op.choices[1]),
                                                                read_float(op.inputs[2], r), op.choices[2], footprint);
  write_float(r, op.outputs[0], v.value);
  write_vec3(r, op.outputs[1], v.colour);
  write_float(r, op.outputs[2], v.distances.x);
  write_float(r, op.outputs[3], v.distances.y);
  write_float(r, op.outputs[4], v.distances.y - v.distances.x);
  write_vec3(r, op.outputs[5], v.normal);
  write_float(r, op.outputs[6], v.coverage);
}

static void emit_voronoi(const TextureOp& op, glsl::OpWriter& w) {
  const std::string p = w.local(op, "p", "vec3",
                                "lamina_space_point(" + w.context("uv") + ", " + w.context("position") + ", " +
                                    std::to_string(op.choices[0]) + ", " + w.input(op, 0) + ")");
  const std::string v =
      w.local(op, "cells", "LaminaVoronoi",
              "lamina_voronoi_cell(" + p + ", " + (op.choices[0] == 1 ? "true" : "false") + ", " + w.input(op, 1) +
                  ", " + seed_literal(op.choices[1]) + ", " + w.input(op, 2) + ", " + std::to_string(op.choices[2]) +
                  ", " + space_footprint(op.choices[0], w) + " * " + w.input(op, 0) + ")");
  w.output(op, 0, v + ".value");
  w.output(op, 1, v + ".colour");
  w.output(op, 2, v + ".distances.x");
  w.output(op, 3, v + ".distances.y");
  w.output(op, 4, v + ".distances.y - " + v + ".distances.x");
  w.output(op, 5, v + ".normal");
  w.output(op, 6, v + ".coverage");
}

NodeDecl declare_texture_voronoi() {
  NodeDecl d;
  d.type = "texture/voronoi";
  d.kind = NodeKind::Texture;
  d.doc =
      "Voronoi cells of one jittered feature point per unit cell: distances to the nearest points (F1, F2) "
      "and the nearest cell's random value, colour and tilted normal";
  add_space_params(d, 8.0);
  d.params.push_back(param("jitter", ValueType::Float)
                         .range(0.0, 1.0)
                         .or_default(0.9)
                         .described("how far feature points stray from their cell's centre, as a fraction of the "
                                    "cell: 0 a regular grid; up to 0.75 the 3x3 cells searched hold F1 and F2 "
                                    "exactly, beyond it F2 rarely (README, Textures)"));
  d.params.push_back(param("tilt_deg", ValueType::Float)
                         .range(0.0, 60.0)
                         .in_unit("degrees")
                         .or_default(0.0)
                         .described("RMS slope angle of the cells' normals, m = tan(tilt_deg): glitter facets tilt "
                                    "1 to 5 degrees (course sec. 5.2.1)"));
  d.params.push_back(param("tilt_distribution", ValueType::Enum)
                         .one_of_described({{"beckmann", "Gaussian slopes (Walter et al. 2007, eq. 28)"},
                                            {"ggx", "GGX slopes, a longer tail (Walter et al. 2007, eq. 35)"}})
                         .or_default(std::string("beckmann"))
                         .described("the distribution of the cells' normals"));
  add_seed_param(d);
  d.outputs.push_back({"value", ValueType::Float, "the nearest cell's random value, uniform in [0, 1)"});
  d.outputs.push_back({"color", ValueType::Color, "the nearest cell's random colour, uniform in [0, 1)^3"});
  d.outputs.push_back({"f1", ValueType::Float, "distance to the nearest feature point, in cells"});
  d.outputs.push_back({"f2", ValueType::Float, "distance to the second nearest feature point, in cells"});
  d.outputs.push_back({"edge", ValueType::Float, "f2 - f1: 0 on the borders between cells"});
  d.outputs.push_back({"normal", ValueType::Vec3,
                       "the nearest cell's unit normal in tangent space, +z untilted; where the pixel covers many "
                       "cells, their mean, whose length below 1 widens the lobe it tilts"});
  d.outputs.push_back({"coverage", ValueType::Float,
                       "how much of the pattern the pixel averages: 0 up to half a cell per pixel, 1 from two "
                       "cells on; link a select's coverage"});
  d.lower = lower_voronoi;
  d.run = run_voronoi;
  d.emit_glsl = emit_voronoi;
  d.uv_detail = space_uv_detail;  // cells per uv unit
  d.varies = true;
  return d;
}

}  // namespace lamina
