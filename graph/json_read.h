// Reading material files: JSON text -> Document, reporting every problem with its JSON pointer.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/file_access.h"
#include "graph/registry.h"

namespace lamina {

// Parses `text` (the content of `file`) and checks each value against the node declarations:
// JSON syntax, structure, unknown keys, types, finiteness, ranges, enum choices, required and
// mutually exclusive parameters. Links are only parsed here; Graph::build resolves them.
// Problems go to `diagnostics`; the returned document holds whatever could be read.
Document read_document(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                       const NodeRegistry& registry = NodeRegistry::builtin());

// Parses "@node" or "@node.output"; false if `text` is not a link.
bool parse_link(std::string_view text, Link& link);
bool is_identifier(std::string_view text);

}  // namespace lamina
