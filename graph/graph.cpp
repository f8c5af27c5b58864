#include "graph/graph.h"

#include <algorithm>
#include <map>

namespace lamina {

std::string describe_expected(ValueType expected) {
  switch (expected) {
    case ValueType::Interface: return "an interface/* node";
    case ValueType::Medium: return "a medium/* node";
    case ValueType::Stack: return "a layer, mix or substrate/* node";
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

// Depth-first search that reports each cycle once, as "a -> b -> a".
class CycleFinder {
 public:
  CycleFinder(const Material& m, const std::vector<std::vector<std::pair<size_t, std::string>>>& inputs)
      : m_(m), inputs_(inputs), state_(m.nodes.size(), 0) {}

  struct Cycle {
    std::vector<size_t> path;  // from the first node back to it
    size_t reader;             // the node whose link closes the cycle
    std::string param;         // that link's parameter
  };

  std::vector<Cycle> find(std::vector<size_t>& order) {
    for (size_t i = 0; i < m_.nodes.size(); ++i)
      if (state_[i] == 0) visit(i, order);
    return cycles_;
  }

 private:
  void visit(size_t i, std::vector<size_t>& order) {
    state_[i] = 1;
    stack_.push_back(i);
    for (const auto& [from, param] : inputs_[i]) {
      if (state_[from] == 1) {
        auto start = std::find(stack_.begin(), stack_.end(), from);
        Cycle c{{start, stack_.end()}, i, param};
        c.path.push_back(from);
        cycles_.push_back(std::move(c));
      } else if (state_[from] == 0) {
        visit(from, order);
      }
    }
    stack_.pop_back();
    state_[i] = 2;
    order.push_back(i);  // post-order: inputs first
  }

  const Material& m_;
  const std::vector<std::vector<std::pair<size_t, std::string>>>& inputs_;
  std::vector<int> state_;  // 0 new, 1 on the stack, 2 done
  std::vector<size_t> stack_;
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
      std::string suggestion = closest_match(link.node, ids);
      error(pointer, "link to unknown node '" + link.node + "'",
            suggestion.empty() ? "node ids in this material: " + join_alternatives(ids)
                               : "did you mean '@" + suggestion + "'?");
      return std::nullopt;
    }
    const NodeDecl& source = *g.decls_[it->second];
    const OutputDecl* output = source.find_output(link.output);
    if (!output) {
      error(pointer, "node '" + link.node + "' (" + source.type + ") has no output '" + link.output + "'",
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
    for (size_t k = 0; k < cycle.path.size(); ++k) text += (k ? " -> " : "") + m.nodes[cycle.path[k]].id;
    error(material_pointer + "/nodes/" + std::to_string(cycle.reader) + "/" + cycle.param,
          "cycle: " + text + " (a node cannot depend on itself)", "links must form a DAG: break one of them");
  }
  if (!ok) return std::nullopt;

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
  for (const auto& e : edges_)
    if (e.to == i && e.input->name == param) return e.from;
  return std::nullopt;
}

const Value* Graph::value(size_t i, std::string_view param) const {
  if (const Value* v = material_.nodes[i].find(param)) return v;
  const ParamDecl* p = decls_[i]->find_param(param);
  return p && p->fallback ? &*p->fallback : nullptr;
}

}  // namespace lamina
