// JSON parsing shared by the material and scene readers: syntax errors and duplicate keys with
// their JSON pointer and line/column, unknown keys with "did you mean". Internal to liblamina
// (it exposes nlohmann::json, which is a private dependency).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graph/diagnostics.h"

namespace lamina {

using Json = nlohmann::ordered_json;

// Parses `text`; on a syntax error, an empty file or a number beyond the double range reports
// one error and returns nothing. Duplicate keys are reported and parsing goes on.
// `empty_hint` tells what the file should contain when it is empty.
std::optional<Json> parse_json(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                               const std::string& empty_hint);

// "a number", "an object", ... for messages.
std::string json_kind(const Json& j);
// A string's value in quotes, otherwise its kind.
std::string json_describe(const Json& j);

// Reports every key of `object` not in `known`, with the closest known key as a hint.
void check_known_keys(const Json& object, const std::string& file, const std::string& pointer,
                      const std::vector<std::string>& known, Diagnostics& diagnostics);

}  // namespace lamina
