// lamina nodes [TYPE]: the node reference, generated from the declarations.
#include <iostream>

#include "graph/diagnostics.h"
#include "graph/registry.h"
#include "graph/schema.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct NodesOptions {
  std::string type;
  bool markdown = false;
};

int run_nodes(const NodesOptions& o) {
  const auto& registry = NodeRegistry::builtin();
  if (o.markdown) {
    std::cout << node_reference_markdown(registry);
    return kExitOk;
  }
  if (!o.type.empty()) {
    const NodeDecl* decl = registry.find(o.type);
    if (!decl) {
      std::string suggestion = closest_match(o.type, registry.type_names());
      print_problem("unknown node type '" + o.type + "'" +
                    (suggestion.empty() ? "" : " (did you mean '" + suggestion + "'?)"));
      std::cerr << "valid types: " << join_alternatives(registry.type_names()) << "\n";
      return kExitInvalid;
    }
    std::cout << node_reference_text(*decl);
    return kExitOk;
  }
  for (const auto& d : registry.all()) {
    std::string type = d.type;
    type.resize(std::max<size_t>(type.size(), 22), ' ');
    std::cout << type << " " << d.doc << "\n";
  }
  std::cout << "\n'lamina nodes TYPE' shows a type's parameters.\n";
  return kExitOk;
}

}  // namespace

void add_nodes(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<NodesOptions>();
  auto* cmd = app.add_subcommand("nodes", "List node types, or show one type's parameters and outputs");
  cmd->add_option("type", o->type, "a node type, e.g. interface/dielectric");
  cmd->add_flag("--markdown", o->markdown, "print the whole reference as Markdown");
  cmd->callback([o, &runner] { runner = [o] { return run_nodes(*o); }; });
}

}  // namespace lamina::cli
