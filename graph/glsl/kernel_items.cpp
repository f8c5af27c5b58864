#include "graph/glsl/kernel_items.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <stdexcept>
#include <utility>

namespace lamina::glsl {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }
bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The position after the comment starting at `at` ("//" up to, not including, the newline;
// "/*" through "*/"), or `at` itself when no comment starts there.
size_t skip_comment(std::string_view s, size_t at) {
  if (at + 1 >= s.size() || s[at] != '/') return at;
  if (s[at + 1] == '/') return std::min(s.find('\n', at), s.size());
  if (s[at + 1] == '*') {
    size_t end = s.find("*/", at + 2);
    return end == std::string_view::npos ? s.size() : end + 2;
  }
  return at;
}

// The position after the number literal starting at `at` (digits, '.', exponent and its sign,
// suffixes, hex digits).
size_t skip_number(std::string_view s, size_t at) {
  bool hex = s.substr(at, 2) == "0x" || s.substr(at, 2) == "0X";
  size_t i = at + 1;
  while (i < s.size()) {
    char c = s[i];
    bool exponent_sign = !hex && (c == '+' || c == '-') && (s[i - 1] == 'e' || s[i - 1] == 'E');
    if (!ident_char(c) && c != '.' && !exponent_sign) break;
    ++i;
  }
  return i;
}

size_t skip_identifier(std::string_view s, size_t at) {
  while (at < s.size() && ident_char(s[at])) ++at;
  return at;
}

// Cuts one file; every position is an offset into `text`, lines start after a '\n' or at 0.
class Cutter {
 public:
  Cutter(std::string_view name, std::string_view text) : name_(name), text_(text) {}

  KernelSource cut() {
    KernelSource source{std::string(name_), {}};
    size_t pos = 0;
    while (pos < text_.size()) {
      KernelPiece piece;
      piece.line = line_number(pos);
      size_t end = pos;
      Line kind = classify(pos, &end);
      if (kind == Line::Blank) {
        end = blank_run_end(pos);
        piece.kind = KernelPiece::Kind::Space;
      } else if (kind == Line::Comment) {
        size_t run_end = end, next = end;
        while (run_end < text_.size() && classify(run_end, &next) == Line::Comment) run_end = next;
        size_t after = run_end;
        Line following = run_end < text_.size() ? classify(run_end, &after) : Line::Blank;
        if (following == Line::Code || following == Line::Directive) {
          end = declaration(run_end, following, piece);
          piece.kind = KernelPiece::Kind::Declaration;
        } else {
          end = run_end;
          piece.kind = KernelPiece::Kind::Comment;
        }
      } else {
        end = declaration(pos, kind, piece);
        piece.kind = KernelPiece::Kind::Declaration;
      }
      piece.text = text_.substr(pos, end - pos);
      if (piece.kind == KernelPiece::Kind::Declaration) piece.uses = identifiers(piece.text);
      source.pieces.push_back(std::move(piece));
      pos = end;
    }
    return source;
  }

 private:
  enum class Line { Blank, Comment, Directive, Code };

  [[noreturn]] void fail(size_t pos, const std::string& why) const {
    throw std::logic_error("nodes/kernels/" + std::string(name_) + ":" + std::to_string(line_number(pos)) +
                           ": cannot split the kernel file: " + why);
  }

  size_t line_number(size_t pos) const {
    return size_t(std::count(text_.begin(), text_.begin() + std::ptrdiff_t(pos), '\n')) + 1;
  }
  size_t line_end(size_t pos) const {
    size_t nl = text_.find('\n', pos);
    return nl == std::string_view::npos ? text_.size() : nl + 1;
  }
  size_t first_non_space(size_t pos) const {
    while (pos < text_.size() && is_space(text_[pos])) ++pos;
    return pos;
  }
  size_t blank_run_end(size_t pos) const {
    size_t end = pos;
    while (end < text_.size()) {
      size_t at = first_non_space(end);
      if (at < text_.size() && text_[at] != '\n') break;
      end = line_end(end);
    }
    return end;
  }
  // Whether [pos, end of line) holds nothing but spaces and at most a comment.
  bool rest_is_blank(size_t pos) const {
    size_t at = first_non_space(pos);
    at = skip_comment(text_, at);
    at = first_non_space(at);
    return at >= text_.size() || text_[at] == '\n';
  }

  // The kind of the line starting at `pos`; *end is the start of the line after it (after the
  // last line of a /* */ comment that starts it).
  Line classify(size_t pos, size_t* end) const {
    size_t at = first_non_space(pos);
    *end = line_end(pos);
    if (at >= text_.size() || text_[at] == '\n') return Line::Blank;
    if (text_.substr(at, 2) == "//") return Line::Comment;
    if (text_.substr(at, 2) == "/*") {
      size_t after = skip_comment(text_, at);
      if (!rest_is_blank(after)) fail(pos, "code after a /* */ comment on its line");
      *end = line_end(after);
      return Line::Comment;
    }
    if (text_[at] == '#') return Line::Directive;
    return Line::Code;
  }

  // The directive keyword of the line starting at `pos` ("define", "ifndef", ...).
  std::string_view keyword(size_t pos, size_t* after) const {
    size_t at = first_non_space(first_non_space(pos) + 1);
    *after = skip_identifier(text_, at);
    return text_.substr(at, *after - at);
  }
  std::string directive_name(size_t pos) const {
    size_t after = 0;
    keyword(pos, &after);
    size_t at = first_non_space(after);
    return std::string(text_.substr(at, skip_identifier(text_, at) - at));
  }

  // Parses the declaration starting on the line at `pos`, fills piece.defines and returns the
  // start of the line after it.
  size_t declaration(size_t pos, Line kind, KernelPiece& piece) const {
    return kind == Line::Directive ? directive(pos, piece) : code(pos, piece);
  }

  size_t directive(size_t pos, KernelPiece& piece) const {
    size_t after = 0;
    std::string_view word = keyword(pos, &after);
    if (word == "if" || word == "ifdef" || word == "ifndef") {
      int depth = 0;
      for (size_t line = pos; line < text_.size();) {
        size_t next = line;
        Line kind = classify(line, &next);
        if (kind == Line::Code) fail(line, "code inside an #if group");
        if (kind == Line::Directive) {
          std::string_view w = keyword(line, &after);
          if (w == "if" || w == "ifdef" || w == "ifndef") ++depth;
          if (w == "define") piece.defines.push_back(directive_name(line));
          if (w == "endif" && --depth == 0) return next;
        }
        line = next;
      }
      fail(pos, "an #if without its #endif");
    }
    if (word != "define") fail(pos, "a #" + std::string(word) + " line declares nothing a kernel can use");
    piece.defines.push_back(directive_name(pos));
    size_t end = line_end(pos);
    // Continuation lines: the line's last character before the newline is a backslash.
    while (end < text_.size() && end >= 2 && text_[end - 2] == '\\') end = line_end(end);
    return end;
  }

  size_t code(size_t pos, KernelPiece& piece) const {
    int depth = 0;
    bool decided = false, function = false;
    std::string last, name;
    size_t i = pos;
    for (; i < text_.size(); ++i) {
      size_t skipped = skip_comment(text_, i);
      if (skipped != i) {
        i = skipped - 1;
        continue;
      }
      char c = text_[i];
      if (digit(c)) {
        i = skip_number(text_, i) - 1;
        continue;
      }
      if (ident_start(c)) {
        size_t end = skip_identifier(text_, i);
        if (depth == 0) last = std::string(text_.substr(i, end - i));
        i = end - 1;
        continue;
      }
      if (depth == 0 && !decided && (c == '(' || c == '{' || c == '[' || c == '=' || c == ';')) {
        decided = true;
        function = c == '(';
        name = last;
      }
      if (c == ',' && depth == 0 && !function) fail(i, "several declarators in one declaration");
      if (c == '(' || c == '{' || c == '[') ++depth;
      if (c == ')' || c == '}' || c == ']') {
        if (--depth < 0) fail(i, "unbalanced brackets");
        if (c == '}' && depth == 0 && function) break;
      }
      if (c == ';' && depth == 0) break;
    }
    if (i >= text_.size()) fail(pos, "a declaration without its end ('}' or ';')");
    if (name.empty()) fail(pos, "a declaration without a name");
    if (!rest_is_blank(i + 1)) fail(i, "code after a declaration on its last line");
    piece.defines.push_back(name);
    return line_end(i);
  }

  std::string_view name_, text_;
};

}  // namespace

