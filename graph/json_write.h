// Canonical writing: stable key order (declaration order for parameters), shortest exact numbers,
// arrays of numbers on one line. write(read(write(d))) == write(d), byte for byte.
#pragma once

#include <string>

#include "graph/document.h"
#include "graph/registry.h"

namespace lamina {

// One value as canonical JSON text: "1.5", "[0.5, 0.25, 0.125]", "\"ggx\"", "\"@tex.value\"".
std::string value_json(const Value& value);

std::string write_document(const Document& document, const NodeRegistry& registry = NodeRegistry::builtin());

}  // namespace lamina
