// A material as a typed DAG: links resolved to node indices, types matched across links, no
// cycles. Built from a Document's Material; everything downstream works on a Graph.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/registry.h"

namespace lamina {

class Graph {
 public:
  struct Edge {
    size_t from;               // the node whose output is read
    const OutputDecl* output;  // which output
    size_t to;                 // the node reading it
    const ParamDecl* input;    // through which parameter
  };

  // Resolves the material's links and checks them: dangling links, unknown outputs, type
  // mismatches (with stack-structure messages), cycles (printed) and the surface. Returns
  // nothing when any of these fails; every problem goes to `diagnostics`, with pointers under
  // `material_pointer` ("/materials/0"). Nodes of unknown type must not be present.
  static std::optional<Graph> build(const Material& material, const std::string& file,
                                    const std::string& material_pointer, Diagnostics& diagnostics,
                                    const NodeRegistry& registry = NodeRegistry::builtin());

  const Material& material() const { return material_; }
  size_t size() const { return material_.nodes.size(); }
  const Node& node(size_t i) const { return material_.nodes[i]; }
  const NodeDecl& decl(size_t i) const { return *decls_[i]; }
  size_t surface() const { return surface_; }
  const std::vector<Edge>& edges() const { return edges_; }

  // Every node after all the nodes it reads from.
  const std::vector<size_t>& topological_order() const { return order_; }
  // The node linked to parameter `param` of node `i`, if that parameter is a link.
  std::optional<size_t> linked(size_t i, std::string_view param) const;
  // The stacks node i sits on or blends: the nodes its given stack parameters link to, in
  // declaration order (a layer's base; a mix's a and b; a select's stack_0, stack_1, ...).
  std::vector<size_t> stacks_below(size_t i) const;
  // The same as they compile: consecutive repeats of one stack (a select whose stack_0 to stack_2
  // are all "@surface", the transparent cells of a sparse glitter map) are one run over the
  // positions [lo, hi) they fill, so that the stack's entries appear once. Where that would leave
  // fewer than two runs, every position is a run of its own (a two-way entry has two sides).
  struct StackRun {
    size_t node;
    int lo, hi;
  };
  std::vector<StackRun> stack_runs(size_t i) const;
  // Whether node i feeds the surface, directly or indirectly (or is the surface).
  bool used(size_t i) const { return used_[i]; }

  // A parameter's value with the declaration's default applied; nullptr if neither exists.
  const Value* value(size_t i, std::string_view param) const;

 private:
  Material material_;
  std::vector<const NodeDecl*> decls_;
  std::vector<Edge> edges_;
  std::vector<std::vector<size_t>> incoming_;  // per node: its edges' indices, so linked() is local
  std::vector<size_t> order_;
  std::vector<bool> used_;
  size_t surface_ = 0;
};

// What a link of type `expected` may point at, in words: "a layer, mix, select or substrate/* node".
std::string describe_expected(ValueType expected);

}  // namespace lamina
