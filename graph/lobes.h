// The lobes of a compiled material: one per interface and one per substrate, per path through
// the mixes. Importance sampling chooses between them (course sec. 3.2.3); the CPU evaluator
// loops over this list and the GLSL back end unrolls it, so both see the same lobes in one order.
#pragma once

#include <string>
#include <vector>

#include "graph/program.h"

namespace lamina {

struct LobeStep {
  int node;       // a LayerNode or MixNode in Program::stack
  int side = -1;  // for a mix: 0 took a, 1 took b
};

struct Lobe {
  int node;                    // a LayerNode (its interface) or a substrate node
  std::vector<LobeStep> path;  // from the root down to, not including, `node`
  std::string name;            // by kind and depth: "interface 0", "substrate 1 (conductor)"
};

// Depth first from the root: a layer's interface before everything below it, a mix's a before b.
std::vector<Lobe> collect_lobes(const Program& program);

}  // namespace lamina
