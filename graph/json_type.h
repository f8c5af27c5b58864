// The JSON type lamina reads and writes with: nlohmann's, keeping keys in the order a file gives
// them. One alias for every file (a private one per file clashed once unity builds put two together).
#pragma once

#include <nlohmann/json.hpp>

namespace lamina {

using Json = nlohmann::ordered_json;

}  // namespace lamina
