// What a node's `lower` (graph/node_decl.h) sees while graph/compile.cpp turns a checked graph into
// a Program: the node's values, and the part of the Program it builds. Texture and math nodes fill
// their TextureOp; stack nodes (layers, mixes, substrates, and a layer's interface and medium) fill
// the StackEntry they belong to.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "graph/file_access.h"
#include "graph/graph.h"
#include "graph/program.h"

namespace lamina {

// How the compiler turns a numeric parameter into an input: its constant, or the registers of
// the output it links to.
class InputSource {
 public:
  virtual ~InputSource() = default;
  virtual InputRef input(size_t node, std::string_view param) const = 0;
};

class NodeLowering {
 public:
  // Called by compile.cpp. `entry` is the stack entry a stack node fills; `op` the op a texture or
  // math node fills; the other is null.
  NodeLowering(const Graph& graph, size_t node, const std::string& file, const AssetPolicy& policy,
               const InputSource& inputs, StackEntry* entry, TextureOp* op, int part = 0)
      : graph_(graph),
        node_(node),
        file_(file),
        policy_(policy),
        inputs_(inputs),
        entry_(entry),
        op_(op),
        part_(part) {}

  const Graph& graph() const { return graph_; }
  size_t index() const { return node_; }
  const std::string& id() const;
  const NodeDecl& decl() const { return graph_.decl(node_); }
  const std::string& file() const { return file_; }
  const AssetPolicy& policy() const { return policy_; }

  // A numeric parameter as an input: the constant the file gives (or the default), or the
  // registers of the output it links to; with the parameter's declared range as its clamp.
  InputRef input(std::string_view param) const { return inputs_.input(node_, param); }
  // Whether the file gives the parameter (e.g. alpha rather than roughness_deg).
  bool given(std::string_view param) const;
  // Constant parameters (never links), with the declaration's default applied.
  double number(std::string_view param) const;
  glm::vec2 vec2(std::string_view param) const;
  bool flag(std::string_view param) const;
  const std::string& text(std::string_view param) const;
  // An enum parameter as the index of its value among the declared choices, which is how the
  // kernels number them (a declaration lists its choices in the kernels' order).
  int choice(std::string_view param) const;
  // The node a structural parameter links to (a layer's interface, medium, base).
  std::optional<size_t> linked(std::string_view param) const { return graph_.linked(node_, param); }

  // Which of its entries a stack node over more than two stacks is lowering: such a node (a
  // select) becomes a chain of two-way entries, entry k blending stack k with the entries after it
  // (compile.cpp). 0 for every other node.
  int part() const { return part_; }
  // A stack node's entry; a layer's interface and medium fill the layer's entry.
  StackEntry& entry() const;
  // Runs the `lower` of the node that structural parameter `param` links to on this entry (a layer
  // lowers its interface and medium so); false when the parameter links nothing.
  bool lower_linked(std::string_view param) const;
  // A texture or math node's op.
  TextureOp& op() const;

  // The material changed on disk between the check and the compile (a texture file): IoError.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  const Value& value(std::string_view param) const;

  const Graph& graph_;
  size_t node_;
  const std::string& file_;
  const AssetPolicy& policy_;
  const InputSource& inputs_;
  StackEntry* entry_;
  TextureOp* op_;
  int part_;
};

}  // namespace lamina
