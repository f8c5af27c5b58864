#include "graph/graph.h"

#include <algorithm>
#include <map>

namespace lamina {

std::string describe_expected(ValueType expected) {
  switch (expected) {
    case ValueType::Interface: return "an interface/* node";
    case ValueType::Medium: return "a medium/* node";
    case ValueType::Stack: return "a layer, mix, select or substrate/* node";
    default: return "an output of type " + std::string(type_name(expected));
  }
}

namespace {

std::vector<std::string> node_ids(const Material& m) {
  std::vector<std::string> ids;
  for (const auto& n : m.nodes)
    if (!n.id.empty()) ids.push_back(n.id);
  return ids;
}

// Depth-first search that reports each cycle once, as "a -> b -> a". Iterative, with an explicit
// stack, so that a chain of any length is walked without exhausting the call stack, and linear:
// a node's position on the path is kept, so closing a cycle does not search the path.
class CycleFinder {
 public:
  CycleFinder(const Material& m, const std::vector<std::vector<std::pair<size_t, std::string>>>& inputs)
      : m_(m), inputs_(inputs), state_(m.nodes.size(), 0), position_(m.nodes.size(), 0) {}

  struct Cycle {
    std::vector<size_t> path;  // from the first node back to it (long cycles shortened, see below)
    size_t length = 0;         // nodes on the cycle
    size_t reader;             // the node whose link closes the cycle
    std::string param;         // that link's parameter
  };

  std::vector<Cycle> find(std::vector<size_t>& order) {
    for (size_t i = 0; i < m_.nodes.size(); ++i)
      if (state_[i] == 0) visit(i, order);
    return cycles_;
  }

  // A cycle prints at most this many nodes: its first ones, then its last one; a message stays
  // short however long the cycle.
  static constexpr size_t kShownNodes = 8;

 private:
  struct Visit {
    size_t node;
    size_t next_input = 0;
  };

  void visit(size_t root, std::vector<size_t>& order) {
    std::vector<Visit> frames{{root}};
    enter(root);
    while (!frames.empty()) {
      Visit& f = frames.back();
      const auto& inputs = inputs_[f.node];
      if (f.next_input == inputs.size()) {
        path_.pop_back();
        state_[f.node] = 2;
        order.push_back(f.node);  // post-order: inputs first
        frames.pop_back();
        continue;
      }
      const auto& [from, param] = inputs[f.next_input++];
      if (state_[from] == 1) {
        Cycle c;
        const size_t start = position_[from];
        c.length = path_.size() - start;
        for (size_t k = start; k < path_.size() && c.path.size() < kShownNodes; ++k) c.path.push_back(path_[k]);
        if (c.length > kShownNodes) c.path.push_back(path_.back());
        c.path.push_back(from);
        c.reader = f.node;
        c.param = param;
        cycles_.push_back(std::move(c));
      } else if (state_[from] == 0) {
        enter(from);
        frames.push_back({from});
      }
    }
  }

  void enter(size_t node) {
    state_[node] = 1;
    position_[node] = path_.size();
    path_.push_back(node);
  }

  const Material& m_;
  const std::vector<std::vector<std::pair<size_t, std::string>>>& inputs_;
  std::vector<int> state_;        // 0 new, 1 on the path, 2 done
  std::vector<size_t> position_;  // where a node on the path is in path_
  std::vector<size_t> path_;
  std::vector<Cycle> cycles_;
};

}  // namespace

std::optional<Graph> Graph::build(const Material& material, const std::string& file,
                                  const std::string& material_pointer, Diagnostics& diagnostics,
                                  const NodeRegistry& registry) {
  Graph g;
  g.material_ = material;
  const Material& m = g.material_;
  bool ok = true;
  auto error = [&](const std::string& pointer, std::string message, std::string hint = {}) {
    diagnostics.error(file, pointer, std::move(message), std::move(hint));
    ok = false;
  };

  std::map<std::string, size_t> index;
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const NodeDecl* decl = registry.find(m.nodes[i].type);
    if (!decl) return std::nullopt;  // already reported by the reader
    g.decls_.push_back(decl);
    index.emplace(m.nodes[i].id, i);
  }
  std::vector<std::string> ids = node_ids(m);

