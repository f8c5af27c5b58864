// The JSON Schema (2020-12) of one declared parameter, shared by the schema of material files
// (a node's parameters, graph/schema.cpp) and of scene files (their keys,
// graph/scene/scene_schema.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "graph/node_decl.h"

namespace lamina {

// {"$ref": "#/$defs/<def>"}
nlohmann::ordered_json schema_ref(const std::string& def);
// The value's type and bounds, its description (with the unit) and its default; a linkable
// parameter also takes a link, and an object is the definition of its name.
nlohmann::ordered_json param_schema(const ParamDecl& p);

}  // namespace lamina
