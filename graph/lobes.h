// The lobes of a compiled material: one per interface and one per substrate, per path through
// the mixes: the stack entries that are not mixes, in the stack's depth-first order. Importance
// sampling chooses between them (course sec. 3.2.3); the CPU evaluator and the GLSL back end both
// walk the stack through the kernels' composition, so both see the same lobes in one order.
#pragma once

#include <string>
#include <vector>

#include "graph/program.h"

namespace lamina {

struct Lobe {
  int entry;         // its index in Program::stack
  std::string name;  // by kind and depth: "interface 0", "substrate 1 (conductor)"
};

std::vector<Lobe> collect_lobes(const Program& program);

}  // namespace lamina