std::set<std::string> identifiers(std::string_view code) {
  std::set<std::string> out;
  for (size_t i = 0; i < code.size();) {
    size_t skipped = skip_comment(code, i);
    if (skipped != i) {
      i = skipped;
    } else if (digit(code[i]) || (code[i] == '.' && i + 1 < code.size() && digit(code[i + 1]))) {
      i = skip_number(code, i);
    } else if (code[i] == '#') {  // the directive keyword is not a name
      size_t at = i + 1;
      while (at < code.size() && is_space(code[at])) ++at;
      i = skip_identifier(code, at);
    } else if (ident_start(code[i])) {
      size_t end = skip_identifier(code, i);
      out.insert(std::string(code.substr(i, end - i)));
      i = end;
    } else {
      ++i;
    }
  }
  return out;
}

KernelSource split_kernel(std::string_view name, std::string_view text) { return Cutter(name, text).cut(); }

std::span<const KernelSource> kernel_sources() {
  static const std::vector<KernelSource> sources = [] {
    std::vector<KernelSource> split;
    for (const KernelFile& f : kernel_files()) split.push_back(split_kernel(f.name, f.text));
    return split;
  }();
  return sources;
}

std::string needed_kernels(std::span<const KernelSource> sources, std::string_view code) {
  using Kind = KernelPiece::Kind;
  // Who declares each name (several pieces may, e.g. the two branches of an #if in a kernel).
  std::map<std::string, std::vector<std::pair<size_t, size_t>>> declared_by;
  std::vector<std::vector<bool>> needed;
  for (size_t f = 0; f < sources.size(); ++f) {
    needed.emplace_back(sources[f].pieces.size(), false);
    for (size_t p = 0; p < sources[f].pieces.size(); ++p)
      for (const std::string& name : sources[f].pieces[p].defines) declared_by[name].push_back({f, p});
  }

  std::set<std::string> seen = identifiers(code);
  std::vector<std::string> work(seen.begin(), seen.end());
  while (!work.empty()) {
    std::string name = std::move(work.back());
    work.pop_back();
    auto it = declared_by.find(name);
    if (it == declared_by.end()) continue;
    for (auto [f, p] : it->second) {
      if (needed[f][p]) continue;
      needed[f][p] = true;
      for (const std::string& used : sources[f].pieces[p].uses)
        if (seen.insert(used).second) work.push_back(used);
    }
  }

  std::string out;
  for (size_t f = 0; f < sources.size(); ++f) {
    const std::vector<KernelPiece>& pieces = sources[f].pieces;
    std::vector<bool>& keep = needed[f];
    if (std::find(keep.begin(), keep.end(), true) == keep.end()) continue;
    // Comments: the file's leading one goes with the file, a later one with the declarations up
    // to the next comment.
    bool leading = true;
    for (size_t p = 0; p < pieces.size(); ++p) {
      if (pieces[p].kind == Kind::Declaration) leading = false;
      if (pieces[p].kind != Kind::Comment) continue;
      bool any = leading;
      for (size_t q = p + 1; !any && q < pieces.size() && pieces[q].kind != Kind::Comment; ++q) any = keep[q];
      keep[p] = any;
    }
    out += "// ---- kernels: nodes/kernels/" + sources[f].name + "\n";
    size_t previous = pieces.size();  // none yet
    for (size_t p = 0; p < pieces.size(); ++p) {
      if (!keep[p] || pieces[p].kind == Kind::Space) continue;
      if (previous < pieces.size()) {
        bool neighbours = true;
        for (size_t q = previous + 1; q < p; ++q) neighbours = neighbours && pieces[q].kind == Kind::Space;
        if (neighbours)
          for (size_t q = previous + 1; q < p; ++q) out += pieces[q].text;
        else
          out += "\n";
      }
      out += pieces[p].text;
      if (out.back() != '\n') out += "\n";
      previous = p;
    }
    out += "\n";
  }
  return out;
}

}  // namespace lamina::glsl
