#include "graph/glsl/glsl_text.h"

#include <charconv>
#include <stdexcept>

namespace lamina::glsl {

std::string float_literal(float x) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  if (ec != std::errc() || x != x || x - x != 0.0f) throw std::invalid_argument("float_literal: not a finite float");
  std::string text(buffer, end);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text + "f";
}

std::string vec2_literal(glm::vec2 v) { return "vec2(" + float_literal(v.x) + ", " + float_literal(v.y) + ")"; }

std::string vec3_literal(glm::vec3 v) {
  return "vec3(" + float_literal(v.x) + ", " + float_literal(v.y) + ", " + float_literal(v.z) + ")";
}

std::string mat3_literal(const glm::mat3& m) {
  return "mat3(" + vec3_literal(m[0]) + ", " + vec3_literal(m[1]) + ", " + vec3_literal(m[2]) + ")";
}

std::string name_part(std::string_view id) {
  std::string out;
  for (char c : id) {
    if (c == '_' && (out.empty() || out.back() == '_')) continue;
    out += c;
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "x" : out;
}

std::string replace_all(std::string text, std::string_view from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::string call(const std::string& head, const std::vector<std::string>& args, const std::string& tail) {
  std::string line = head + "(";
  for (size_t i = 0; i < args.size(); ++i) line += (i ? ", " : "") + args[i];
  line += ")" + tail;
  if (line.size() <= 100) return line + "\n";
  std::string indent(head.find_first_not_of(' ') + 4, ' ');
  std::string text = head + "(\n";
  for (size_t i = 0; i < args.size(); ++i) text += indent + args[i] + (i + 1 < args.size() ? ",\n" : ")" + tail + "\n");
  return text;
}

std::string NameTable::unique(const std::string& name) {
  std::string candidate = name;
  for (int i = 2; used_.count(candidate); ++i) candidate = name + "_" + std::to_string(i);
  used_.insert(candidate);
  return candidate;
}

}  // namespace lamina::glsl
