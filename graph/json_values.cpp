#include "graph/json_values.h"

#include <algorithm>
#include <set>

namespace lamina {

namespace {

// Follows the parser through the document so that a syntax error and a duplicate key can be
// reported with the JSON pointer of where they happen (nlohmann only gives a byte offset).
class PathTracker {
 public:
  explicit PathTracker(std::vector<std::string>& duplicates) : duplicates_(duplicates) {}

  bool on_event(int depth, Json::parse_event_t event, const Json& parsed) {
    (void)depth;
    switch (event) {
      case Json::parse_event_t::object_start: stack_.push_back(Frame{false, 0, {}, false, {}}); break;
      case Json::parse_event_t::array_start: stack_.push_back(Frame{true, 0, {}, false, {}}); break;
      case Json::parse_event_t::key: {
        auto& top = stack_.back();
        top.key = parsed.get<std::string>();
        top.has_key = true;
        if (!top.keys.insert(top.key).second) duplicates_.push_back(pointer());
        break;
      }
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        stack_.pop_back();
        finish_value();
        break;
      case Json::parse_event_t::value: finish_value(); break;
    }
    return true;
  }

  std::string pointer() const {
    std::string out;
    for (const auto& f : stack_) {
      if (f.array)
        out = pointer_append(out, f.index);
      else if (f.has_key)
        out = pointer_append(out, f.key);
    }
    return out;
  }

 private:
  struct Frame {
    bool array;
    size_t index = 0;
    std::string key;
    bool has_key = false;
    std::set<std::string> keys;
  };
  void finish_value() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }
  std::vector<Frame> stack_;
  std::vector<std::string>& duplicates_;
};

void line_and_column(std::string_view text, size_t byte, size_t& line, size_t& column) {
  line = 1;
  column = 1;
  size_t end = std::min(byte, text.size());
  for (size_t i = 0; i + 1 < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

// nlohmann's messages start with "[json.exception...] parse error at line L, column C: ".
std::string syntax_reason(const std::string& what) {
  auto at = what.find(": ");
  return at == std::string::npos ? what : what.substr(at + 2);
}

}  // namespace

std::string json_kind(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

std::string json_describe(const Json& j) {
  if (j.is_string()) return "\"" + j.get<std::string>() + "\"";
  return json_kind(j);
}

std::optional<Json> parse_json(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                               const std::string& empty_hint) {
  std::vector<std::string> duplicates;
  PathTracker tracker(duplicates);
  Json root;
  try {
    root = Json::parse(text, [&](int depth, Json::parse_event_t event, Json& parsed) {
      return tracker.on_event(depth, event, parsed);
    });
  } catch (const Json::parse_error& e) {
    if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
      diagnostics.error(file, "", "the file is empty", empty_hint);
      return std::nullopt;
    }
    size_t line = 0, column = 0;
    line_and_column(text, e.byte, line, column);
    bool at_end = e.byte >= text.size();
    diagnostics.error(file, tracker.pointer(),
                      "malformed JSON at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " +
                          syntax_reason(e.what()),
                      at_end ? "the file ends early: is it truncated, or is a bracket left open?"
                             : "NaN, Infinity, comments and trailing commas are not JSON");
    return std::nullopt;
  } catch (const Json::out_of_range&) {
    // nlohmann refuses numbers beyond the double range (error 406) rather than returning inf.
    diagnostics.error(file, tracker.pointer(),
                      "number is not finite: it overflows the range of a double (about 1.8e308)",
                      "write a finite number");
    return std::nullopt;
  }
  for (const auto& pointer : duplicates)
    diagnostics.error(file, pointer, "duplicate key: JSON keeps only one of the two values", "remove one of them");
  return root;
}

void check_known_keys(const Json& object, const std::string& file, const std::string& pointer,
                      const std::vector<std::string>& known, Diagnostics& diagnostics) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string suggestion = closest_match(key, known);
    diagnostics.error(
        file, pointer_append(pointer, key), "unknown key \"" + key + "\"",
        suggestion.empty() ? "expected " + join_alternatives(known) : "did you mean \"" + suggestion + "\"?");
  }
}

}  // namespace lamina
