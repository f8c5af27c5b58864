// Entry points: a material file in, a checked document and its graphs out.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "graph/classify.h"
#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/graph.h"
#include "graph/json_read.h"

namespace lamina {

struct CheckedFile {
  Document document;
  Diagnostics diagnostics;
  std::vector<std::optional<Graph>> graphs;  // one per material; empty when it has errors
  bool ok() const { return diagnostics.ok(); }
};

// Reads and checks everything in one pass: syntax, values, links, types, cycles, node rules
// (such as texture files existing), plus warnings for unused nodes and class tags that
// disagree with the structure.
// Texture files are followed and decoded under `policy` (file_access.h; its roots default to the
// folder of `file`), exactly as compiling the document will; the document keeps the policy.
CheckedFile check_text(std::string_view text, const std::string& file, const AssetPolicy& policy,
                       const NodeRegistry& registry = NodeRegistry::builtin());
CheckedFile check_text(std::string_view text, const std::string& file,
                       const NodeRegistry& registry = NodeRegistry::builtin());
// As check_text; throws IoError when the file cannot be read. A file beyond kMaxJsonFileBytes is
// an error of the file, in the diagnostics.
CheckedFile check_file(const std::filesystem::path& path, const AssetPolicy& policy = {},
                       const NodeRegistry& registry = NodeRegistry::builtin());

// The library's one-call loader: a valid document or lamina::Error with every problem.
Document load(const std::filesystem::path& path);

}  // namespace lamina
