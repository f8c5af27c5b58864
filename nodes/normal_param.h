// The `normal` parameter every interface and substrate takes: the direction its frame is tilted to.
#pragma once

#include "graph/lowering.h"
#include "graph/node_decl.h"

namespace lamina {

// Adds `normal` (a vec3 in tangent space, +z the surface's normal; linkable) to `decl`.
void add_normal_param(NodeDecl& decl);

// Lowers it into the node's stack entry's frame slot (StackEntry::normal).
void lower_normal_param(NodeLowering& node);

}  // namespace lamina
