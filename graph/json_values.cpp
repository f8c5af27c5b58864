#include "graph/json_values.h"

#include <algorithm>
#include <set>

#include "graph/limits.h"

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

  // Built in one pass: linear in the pointer's length, however deep.
  std::string pointer() const {
    std::string out;
    for (const auto& f : stack_) {
      if (f.array)
        append_pointer_token(out, std::to_string(f.index));
      else if (f.has_key)
        append_pointer_token(out, f.key);
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

// Line and column of the character before `byte` (nlohmann's offsets point one past the error).
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

void append_utf8(std::string& out, uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xc0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3f));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xe0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
    out += static_cast<char>(0x80 | (code & 0x3f));
  } else {
    out += static_cast<char>(0xf0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3f));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
    out += static_cast<char>(0x80 | (code & 0x3f));
  }
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The four hex digits at text[at..at+4) as a number, or -1.
long hex4(std::string_view text, size_t at) {
  if (at + 4 > text.size()) return -1;
  long v = 0;
  for (size_t i = at; i < at + 4; ++i) {
    const int d = hex_digit(text[i]);
    if (d < 0) return -1;
    v = v * 16 + d;
  }
  return v;
}

// Scans the string starting at the quote text[i]; returns the index after its closing quote (or
// text.size() when it is not closed) and, when `decoded` is given, its value with the escapes of
// RFC 8259 sec. 7 decoded (an invalid escape is kept as written: the parser reports it later).
size_t scan_string(std::string_view text, size_t i, std::string* decoded) {
  ++i;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '"') return i + 1;
    if (c != '\\') {
      if (decoded) *decoded += c;
      ++i;
      continue;
    }
    if (i + 1 >= text.size()) return text.size();
    const char e = text[i + 1];
    if (e == 'u') {
      long code = hex4(text, i + 2);
      size_t next = i + 6;
      if (code >= 0xd800 && code < 0xdc00 && next + 1 < text.size() && text[next] == '\\' && text[next + 1] == 'u') {
        const long low = hex4(text, next + 2);
        if (low >= 0xdc00 && low < 0xe000) {
          code = 0x10000 + ((code - 0xd800) << 10) + (low - 0xdc00);
          next += 6;
        }
      }
      if (decoded) {
        if (code >= 0)
          append_utf8(*decoded, static_cast<uint32_t>(code));
        else
          decoded->append(text.substr(i, std::min<size_t>(6, text.size() - i)));
      }
      i = code >= 0 ? next : i + 2;
      continue;
    }
    if (decoded) {
      switch (e) {
        case 'n': *decoded += '\n'; break;
        case 't': *decoded += '\t'; break;
        case 'r': *decoded += '\r'; break;
        case 'b': *decoded += '\b'; break;
        case 'f': *decoded += '\f'; break;
        default: *decoded += e;  // '"', '\\', '/'
      }
    }
    i += 2;
  }
  return text.size();
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
  if (!j.is_string()) return json_kind(j);
  const std::string& text = j.get_ref<const std::string&>();
  constexpr size_t kShown = 64;
  if (text.size() <= kShown) return "\"" + text + "\"";
  return "\"" + text.substr(0, kShown) + "...\" (a string of " + std::to_string(text.size()) + " bytes)";
}

std::optional<NestingExcess> find_nesting_excess(std::string_view text, int max_depth) {
  struct Frame {
    bool array;
    size_t index = 0;
    std::string key;
    bool expecting_key = true;  // objects: the next string is a key
  };
  std::vector<Frame> stack;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '"') {
      const bool key = !stack.empty() && !stack.back().array && stack.back().expecting_key;
      if (key) stack.back().key.clear();
      i = scan_string(text, i, key ? &stack.back().key : nullptr);
      if (key) stack.back().expecting_key = false;
      continue;
    }
    if (c == '[' || c == '{') {
      if (static_cast<int>(stack.size()) >= max_depth) {
        NestingExcess excess;
        excess.offset = i;
        for (const Frame& f : stack) append_pointer_token(excess.pointer, f.array ? std::to_string(f.index) : f.key);
        return excess;
      }
      stack.push_back(Frame{c == '[', 0, {}, true});
    } else if ((c == ']' || c == '}') && !stack.empty()) {
      stack.pop_back();
    } else if (c == ',' && !stack.empty()) {
      if (stack.back().array)
        ++stack.back().index;
      else
        stack.back().expecting_key = true;
    }
    ++i;
  }
  return std::nullopt;
}

std::string line_and_column_text(std::string_view text, size_t offset) {
  size_t line = 0, column = 0;
  line_and_column(text, offset + 1, line, column);
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::optional<Json> parse_json(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                               const std::string& empty_hint) {
  if (auto excess = find_nesting_excess(text, kMaxJsonDepth)) {
    diagnostics.error(file, excess->pointer,
                      "arrays and objects nest deeper than " + std::to_string(kMaxJsonDepth) + " levels here (" +
                          line_and_column_text(text, excess->offset) + ")",
                      "lamina reads JSON nested at most " + std::to_string(kMaxJsonDepth) + " levels deep");
    return std::nullopt;
  }
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
