// Generated documentation of the node library: the JSON Schema (2020-12) of material files and
// the Markdown reference of every node type. Both come from the node declarations only.
#pragma once

#include <string>

#include "graph/registry.h"

namespace lamina {

std::string material_schema(const NodeRegistry& registry = NodeRegistry::builtin());
// The JSON Schema of scene files, from the scene field declarations (graph/scene/scene_fields.h).
std::string scene_schema();
std::string node_reference_markdown(const NodeRegistry& registry = NodeRegistry::builtin());
// The README's summary table of node types: one row per type with its description, parameters (a
// choice's values in parentheses) and outputs.
std::string node_table_markdown(const NodeRegistry& registry = NodeRegistry::builtin());
// One node type's reference as plain text for `lamina nodes TYPE`.
std::string node_reference_text(const NodeDecl& decl);
// The default of a parameter as JSON text ("0.0", "[1.0, 1.0]", "\"beckmann\"").
std::string default_text(const ParamDecl& p);

}  // namespace lamina
