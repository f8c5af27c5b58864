// select: one of N stacks, chosen per shading point by an index, so that a Voronoi cell map gives
// each cell one of several layered materials (the course's surface map of 9 entries and glitter
// map of 4, course sec. 5.2.1, fig. 5.2). A glitter map's transparent cells are a select entry
// that is the map below it.
#include <cmath>
#include <string>

#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/number_text.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// Stacks a select blends at most: its parameters stack_0 .. stack_15.
inline constexpr int kMaxSelectStacks = 16;

static std::string stack_param(int k) { return "stack_" + std::to_string(k); }

// The stacks are given from stack_0 on without gaps, at least two of them, and a constant index
// names one of them.
static void check_select(const NodeCheckContext& ctx) {
  int given = 0;
  int first_gap = -1;
  for (int k = 0; k < kMaxSelectStacks; ++k) {
    if (ctx.get(stack_param(k))) {
      if (first_gap >= 0) {
        ctx.error(stack_param(k), stack_param(k) + " is given but " + stack_param(first_gap) + " is not",
                  "give the stacks as stack_0, stack_1, ... without gaps");
        return;
      }
      ++given;
    } else if (first_gap < 0) {
      first_gap = k;
    }
  }
  if (given < 2) {
    ctx.error(given == 0 ? "stack_0" : "stack_1", "a select needs at least two stacks, found " + std::to_string(given),
              "give stack_0 and stack_1 (a single stack needs no select: link it directly)");
    return;
  }
  const Value* index = ctx.get("index");
  if (index && std::holds_alternative<double>(*index) && std::floor(std::get<double>(*index)) >= given)
    ctx.error("index",
              "index " + number_text(std::get<double>(*index)) + " names no stack: there are " + std::to_string(given) +
                  " (stack_0 to " + stack_param(given - 1) + ")",
              "the index counts from 0; floor(index) picks the stack");
}

// Entry `part` k of the chain (compile.cpp) shows run k of the stacks (Graph::stack_runs: stacks
// lo to hi - 1 when they are the same one) where floor(index) < hi, else the entries after it
// (lamina_select_weight, which also reads the coverage and the number of stacks).
static void lower_select(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_MIX;
  e.model = kernels::LAMINA_MIX_SELECT;
  e.scalar_x = n.input("index");
  const Graph::StackRun run = n.graph().stack_runs(n.index()).at(size_t(n.part()));
  e.scalar_y.constant = glm::vec3(float(run.hi));
  e.colour0.constant = glm::vec3(float(run.lo));
  e.scalar_z = n.input("coverage");
  int count = 0;
  while (count < kMaxSelectStacks && n.given(stack_param(count))) ++count;
  e.scalar_w.constant = glm::vec3(float(count));
}

NodeDecl declare_select() {
  NodeDecl d;
  d.type = "select";
  d.kind = NodeKind::Select;
  d.doc =
      "one of N stacks per shading point: stack_k where floor(index) = k (index clamped to [0, N - 1]); where a "
      "pixel covers many cells (coverage), every stack in proportion; only the stacks shown are evaluated, and "
      "consecutive places naming the same stack compile once";
  d.params.push_back(param("index", ValueType::Float)
                         .range(0.0, double(kMaxSelectStacks - 1))
                         .links()
                         .described("which stack, counted from 0; usually a cell value remapped to [0, N), e.g. "
                                    "a texture/voronoi value through math/remap with out_max N"));
  d.params.push_back(param("coverage", ValueType::Float)
                         .range(0.0, 1.0)
                         .or_default(0.0)
                         .links()
                         .described("how much of the cell pattern behind the index a pixel covers: 0 shows the one "
                                    "stack the index names, 1 every stack in equal shares, the mean over many "
                                    "cells whose uniform values the index spreads over [0, N); link "
                                    "texture/voronoi's coverage"));
  for (int k = 0; k < kMaxSelectStacks; ++k)
    d.params.push_back(param(stack_param(k), ValueType::Stack)
                           .links()
                           .optional()
                           .described(k == 0 ? "the stack where floor(index) is 0 (at least stack_0 and stack_1)"
                                             : "the stack where floor(index) is " + std::to_string(k)));
  d.outputs.push_back({"stack", ValueType::Stack, "the selected stack"});
  d.check = check_select;
  d.lower = lower_select;
  return d;
}

}  // namespace lamina
