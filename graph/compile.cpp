#include "graph/compile.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>

#include "graph/json_write.h"
#include "graph/limits.h"
#include "graph/load.h"
#include "graph/lowering.h"
#include "graph/model.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

namespace {

// Walks a checked graph once: texture and math nodes in topological order, each lowered by its
// own behaviour into an op (or folded into constants when it is pure and its inputs are), then the
// stack from the surface, depth first, each stack node lowered into its entry.
class Compiler final : public InputSource {
 public:
  Compiler(const Graph& graph, const std::string& file, const AssetPolicy& policy)
      : g_(graph), file_(file), policy_(policy) {}

  Program run() {
    program_.name = g_.material().name;
    program_.source_file = file_;
    program_.clamp_lower_roughness = g_.material().clamp_lower_roughness.value_or(true);
    program_.model = model_number(g_.material().model.value_or(std::string(kDefaultModel)));
    for (size_t i : g_.topological_order()) {
      if (!g_.used(i)) continue;
      NodeKind kind = g_.decl(i).kind;
      if (kind == NodeKind::Texture || kind == NodeKind::Math) lower_op(i);
    }
    expand(g_.surface(), -1, 0);
    program_.slot_count = slots_;
    return std::move(program_);
  }

  InputRef input(size_t node, std::string_view param) const override {
    const NodeDecl& decl = g_.decl(node);
    const ParamDecl* p = decl.find_param(param);
    const Value* v = g_.value(node, param);
    if (!p || !v) throw std::logic_error("compile: " + g_.node(node).id + " has no value for " + std::string(param));
    InputRef r;
    r.node = g_.node(node).id;
    r.parameter = std::string(param);
    r.size = value_components(p->type);
    r.lo = float(p->lo);
    r.hi = float(p->hi);
    if (const auto* link = std::get_if<Link>(v)) {
      const size_t from = *g_.linked(node, param);
      const InputRef& out = outputs_.at({from, g_.decl(from).find_output(link->output)->name});
      r.slot = out.slot;
      r.constant = out.constant;
    } else if (const auto* d = std::get_if<double>(v)) {
      r.constant = glm::vec3(float(*d), 0.0f, 0.0f);
    } else if (const auto* v2 = std::get_if<Vec2d>(v)) {
      r.constant = glm::vec3(float((*v2)[0]), float((*v2)[1]), 0.0f);
    } else if (const auto* v3 = std::get_if<Vec3d>(v)) {
      r.constant = glm::vec3(float((*v3)[0]), float((*v3)[1]), float((*v3)[2]));
    } else {
      throw std::logic_error("compile: " + r.node + "." + r.parameter + " is not a numeric input");
    }
    return r;
  }

 private:
  int allocate(int count) {
    int first = slots_;
    slots_ += count;
    return first;
  }

  void lower_op(size_t i) {
    const NodeDecl& decl = g_.decl(i);
    if (!decl.lower || !decl.run || !decl.emit_glsl)
      throw std::logic_error("compile: " + decl.type + " lacks a lowering, a CPU run or a GLSL emission");
    TextureOp op;
    op.decl = &decl;
    op.node = g_.node(i).id;
    NodeLowering lowering(g_, i, file_, policy_, *this, nullptr, &op);
    decl.lower(lowering);
    const bool constant =
        !decl.varies && std::none_of(op.inputs.begin(), op.inputs.end(), [](const InputRef& r) { return r.linked(); });
    if (constant) {
      // A pure node of constants: run once here, with the same code every evaluator runs.
      std::vector<float> scratch;
      for (const OutputDecl& o : decl.outputs) {
        op.outputs.push_back(int(scratch.size()));
        scratch.resize(scratch.size() + size_t(value_components(o.type)), 0.0f);
      }
      decl.run(op, ShadingContext{}, scratch.data());
      for (size_t k = 0; k < decl.outputs.size(); ++k) {
        InputRef out;
        const int first = op.outputs[k];
        for (int c = 0; c < value_components(decl.outputs[k].type); ++c) out.constant[c] = scratch[size_t(first + c)];
        outputs_[{i, decl.outputs[k].name}] = out;
      }
      return;
    }
    for (const OutputDecl& o : decl.outputs) {
      InputRef out;
      out.slot = allocate(value_components(o.type));
      op.outputs.push_back(out.slot);
      outputs_[{i, o.name}] = out;
    }
    program_.ops.push_back(std::move(op));
  }

