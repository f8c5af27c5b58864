#include "graph/diagnostics.h"

#include <algorithm>
#include <numeric>

namespace lamina {

namespace {

// A pointer as printed: a token (a key) longer than any name lamina knows is shown by its start and
// its length, so that a hostile key cannot make every message that points near it kilobytes long.
// Diagnostic::pointer itself stays exact.
std::string shown_pointer(std::string_view pointer) {
  constexpr size_t kLongToken = 64, kShown = 32;
  std::string out;
  size_t start = 0;
  while (start < pointer.size()) {
    size_t end = pointer.find('/', start + 1);
    if (end == std::string_view::npos) end = pointer.size();
    const std::string_view token = pointer.substr(start, end - start);  // with its leading '/'
    if (token.size() > kLongToken + 1)
      out += std::string(token.substr(0, kShown + 1)) + "...(a key of " + std::to_string(token.size() - 1) + " bytes)";
    else
      out += token;
    start = end;
  }
  return out;
}

}  // namespace

std::string format(const Diagnostic& d) {
  // RFC 6901: the empty pointer is the whole document ("/" would be the member named "").
  std::string out = printable(d.file) + ":" + printable(shown_pointer(d.pointer)) + ": ";
  if (d.severity == Severity::Warning) out += "warning: ";
  out += printable(d.message);
  if (!d.hint.empty()) out += " (" + printable(d.hint) + ")";
  return out;
}

std::string quote_excerpt(std::string_view text, char mark) {
  constexpr size_t kShown = 64;
  if (text.size() <= kShown) return mark + std::string(text) + mark;
  return mark + std::string(text.substr(0, kShown)) + "..." + mark + " (a string of " + std::to_string(text.size()) +
         " bytes)";
}

std::string printable(std::string_view text) {
  static const char digits[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  auto hex_byte = [&](unsigned char b) {
    out += "\\x";
    out += digits[b >> 4];
    out += digits[b & 0xf];
  };
  for (size_t i = 0; i < text.size();) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b < 0x20 || b == 0x7f) {
      switch (b) {
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default: hex_byte(b);
      }
      ++i;
      continue;
    }
    if (b < 0x80) {
      out += static_cast<char>(b);
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, then continuation bytes (RFC 3629 sec. 4,
    // without overlong forms and surrogates).
    size_t length = b >= 0xc2 && b <= 0xdf ? 2 : b >= 0xe0 && b <= 0xef ? 3 : b >= 0xf0 && b <= 0xf4 ? 4 : 0;
    bool valid = length > 0 && i + length <= text.size();
    for (size_t k = 1; valid && k < length; ++k) valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
    if (valid && length == 3) {
      const auto b1 = static_cast<unsigned char>(text[i + 1]);
      valid = !(b == 0xe0 && b1 < 0xa0) && !(b == 0xed && b1 >= 0xa0);
    }
    if (valid && length == 4) {
      const auto b1 = static_cast<unsigned char>(text[i + 1]);
      valid = !(b == 0xf0 && b1 < 0x90) && !(b == 0xf4 && b1 >= 0x90);
    }
    if (!valid) {
      hex_byte(b);
      ++i;
      continue;
    }
    if (length == 2 && b == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0) {
      out += "\\u00";  // a C1 control, U+0080 to U+009F
      const auto c = static_cast<unsigned char>(text[i + 1]);
      out += digits[c >> 4];
      out += digits[c & 0xf];
    } else {
      out.append(text.substr(i, length));
    }
    i += length;
  }
  return out;
}

void Diagnostics::error(std::string file, std::string pointer, std::string message, std::string hint) {
  errors_.push_back({Severity::Error, std::move(file), std::move(pointer), std::move(message), std::move(hint)});
}

void Diagnostics::warning(std::string file, std::string pointer, std::string message, std::string hint) {
  warnings_.push_back({Severity::Warning, std::move(file), std::move(pointer), std::move(message), std::move(hint)});
}

void Diagnostics::append(const Diagnostics& other) {
  errors_.insert(errors_.end(), other.errors_.begin(), other.errors_.end());
  warnings_.insert(warnings_.end(), other.warnings_.begin(), other.warnings_.end());
}

static std::string first_message(const std::vector<Diagnostic>& diagnostics) {
  return diagnostics.empty() ? std::string("invalid input") : format(diagnostics.front());
}

Error::Error(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(first_message(diagnostics)), diagnostics_(std::move(diagnostics)) {}

void append_pointer_token(std::string& pointer, std::string_view token) {
  pointer += '/';
  for (char c : token) {
    if (c == '~')
      pointer += "~0";
    else if (c == '/')
      pointer += "~1";
    else
      pointer += c;
  }
}

std::string pointer_append(std::string_view base, std::string_view token) {
  std::string out(base);
  append_pointer_token(out, token);
  return out;
}

std::string pointer_append(std::string_view base, size_t index) {
  return std::string(base) + "/" + std::to_string(index);
}

static size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), size_t{0});
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t above = row[j];
      size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string Suggester::closest(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& candidate : candidates) {
    if (left_ == 0) break;
    --left_;
    // The distance is at least the difference in length: no need to compute it then.
    const size_t length_gap =
        word.size() > candidate.size() ? word.size() - candidate.size() : candidate.size() - word.size();
    if (length_gap >= best_distance) continue;
    size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  return Suggester().closest(word, candidates);
}

std::string join_alternatives(const std::vector<std::string>& words) {
  const size_t listed = words.size() > kListedAlternatives ? kListedAlternatives - 1 : words.size();
  std::string out;
  for (size_t i = 0; i < listed; ++i) {
    if (i > 0) out += (i + 1 == words.size()) ? " or " : ", ";
    out += words[i];
  }
  if (listed < words.size()) out += ", ... and " + std::to_string(words.size() - listed) + " more";
  return out;
}

}  // namespace lamina
