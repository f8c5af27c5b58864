#include "nodes/procedural_params.h"

namespace lamina {

void add_space_params(NodeDecl& decl, double scale) {
  // The choices in the order of lamina_space_point's codes.
  decl.params.push_back(param("space", ValueType::Enum)
                            .one_of_described({{"uv", "the texture coordinates (u, v): a 2D pattern"},
                                               {"position", "the world-space position: a 3D pattern, as if carved"}})
                            .or_default(std::string("uv"))
                            .described("where the pattern is read"));
  decl.params.push_back(param("scale", ValueType::Float)
                            .range(1.0e-6, 1.0e6)
                            .or_default(scale)
                            .described("features (noise cells, Voronoi cells) per unit of uv or of position"));
}

void add_fractal_params(NodeDecl& decl) {
  decl.params.push_back(param("octaves", ValueType::Integer)
                            .range(1.0, kMaxOctaves)
                            .or_default(4.0)
                            .described("noise octaves summed; each costs as much as the first"));
  decl.params.push_back(param("lacunarity", ValueType::Float)
                            .range(1.0, 8.0)
                            .or_default(2.0)
                            .described("frequency ratio of successive octaves"));
  decl.params.push_back(param("gain", ValueType::Float)
                            .range(0.0, 1.0)
                            .or_default(0.5)
                            .described("amplitude ratio of successive octaves (0.5: each octave half as strong)"));
}

void add_seed_param(NodeDecl& decl) {
  decl.params.push_back(param("seed", ValueType::Integer)
                            .range(0.0, kMaxSeed)
                            .or_default(0.0)
                            .described("chooses an independent pattern: the same seed gives the same pattern "
                                       "on every back end"));
}

std::string space_footprint(int space, glsl::OpWriter& w) {
  return "lamina_space_footprint(" + w.context("footprint") + ", " + std::to_string(space) + ")";
}

float space_uv_detail(const TextureOp& op) { return op.choices[0] == 0 ? op.inputs[0].largest() : 0.0f; }

std::string seed_literal(int seed) { return std::to_string(static_cast<unsigned>(seed)) + "u"; }

}  // namespace lamina
