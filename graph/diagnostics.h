// User-facing problems: every one names the file and the JSON pointer of the offending value.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace lamina {

enum class Severity { Error, Warning };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string file;
  std::string pointer;  // RFC 6901, "" is the whole document
  std::string message;
  std::string hint;  // optional: what to write instead
};

// "file:pointer: message (hint)" -- the one format the CLI prints, on one line: every part passes
// through printable(), so that nothing a file contains can move the cursor, colour the terminal
// or start a line that looks like another message. A pointer token (a key) longer than 64 bytes is
// printed as its start and its length.
std::string format(const Diagnostic& d);

// `text` between `mark`s, as a message quotes what a file wrote: its first 64 bytes and its length
// when it is longer, so that no hostile string makes a message kilobytes long.
std::string quote_excerpt(std::string_view text, char mark = '"');

// `text` with control characters escaped: C0 controls, DEL and C1 controls as \n, \t, \x1b,
// \u009b, and bytes that are not UTF-8 as \xHH; printable UTF-8 stays as it is.
std::string printable(std::string_view text);

// "Did you mean" suggestions by edit distance. A suggester compares at most `comparisons` pairs
// of words in all, so that a file naming a million unknown ids among a million known ones costs a
// bounded search rather than a quadratic one: the first problems get suggestions, the rest none.
class Suggester {
 public:
  explicit Suggester(size_t comparisons = kSuggestionComparisons) : left_(comparisons) {}
  // The closest candidate, or "" when nothing is close enough (or the budget is spent).
  std::string closest(std::string_view word, const std::vector<std::string>& candidates);

  static constexpr size_t kSuggestionComparisons = 100000;

 private:
  size_t left_;
};

// Errors and warnings travel separately so that callers can treat warnings as advice.
class Diagnostics {
 public:
  void error(std::string file, std::string pointer, std::string message, std::string hint = {});
  void warning(std::string file, std::string pointer, std::string message, std::string hint = {});
  void append(const Diagnostics& other);

  const std::vector<Diagnostic>& errors() const { return errors_; }
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  bool ok() const { return errors_.empty(); }

  // A suggestion for a message about this file: all of a file's suggestions share one budget.
  std::string suggest(std::string_view word, const std::vector<std::string>& candidates) {
    return suggester_.closest(word, candidates);
  }

 private:
  std::vector<Diagnostic> errors_;
  std::vector<Diagnostic> warnings_;
  Suggester suggester_;
};

// Thrown by the convenience API (lamina::load) when a file has user mistakes; carries all of them.
class Error : public std::runtime_error {
 public:
  explicit Error(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  const Diagnostic& first() const { return diagnostics_.front(); }

 private:
  std::vector<Diagnostic> diagnostics_;
};

// JSON pointer helpers (RFC 6901 escaping of '~' and '/').
void append_pointer_token(std::string& pointer, std::string_view token);  // in place: linear
std::string pointer_append(std::string_view base, std::string_view token);
std::string pointer_append(std::string_view base, size_t index);

// The closest candidate by edit distance, or "" when nothing is close enough to suggest (one
// Suggester's budget: for short lists such as parameter names and node types).
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);
// "a, b or c" for messages; a list longer than kListedAlternatives is cut, with its length:
// "a, b, ..., x and 4976 more".
std::string join_alternatives(const std::vector<std::string>& words);
inline constexpr size_t kListedAlternatives = 24;

}  // namespace lamina
