// The kernels' view of a compiled stack (LaminaEntry and LaminaInputs of nodes/kernels/stack.glsl),
// shared by the back ends so that each hands the composition the same numbers.
#pragma once

#include "graph/program.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// An entry as the kernels read it. With fold_slopes, a constant roughness angle is given as its
// slope (see kernel_constants), so the entry reads a slope.
kernels::LaminaEntry kernel_entry(const StackEntry& entry, bool fold_slopes);

// An entry's inputs with every constant filled in (linked inputs hold their constant, 0, until a
// shading point reads their registers). With fold_slopes, a constant roughness angle becomes its
// slope here, once (lamina_slope calls tan); lamina_slope then passes it through unchanged (a
// slope is at most tan 45 deg, which rounds to 1). The CPU evaluator and inlined GLSL fold; a GLSL
// uniform block, whose members hold the file's values for live editing, does not.
kernels::LaminaInputs kernel_constants(const StackEntry& entry, bool fold_slopes);

}  // namespace lamina
