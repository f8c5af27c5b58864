// Parameters shared by the procedural texture nodes (texture/noise, texture/marble,
// texture/voronoi): where they read the shading point, how fine they are, their fractal sum and
// their seed; declared once so that every node documents and checks them alike.
#pragma once

#include <string>

#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"

namespace lamina {

// Octaves of a fractal sum: each costs one gradient noise (8 hashed lattice corners); 12 octaves of
// lacunarity 2 span 4096:1 in frequency, finer than any texel the coarsest octave covers.
inline constexpr double kMaxOctaves = 12.0;
// Seeds are whole numbers up to this; the kernels take them as 32-bit unsigned integers.
inline constexpr double kMaxSeed = 1.0e9;

// Adds space (uv | position) and scale (features per unit, default `scale`).
void add_space_params(NodeDecl& decl, double scale);
// Adds octaves, lacunarity and gain of a fractal sum.
void add_fractal_params(NodeDecl& decl);
// Adds seed.
void add_seed_param(NodeDecl& decl);

// The footprint a node of `space` filters over, as GLSL: lamina_space_footprint of the context's.
std::string space_footprint(int space, glsl::OpWriter& w);

// The uv detail (NodeDecl::uv_detail) of a node whose lowering puts `space` first among its choices
// and `scale` first among its inputs: scale features per uv unit over uv, 0 over position.
float space_uv_detail(const TextureOp& op);

// The GLSL literal of a seed (an unsigned integer) as the node's lowering stored it.
std::string seed_literal(int seed);

}  // namespace lamina
