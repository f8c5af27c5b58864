#include "graph/stack_size.h"

#include <algorithm>
#include <vector>

#include "graph/limits.h"

namespace lamina {

StackSize measure_stack(const Graph& graph) {
  StackSize size;
  // Per node, its lobes and the entries it compiles to, counted over every path below it. A
  // structural link left out (an error reported elsewhere) counts as nothing.
  // `leaves`: the layers and substrates a layer over the node would lie on, one per stack a mix
  // blends (compile.cpp hands a layer over a mix down into each of them).
  // `longest`: the entries of the longest part below the node (a layer's part runs on down its base).
  std::vector<int> lobes(graph.size(), 0), entries(graph.size(), 0), leaves(graph.size(), 1), longest(graph.size(), 0);
  for (size_t i : graph.topological_order()) {
    if (!graph.used(i)) continue;
    const NodeDecl& decl = graph.decl(i);
    switch (decl.kind) {
      case NodeKind::Layer:
      case NodeKind::Mix:
      case NodeKind::Select:
      case NodeKind::Substrate: {
        ++size.stack_nodes;
        const std::vector<Graph::StackRun> below = graph.stack_runs(i);
        if (decl.kind == NodeKind::Layer) {
          // An entry and a lobe (its interface's) per stack it lies on: one, or each one a mix
          // below it blends.
          const int base_leaves = below.empty() ? 1 : leaves[below.front().node];
          lobes[i] = base_leaves;
          entries[i] = base_leaves;
          leaves[i] = base_leaves;
        } else if (decl.kind == NodeKind::Substrate) {
          lobes[i] = 1;
          entries[i] = 1;
        } else {
          // A select of N runs of stacks is a chain of N - 1 entries, each run's stack compiled
          // once (Graph::stack_runs).
          entries[i] = decl.kind == NodeKind::Select ? std::max(int(below.size()) - 1, 1) : 1;
          leaves[i] = 0;
        }
        for (const Graph::StackRun& b : below) {
          lobes[i] += lobes[b.node];
          entries[i] += entries[b.node];
          if (decl.kind != NodeKind::Layer) leaves[i] += leaves[b.node];
          longest[i] = std::max(longest[i], longest[b.node]);
        }
        if (decl.kind == NodeKind::Layer || decl.kind == NodeKind::Substrate)
          longest[i] = std::min(longest[i] + 1, kMaxStackEntries + 1);
        leaves[i] = std::min(std::max(leaves[i], 1), kMaxStackEntries + 1);
        break;
      }
      case NodeKind::Texture:
      case NodeKind::Math:
        for (const OutputDecl& output : decl.outputs) size.registers += value_components(output.type);
        break;
      case NodeKind::Interface:
      case NodeKind::Medium: break;
    }
    lobes[i] = std::min(lobes[i], kMaxLobes + 1);
    entries[i] = std::min(entries[i], kMaxStackEntries + 1);
  }
  size.lobes = lobes[graph.surface()];
  size.entries = entries[graph.surface()];
  size.parts = leaves[graph.surface()];
  size.longest_part = longest[graph.surface()];
  return size;
}

int glsl_loop_entries(const StackSize& size) {
  return size.entries > kGlslUnrolledEntries && size.parts > 1 ? size.longest_part : size.entries;
}

bool check_stack_size(const Graph& graph, const std::string& file, const std::string& material_pointer,
                      Diagnostics& diagnostics) {
  const StackSize size = measure_stack(graph);
  const std::string pointer = material_pointer + "/surface";
  bool ok = true;
  if (size.stack_nodes > kMaxStackNodes) {
    diagnostics.error(file, pointer,
                      "the stack has " + std::to_string(size.stack_nodes) +
                          " layers, mixes and substrates; lamina's back ends hold at most " +
                          std::to_string(kMaxStackNodes),
                      "split the material, or share layers between the sides of a mix");
    ok = false;
  }
  // More lobes than stack nodes come from stacks shared by both sides of mixes.
  if (size.lobes > kMaxLobes && size.stack_nodes <= kMaxStackNodes) {
    diagnostics.error(file, pointer,
                      "the stack has more than " + std::to_string(kMaxLobes) +
                          " lobes (one per interface and substrate on each path through the mixes); lamina's back "
                          "ends hold at most " +
                          std::to_string(kMaxLobes),
                      "nested mixes that share a stack on both sides double its lobes at every level");
    ok = false;
  }
  if (size.registers > kMaxSlots) {
    diagnostics.error(file, pointer,
                      "the texture and math nodes feeding the stack produce " + std::to_string(size.registers) +
                          " values; lamina's back ends hold at most " + std::to_string(kMaxSlots),
                      "use fewer texture and math nodes");
    ok = false;
  }
  return ok;
}

void warn_glsl_unrolling(int entries, const std::string& file, const std::string& material_pointer,
                         Diagnostics& diagnostics) {
  if (entries <= kGlslUnrolledEntries) return;
  diagnostics.warning(file, material_pointer + "/surface",
                      "a chain of layers down to a substrate compiles to " + std::to_string(entries) +
                          " entries, more than the " + std::to_string(kGlslUnrolledEntries) +
                          " iterations GLSL compilers unroll a loop for: its GLSL module keeps the composition's "
                          "loops over it and compiles slowly (minutes on Mesa's llvmpipe)",
                      "use fewer layers in one stack, or split the material");
}

}  // namespace lamina
