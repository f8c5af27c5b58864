// Canonical writing: stable key order (declaration order for parameters), shortest exact numbers,
// arrays of numbers on one line. write(read(write(d))) == write(d), byte for byte.
#pragma once

#include <string>

#include "graph/document.h"
#include "graph/registry.h"

namespace lamina {

std::string write_document(const Document& document, const NodeRegistry& registry = NodeRegistry::builtin());

}  // namespace lamina
