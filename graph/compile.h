// Compiling a checked material graph into a Program: links become registers, constants are
// folded, texture files are decoded once, and the stack becomes a small tree.
#pragma once

#include <string_view>

#include "graph/document.h"
#include "graph/graph.h"
#include "graph/program.h"

namespace lamina {

// `graph` must come from a valid document (check_file(...).graphs). Texture paths are resolved
// against `material_file`'s directory. Throws IoError when a texture cannot be decoded.
Program compile(const Graph& graph, const std::string& material_file);

// Checks `document` again, then compiles the material called `material`. Throws lamina::Error
// for an invalid document or an unknown material name.
Program compile(const Document& document, std::string_view material);

}  // namespace lamina