  // The entry of stack node `i` reached from entry `parent` (side: which stack of a mix parent),
  // then its children: the stacks the node sits on or blends, in declaration order (a layer's
  // base; a mix's a and b), consecutive repeats of a select's stack as one run (Graph::stack_runs).
  // A node over N > 2 runs (a select) becomes a chain of N - 1 two-way entries: entry `part` k has
  // run k first and, second, entry k + 1, or for the last, run N - 1. Returns the entry's index.
  //
  // A layer whose chain of layers ends on a mix or a select is handed down into each stack the
  // mix blends (`over`, outermost first): layer over mix(a, b) compiles as mix(layer over a, layer
  // over b). A mix is a share of the surface, and a layer over it lies over each share; the seeds'
  // composition is linear in the base, so its BRDF is the same either way, while the
  // energy-conserving model's coupling of a layer with the diffuse light below it (its diffuse
  // coefficient) needs the one stack under it, which a mix does not have.
  int expand(size_t i, int parent, int side, int part = 0, std::vector<size_t> over = {}) {
    const NodeKind kind = g_.decl(i).kind;
    const bool blends = kind == NodeKind::Mix || kind == NodeKind::Select;
    if (kind == NodeKind::Layer && layers_end_on_blend(i)) {
      over.push_back(i);
      return expand(g_.stack_runs(i).front().node, parent, side, 0, std::move(over));
    }
    if (!blends && !over.empty()) return expand_under(over, 0, i, parent, side);
    const int index = add_entry(i, parent, side, part);
    const std::vector<Graph::StackRun> below = g_.stack_runs(i);
    const size_t k = size_t(part);
    if (below.size() > k) {
      const int first = expand(below[k].node, index, 0, 0, over);
      program_.stack[size_t(index)].first = first;
    }
    if (below.size() > k + 1) {
      const int second =
          below.size() > k + 2 ? expand(i, index, 1, part + 1, over) : expand(below[k + 1].node, index, 1, 0, over);
      program_.stack[size_t(index)].second = second;
    }
    return index;
  }

  // Whether the chain of layers from layer i down its bases ends on a mix or a select.
  bool layers_end_on_blend(size_t i) const {
    size_t n = i;
    while (g_.decl(n).kind == NodeKind::Layer) {
      const std::vector<Graph::StackRun> below = g_.stack_runs(n);
      if (below.empty()) return false;
      n = below.front().node;
    }
    return g_.decl(n).kind == NodeKind::Mix || g_.decl(n).kind == NodeKind::Select;
  }

  // The layers over[k..] handed down to stack node `stack` (a layer or substrate), each the base of
  // the one before, then `stack` below them. Returns the first's entry.
  int expand_under(const std::vector<size_t>& over, size_t k, size_t stack, int parent, int side) {
    if (k == over.size()) return expand(stack, parent, side);
    const int index = add_entry(over[k], parent, side, 0);
    const int first = expand_under(over, k + 1, stack, index, 0);
    program_.stack[size_t(index)].first = first;
    return index;
  }

  // Stack node i's entry, lowered by its own behaviour, without its children yet.
  int add_entry(size_t i, int parent, int side, int part) {
    if (int(program_.stack.size()) >= kMaxStackEntries)
      throw std::logic_error("compile: the stack of '" + program_.name + "' exceeds " +
                             std::to_string(kMaxStackEntries) + " entries, which the checker refuses");
    const NodeDecl& decl = g_.decl(i);
    if (!decl.lower) throw std::logic_error("compile: " + decl.type + " has no lowering");
    StackEntry entry;
    entry.parent = parent;
    entry.side = side;
    entry.decl = &decl;
    entry.node = g_.node(i).id;
    NodeLowering lowering(g_, i, file_, policy_, *this, &entry, nullptr, part);
    decl.lower(lowering);
    program_.stack.push_back(std::move(entry));
    return int(program_.stack.size()) - 1;
  }

  const Graph& g_;
  const std::string& file_;
  const AssetPolicy& policy_;
  Program program_;
  int slots_ = 0;
  std::map<std::pair<size_t, std::string>, InputRef> outputs_;  // (node, output) -> its value
};

}  // namespace

Program compile(const Graph& graph, const std::string& material_file, const AssetPolicy& policy) {
  return Compiler(graph, material_file, policy).run();
}

Program compile(const Graph& graph, const std::string& material_file) {
  return compile(graph, material_file, AssetPolicy{}.with_default_root(material_file));
}

Program compile(const Document& document, std::string_view material) {
  const Material* found = document.find_material(material);
  if (!found) {
    std::vector<std::string> names;
    for (const auto& m : document.materials) names.push_back(m.name);
    throw Error(
        {Diagnostic{Severity::Error, document.path, "/materials", "no material named '" + std::string(material) + "'",
                    "materials in this file: " + join_alternatives(names)}});
  }
  // That material alone is checked again (its textures decoded as the check decodes them), so
  // that compiling each material of a file of thousands costs time linear in the file.
  Document single;
  single.path = document.path;
  single.policy = document.policy;
  single.format = document.format;
  single.materials.push_back(*found);
  CheckedFile checked = check_text(write_document(single), document.path, document.policy);
  if (!checked.ok()) throw Error(checked.diagnostics.errors());
  return compile(*checked.graphs[0], document.path, checked.document.policy);
}

}  // namespace lamina
