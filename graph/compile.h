// Compiling a checked material graph into a Program: links become registers, constants are
// folded, texture files are decoded once, and the stack becomes a small tree.
#pragma once

#include <string_view>

#include "graph/document.h"
#include "graph/graph.h"
#include "graph/program.h"

namespace lamina {

// `graph` must come from a valid document (check_file(...).graphs). Texture files are followed
// from `material_file` under `policy` (file_access.h), as the check did: pass the checked
// document's policy. Throws IoError when a texture can no longer be read or decoded.
Program compile(const Graph& graph, const std::string& material_file, const AssetPolicy& policy);
// As above, with the default policy for `material_file` (its folder is the only root).
Program compile(const Graph& graph, const std::string& material_file);

// Checks `document` again, then compiles the material called `material`. Throws lamina::Error
// for an invalid document or an unknown material name.
Program compile(const Document& document, std::string_view material);

}  // namespace lamina
