// How much of the back ends' fixed capacity a material takes (graph/limits.h): counted on the
// checked graph, so that `lamina validate` refuses what no command could evaluate, and every
// command agrees with it.
#pragma once

#include <string>

#include "graph/diagnostics.h"
#include "graph/graph.h"

namespace lamina {

struct StackSize {
  int stack_nodes = 0;  // layers, mixes, selects and substrates that feed the surface
  // The compiled stack's entries: one per stack node on each path through the mixes, N - 1 for a
  // select of N stacks (its chain); below 2 kMaxLobes whenever the lobes fit, at most kMaxStackEntries + 1.
  int entries = 0;
  int lobes = 0;      // one per interface and substrate on each path through the mixes; at most kMaxLobes + 1
  int registers = 0;  // floats the texture and math nodes feeding the surface produce
  // The compiled stack's parts (graph/kernel_stack.h, StackBlend: the chains of layers down to a
  // substrate below its mixes, a layer over a mix handed down into each) and the longest's entries.
  int parts = 0;
  int longest_part = 0;
};

// The entries the loops of a material's GLSL run over: the whole stack's, or the longest part's when
// the stack is longer than GLSL compilers unroll and has several parts (glsl::evaluates_by_parts,
// which decides the same from the compiled Program).
int glsl_loop_entries(const StackSize& size);

// Linear in the graph's size: every count is made once per node, in topological order, and the
// lobe count stops growing past the limit (a stack shared by both sides of nested mixes doubles
// its lobes per level).
StackSize measure_stack(const Graph& graph);

// Reports, at the material's "surface", each count beyond its limit; returns whether all fit.
bool check_stack_size(const Graph& graph, const std::string& file, const std::string& material_pointer,
                      Diagnostics& diagnostics);

// Warns, at the material's "surface", when the loops of its GLSL run over more `entries` than GLSL
// compilers unroll a loop for (kGlslUnrolledEntries): a part longer than that, whether the whole
// stack or one of several (advice for `lamina validate`, which counts them with glsl_loop_entries,
// and `lamina glsl`, from the compiled Program: the CPU evaluator does not care).
void warn_glsl_unrolling(int entries, const std::string& file, const std::string& material_pointer,
                         Diagnostics& diagnostics);

}  // namespace lamina
