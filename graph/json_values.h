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
#include "graph/json_type.h"

namespace lamina {

// Parses `text`; on a syntax error, an empty file, a number beyond the double range or nesting
// deeper than kMaxJsonDepth (checked first, before any tree is built) reports one error and
// returns nothing. Duplicate keys are reported and parsing goes on.
// `empty_hint` tells what the file should contain when it is empty.
std::optional<Json> parse_json(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                               const std::string& empty_hint);

// Where arrays and objects in `text` first nest deeper than `max_depth`: the JSON pointer of the
// array or object that is one level too deep, and its byte offset. A linear scan that needs no
// valid JSON (it stops at the first excess); nothing when the nesting is within the limit.
struct NestingExcess {
  std::string pointer;
  size_t offset = 0;
};
std::optional<NestingExcess> find_nesting_excess(std::string_view text, int max_depth);

// "line L, column C" of byte `offset` (1-based, columns count bytes).
std::string line_and_column_text(std::string_view text, size_t offset);

// "a number", "an object", ... for messages.
std::string json_kind(const Json& j);
// A string's value in quotes (its first 64 bytes and its length when longer), otherwise its kind.
std::string json_describe(const Json& j);

// Reports every key of `object` not in `known`, with the closest known key as a hint.
void check_known_keys(const Json& object, const std::string& file, const std::string& pointer,
                      const std::vector<std::string>& known, Diagnostics& diagnostics);

}  // namespace lamina
