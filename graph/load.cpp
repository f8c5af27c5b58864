#include "graph/load.h"

#include <algorithm>

#include "graph/stack_size.h"

namespace lamina {

namespace {

void check_material(CheckedFile& out, size_t index, const NodeRegistry& registry) {
  const AssetPolicy& policy = out.document.policy;
  const Material& m = out.document.materials[index];
  const std::string& file = out.document.path;
  std::string pointer = "/materials/" + std::to_string(index);

  bool all_known = true;
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const NodeDecl* decl = registry.find(m.nodes[i].type);
    if (!decl) {
      all_known = false;
      continue;
    }
    if (decl->check) {
      std::string node_pointer = pointer + "/nodes/" + std::to_string(i);
      decl->check(NodeCheckContext{m.nodes[i], file, node_pointer, out.diagnostics, policy});
    }
  }
  // Links are resolved only when every node could be read with its id and type: against an
  // incomplete node list they would only produce knock-on errors.
  bool complete = all_known && !m.nodes.empty() &&
                  std::none_of(m.nodes.begin(), m.nodes.end(), [](const Node& n) { return n.id.empty(); });
  if (!complete || m.surface.node.empty()) return;

  auto graph = Graph::build(m, file, pointer, out.diagnostics, registry);
  if (!graph) return;
  // Before anything walks the stack (classification, warnings): a stack beyond the back ends'
  // capacity is refused here, so that every command agrees with lamina validate.
  if (!check_stack_size(*graph, file, pointer, out.diagnostics)) return;
  for (size_t i = 0; i < graph->size(); ++i) {
    if (!graph->used(i))
      out.diagnostics.warning(file, pointer + "/nodes/" + std::to_string(i),
                              "node '" + graph->node(i).id + "' does not feed the surface", "remove it or link it");
  }
  // The class is judged only on a material without errors: a value dropped by an error (a
  // layer's base, say) would make the structure look different from what the author wrote.
  if (m.class_tag && out.diagnostics.ok()) {
    Classification c = classify(*graph);
    if (std::find(c.accepted.begin(), c.accepted.end(), *m.class_tag) == c.accepted.end())
      out.diagnostics.warning(
          file, pointer + "/class",
          "declared class " + *m.class_tag + ") " + class_name(*m.class_tag) +
              " disagrees with the structure: " + (c.letter.empty() ? c.name : c.letter + ") " + c.name),
          c.reason);
  }
  out.graphs[index] = std::move(graph);
}

}  // namespace

CheckedFile check_text(std::string_view text, const std::string& file, const NodeRegistry& registry) {
  return check_text(text, file, AssetPolicy{}, registry);
}

CheckedFile check_text(std::string_view text, const std::string& file, const AssetPolicy& policy,
                       const NodeRegistry& registry) {
  CheckedFile out;
  out.document = read_document(text, file, out.diagnostics, registry);
  out.document.policy = policy.with_default_root(file);
  out.graphs.resize(out.document.materials.size());
  for (size_t i = 0; i < out.document.materials.size(); ++i) check_material(out, i, registry);
  // A graph built from a document with errors elsewhere is still usable for messages, but
  // callers get graphs only for fully valid files.
  if (!out.diagnostics.ok())
    for (auto& g : out.graphs) g.reset();
  return out;
}

CheckedFile check_file(const std::filesystem::path& path, const AssetPolicy& policy, const NodeRegistry& registry) {
  std::string text;
  try {
    text = read_input_file(path, kMaxJsonFileBytes);
  } catch (const Error& e) {  // too large: a mistake of the file, reported like the others
    CheckedFile out;
    out.document.path = path.string();
    out.document.policy = policy.with_default_root(path);
    for (const auto& d : e.diagnostics()) out.diagnostics.error(d.file, d.pointer, d.message, d.hint);
    return out;
  }
  return check_text(text, path.string(), policy, registry);
}

Document load(const std::filesystem::path& path) {
  CheckedFile checked = check_file(path);
  if (!checked.ok()) throw Error(checked.diagnostics.errors());
  return std::move(checked.document);
}

}  // namespace lamina
