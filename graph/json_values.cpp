#include "graph/json_values.h"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "graph/limits.h"

namespace lamina {

namespace {

// Builds the document from the parser's events while following where it is, so that a syntax
// error and a duplicate key are reported with their JSON pointer (nlohmann only gives a byte
// offset). Linear in the text: members are appended without nlohmann's search of the object (an
// ordered object searches linearly), each object's keys are indexed here, and nothing scans the
// siblings of a finished value (nlohmann's callback parser does, which is quadratic).
class DocumentBuilder {
 public:
  // nlohmann's SAX interface.
  bool null() { return value(Json(nullptr)); }
  bool boolean(bool v) { return value(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return value(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return value(Json(v)); }
  bool number_float(Json::number_float_t v, const std::string&) { return value(Json(v)); }
  bool string(std::string& v) { return value(Json(std::move(v))); }
  bool binary(Json::binary_t&) { return false; }  // not produced by the JSON parser
  bool start_object(size_t) {
    Json* object = place(Json::object());
    frames_.push_back(OpenValue{object, false, 0, {}, false, {}});
    return true;
  }
  bool key(std::string& key) {
    OpenValue& top = frames_.back();
    top.key = key;
    top.has_key = true;
    auto& members = top.value->get_ref<Json::object_t&>();
    auto [at, inserted] = top.index_of.emplace(key, members.size());
    if (inserted) {
      members.emplace_back(key, nullptr);
    } else {
      duplicates_.push_back(pointer());  // JSON keeps one value: the later one replaces the first
    }
    member_ = &(members.begin() + static_cast<std::ptrdiff_t>(at->second))->second;
    return true;
  }
  bool end_object() {
    frames_.pop_back();
    finish_value();
    return true;
  }
  bool start_array(size_t) {
    Json* array = place(Json::array());
    frames_.push_back(OpenValue{array, true, 0, {}, false, {}});
    return true;
  }
  bool end_array() { return end_object(); }
  bool parse_error(size_t position, const std::string&, const nlohmann::detail::exception& e) {
    error_position_ = position;
    error_id_ = e.id;
    error_text_ = e.what();
    return false;
  }

  // Built in one pass: linear in the pointer's length, however deep.
  std::string pointer() const {
    std::string out;
    for (const auto& f : frames_) {
      if (f.array)
        append_pointer_token(out, std::to_string(f.index));
      else if (f.has_key)
        append_pointer_token(out, f.key);
    }
    return out;
  }

  Json root;
  std::vector<std::string> duplicates_;
  size_t error_position_ = 0;
  int error_id_ = 0;
  std::string error_text_;

 private:
  struct OpenValue {
    Json* value;  // the array or object being filled
    bool array;
    size_t index = 0;  // arrays: the element being read
    std::string key;   // objects: the member being read
    bool has_key = false;
    std::unordered_map<std::string, size_t> index_of;  // objects: where each key's member is
  };

  // Where the next value goes: the root, the end of the current array, or the current member.
  // Pointers to it stay valid while it is being filled: its parent grows only after it is done.
  Json* place(Json v) {
    if (frames_.empty()) {
      root = std::move(v);
      return &root;
    }
    OpenValue& top = frames_.back();
    if (top.array) {
      auto& elements = top.value->get_ref<Json::array_t&>();
      elements.push_back(std::move(v));
      return &elements.back();
    }
    *member_ = std::move(v);
    return member_;
  }
  bool value(Json v) {
    place(std::move(v));
    finish_value();
    return true;
  }
  void finish_value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }

  std::vector<OpenValue> frames_;
  Json* member_ = nullptr;
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
  std::string reason = at == std::string::npos ? what : what.substr(at + 2);
  // The parser quotes the token it was reading, which may be a whole 100 MB string: keep its end,
  // where the error is.
  const std::string marker = "last read: '";
  const size_t token = reason.find(marker);
  constexpr size_t kShown = 64;
  if (token != std::string::npos) {
    const size_t begin = token + marker.size();
    const size_t length = reason.size() - begin - (reason.back() == '\'' ? 1 : 0);
    if (length > kShown)
      reason = reason.substr(0, begin) + "..." + reason.substr(begin + length - kShown, kShown) + "' (the last " +
               std::to_string(kShown) + " of " + std::to_string(length) + " bytes)";
  }
  return reason;
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
  return quote_excerpt(j.get_ref<const std::string&>());
}

std::optional<NestingExcess> find_nesting_excess(std::string_view text, int max_depth) {
  struct OpenBracket {
    bool array;
    size_t index = 0;
    std::string key;
    bool expecting_key = true;  // objects: the next string is a key
  };
  std::vector<OpenBracket> stack;
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
        for (const OpenBracket& f : stack)
          append_pointer_token(excess.pointer, f.array ? std::to_string(f.index) : f.key);
        return excess;
      }
      stack.push_back(OpenBracket{c == '[', 0, {}, true});
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
  DocumentBuilder builder;
  if (Json::sax_parse(text, &builder)) {
    for (const auto& pointer : builder.duplicates_)
      diagnostics.error(file, pointer, "duplicate key: JSON keeps only one of the two values", "remove one of them");
    return std::move(builder.root);
  }
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    diagnostics.error(file, "", "the file is empty", empty_hint);
    return std::nullopt;
  }
  if (builder.error_id_ == 406) {
    // nlohmann refuses numbers beyond the double range (error 406) rather than returning inf.
    diagnostics.error(file, builder.pointer(),
                      "number is not finite: it overflows the range of a double (about 1.8e308)",
                      "write a finite number");
    return std::nullopt;
  }
  size_t line = 0, column = 0;
  line_and_column(text, builder.error_position_, line, column);
  const bool at_end = builder.error_position_ >= text.size();
  diagnostics.error(file, builder.pointer(),
                    "malformed JSON at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " +
                        syntax_reason(builder.error_text_),
                    at_end ? "the file ends early: is it truncated, or is a bracket left open?"
                           : "NaN, Infinity, comments and trailing commas are not JSON");
  return std::nullopt;
}

void check_known_keys(const Json& object, const std::string& file, const std::string& pointer,
                      const std::vector<std::string>& known, Diagnostics& diagnostics) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string suggestion = closest_match(key, known);
    diagnostics.error(
        file, pointer_append(pointer, key), "unknown key " + quote_excerpt(key),
        suggestion.empty() ? "expected " + join_alternatives(known) : "did you mean \"" + suggestion + "\"?");
  }
}

}  // namespace lamina