  // Resolves one link; reports dangling ids, unknown outputs and type mismatches.
  auto resolve = [&](const Link& link, ValueType expected, const std::string& pointer,
                     const std::string& what) -> std::optional<std::pair<size_t, const OutputDecl*>> {
    auto it = index.find(link.node);
    if (it == index.end()) {
      std::string suggestion = diagnostics.suggest(link.node, ids);
      error(pointer, "link to unknown node " + quote_excerpt(link.node, '\''),
            suggestion.empty() ? "node ids in this material: " + join_alternatives(ids)
                               : "did you mean '@" + suggestion + "'?");
      return std::nullopt;
    }
    const NodeDecl& source = *g.decls_[it->second];
    const OutputDecl* output = source.find_output(link.output);
    if (!output) {
      error(pointer,
            "node " + quote_excerpt(link.node, '\'') + " (" + source.type + ") has no output " +
                quote_excerpt(link.output, '\''),
            "its outputs: " + join_alternatives(source.output_names()));
      return std::nullopt;
    }
    if (output->type != expected) {
      if (is_closure(expected) || is_closure(output->type)) {
        error(pointer,
              what + " must be " + describe_expected(expected) + ", but '" + link.node + "' is " + source.type);
      } else {
        std::vector<std::string> fitting;
        for (const auto& o : source.outputs)
          if (o.type == expected) fitting.push_back("@" + link.node + "." + o.name);
        error(pointer,
              what + " expects a " + std::string(type_name(expected)) + " but '" + to_string(link) + "' gives a " +
                  std::string(type_name(output->type)),
              fitting.empty() ? std::string() : "use " + join_alternatives(fitting));
      }
      return std::nullopt;
    }
    return std::make_pair(it->second, output);
  };

  std::vector<std::vector<std::pair<size_t, std::string>>> inputs(m.nodes.size());
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const Node& n = m.nodes[i];
    std::string node_pointer = material_pointer + "/nodes/" + std::to_string(i);
    for (const auto& p : n.params) {
      const auto* link = std::get_if<Link>(&p.value);
      if (!link) continue;
      const ParamDecl* decl = g.decls_[i]->find_param(p.name);
      std::string pointer = pointer_append(node_pointer, p.name);
      if (auto target = resolve(*link, decl->type, pointer, n.type + " input '" + p.name + "'")) {
        g.edges_.push_back({target->first, target->second, i, decl});
        inputs[i].emplace_back(target->first, p.name);
      }
    }
  }

  if (auto target = resolve(m.surface, ValueType::Stack, material_pointer + "/surface", "the surface")) {
    g.surface_ = target->first;
  }

  CycleFinder finder(m, inputs);
  for (const auto& cycle : finder.find(g.order_)) {
    std::string text;
    for (size_t k = 0; k < cycle.path.size(); ++k) {
      // A shortened cycle: its first nodes, "...", its last node, and the first again.
      if (cycle.length > CycleFinder::kShownNodes && k + 2 == cycle.path.size())
        text += " -> ... (" + std::to_string(cycle.length - CycleFinder::kShownNodes - 1) + " more)";
      text += (k ? " -> " : "") + m.nodes[cycle.path[k]].id;
    }
    error(material_pointer + "/nodes/" + std::to_string(cycle.reader) + "/" + cycle.param,
          "cycle: " + text + " (a node cannot depend on itself)", "links must form a DAG: break one of them");
  }
  if (!ok) return std::nullopt;

  g.incoming_.resize(m.nodes.size());
  for (size_t e = 0; e < g.edges_.size(); ++e) g.incoming_[g.edges_[e].to].push_back(e);

  g.used_.assign(m.nodes.size(), false);
  std::vector<size_t> todo{g.surface_};
  while (!todo.empty()) {
    size_t i = todo.back();
    todo.pop_back();
    if (g.used_[i]) continue;
    g.used_[i] = true;
    for (const auto& [from, param] : inputs[i]) todo.push_back(from);
  }
  return g;
}

std::optional<size_t> Graph::linked(size_t i, std::string_view param) const {
  for (size_t e : incoming_[i])
    if (edges_[e].input->name == param) return edges_[e].from;
  return std::nullopt;
}

std::vector<size_t> Graph::stacks_below(size_t i) const {
  std::vector<size_t> below;
  for (const ParamDecl& p : decls_[i]->params)
    if (p.type == ValueType::Stack)
      if (auto target = linked(i, p.name)) below.push_back(*target);
  return below;
}

std::vector<Graph::StackRun> Graph::stack_runs(size_t i) const {
  const std::vector<size_t> below = stacks_below(i);
  std::vector<StackRun> runs;
  for (size_t k = 0; k < below.size(); ++k) {
    if (!runs.empty() && runs.back().node == below[k])
      ++runs.back().hi;
    else
      runs.push_back({below[k], int(k), int(k) + 1});
  }
  if (runs.size() < 2 && below.size() >= 2) {
    runs.clear();
    for (size_t k = 0; k < below.size(); ++k) runs.push_back({below[k], int(k), int(k) + 1});
  }
  return runs;
}

const Value* Graph::value(size_t i, std::string_view param) const {
  if (const Value* v = material_.nodes[i].find(param)) return v;
  const ParamDecl* p = decls_[i]->find_param(param);
  return p && p->fallback ? &*p->fallback : nullptr;
}

}  // namespace lamina
