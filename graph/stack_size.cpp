#include "graph/stack_size.h"

#include <algorithm>
#include <vector>

#include "graph/limits.h"

namespace lamina {

StackSize measure_stack(const Graph& graph) {
  StackSize size;
  std::vector<int> lobes(graph.size(), 0);
  // A structural link left out (an error reported elsewhere) counts as no lobe.
  auto lobes_of = [&](size_t i, const char* param) {
    const auto linked = graph.linked(i, param);
    return linked ? lobes[*linked] : 0;
  };
  for (size_t i : graph.topological_order()) {
    if (!graph.used(i)) continue;
    const NodeDecl& decl = graph.decl(i);
    switch (decl.kind) {
      case NodeKind::Layer:
        ++size.stack_nodes;
        lobes[i] = 1 + lobes_of(i, "base");
        break;
      case NodeKind::Mix:
        ++size.stack_nodes;
        lobes[i] = lobes_of(i, "a") + lobes_of(i, "b");
        break;
      case NodeKind::Substrate:
        ++size.stack_nodes;
        lobes[i] = 1;
        break;
      case NodeKind::Texture:
      case NodeKind::Math:
        for (const OutputDecl& output : decl.outputs) size.registers += value_components(output.type);
        break;
      case NodeKind::Interface:
      case NodeKind::Medium: break;
    }
    lobes[i] = std::min(lobes[i], kMaxLobes + 1);
  }
  size.lobes = lobes[graph.surface()];
  return size;
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

}  // namespace lamina
