// The kernels' view of a compiled stack (LaminaEntry and LaminaInputs of nodes/kernels/stack.glsl),
// shared by the back ends so that each hands the composition the same numbers.
#pragma once

#include <vector>

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

// An entry's inputs at a shading point: `constants` (kernel_constants) with every linked input read
// from the point's registers, clamped to its range.
kernels::LaminaInputs kernel_inputs(const StackEntry& entry, const kernels::LaminaInputs& constants,
                                    const float* registers);

// A compiled stack as its blend over its parts (nodes/kernels/stack.glsl, "a blend of parts"): the
// mixes at its top, and below them the parts, each a stack without a mix above it. A stack that is
// not a mix at its top is one part under a blend of that part alone.
struct StackBlend {
  struct Part {
    int first = 0;  // its entries are [first, first + count) of the whole stack, its own stack in order
    int count = 0;
    int blend = 0;  // its first entry's place in the blend
  };
  // The blend's entries as the kernels read them, in stack order: its mixes, then (each where the
  // whole stack has it) the parts' first entries; parent and side index the blend (first and
  // second too for a mix; -1 for a part), and whole[i] is entry i's index in the whole stack.
  std::vector<kernels::LaminaEntry> entries;
  std::vector<int> whole;
  std::vector<Part> parts;

  int longest_part() const;
  // Part k's entries as a stack of its own: parent, first and second counted from its first entry.
  std::vector<kernels::LaminaEntry> part_entries(const Program& program, size_t k, bool fold_slopes) const;
};

StackBlend split_blend(const Program& program, bool fold_slopes);

// A resolved stack without the entries no mix shows (LaminaParams::share 0: the stacks a select's
// chain hides at this point). An entry no mix shows adds exact zeros to every query of the
// composition (lamina_eval_enter leaves it unreached, lamina_stack_estimate gives it no weight), so
// each query gives on the shown stack bit for bit what it gives on the whole one, in fewer steps.
// A hidden stack under a shown mix stays as one stand-in entry, a childless substrate that no mix
// shows, so that the mix keeps its two stacks. Writes the shown stack into out_entries and
// out_params (count entries at most), with whole[i] entry i's index in the given stack, and
// returns its length; returns 0, writing nothing, when every entry is shown. count: at most kMaxStackEntries.
int shown_stack(int count, const kernels::LaminaEntry* entries, const kernels::LaminaParams* params,
                kernels::LaminaEntry* out_entries, kernels::LaminaParams* out_params, int* whole);

}  // namespace lamina
