// Named metals: complex index of refraction n + ik per RGB channel.
#pragma once

#include <span>
#include <string_view>

#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/value.h"

namespace lamina {

// The largest n and k a conductor takes. Measured metals stay far below it in the visible (n < 10,
// k < 15); the exact Fresnel term squares products of n and k, which overflow float near 1e19.
inline constexpr double kMaxConductorIndex = 1000.0;

struct Metal {
  std::string_view name;
  Vec3d n;
  Vec3d k;
  std::string_view source;
};

std::span<const Metal> metals();
const Metal* find_metal(std::string_view name);

// A metal-like base's index: `metal` (a named one) or `n` and `k`, declared once for every node
// with such a base (substrate/conductor, substrate/thin_film), and lowered into the entry's colour0
// (n) and colour1 (k).
void add_metal_params(NodeDecl& decl);
void lower_metal_params(NodeLowering& node);

}  // namespace lamina
