// Roughness, distribution and Fresnel parameters shared by every microfacet node (interfaces, conductors).
#pragma once

#include "graph/lowering.h"
#include "graph/node_decl.h"

namespace lamina {

// Course convention: roughness is the RMS microfacet slope angle; m = tan(roughness_deg).
// 45 degrees (m = 1) bounds both forms; the course's roughest example is 35 degrees.
inline constexpr double kMaxRoughnessDeg = 45.0;
inline constexpr double kMaxAlpha = 1.0;

// Adds roughness_deg | alpha (at most one; default: smooth), distribution and, with `fresnel`, the
// choice of the Fresnel term's form to `decl`. Every microfacet node has a Fresnel term, so that
// choice is declared here, once; a node whose term is its own (substrate/thin_film) goes without.
void add_microfacet_params(NodeDecl& decl, bool fresnel = true);

// Lowers those parameters into the node's stack entry: the distribution and Fresnel term as the
// kernels number them (a node without the choice keeps the entry's), the roughness as the entry's
// scalars.y with its unit.
void lower_microfacet_params(NodeLowering& node);

}  // namespace lamina
