// Small pieces of GLSL text: literals that read back as the exact float, and identifiers that
// stay legal whatever the user named a node.
#pragma once

#include <glm/glm.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace lamina::glsl {

// The shortest decimal that reads back as exactly x, as a GLSL float literal: "1.5f", "1.0f",
// "1e-05f", "-0.25f". x must be finite.
std::string float_literal(float x);
std::string vec2_literal(glm::vec2 v);
std::string vec3_literal(glm::vec3 v);
// Column by column, as GLSL and glm store a matrix.
std::string mat3_literal(const glm::mat3& m);

// `id` (a lamina identifier, [A-Za-z_][A-Za-z0-9_]*) as a part of a GLSL name: runs of '_'
// collapsed and '_' trimmed at both ends, because GLSL reserves every name containing "__".
std::string name_part(std::string_view id);

// `text` with every `from` replaced by `to`.
std::string replace_all(std::string text, std::string_view from, const std::string& to);

// A call or declaration `head(a, b, c)tail` plus a newline: on one line when it fits in 100
// columns, else one argument per line, indented four more than `head`'s leading spaces.
std::string call(const std::string& head, const std::vector<std::string>& args, const std::string& tail);

// Hands out names once: the first request for a name gets it, later ones get name_2, name_3...
class NameTable {
 public:
  std::string unique(const std::string& name);

 private:
  std::set<std::string> used_;
};

}  // namespace lamina::glsl
