// The kernel files split into their top-level pieces, so that a module embeds only the kernel
// functions (and the constants and macros they use) that its materials call, each one verbatim.
//
// A kernel file is cut, without loss, into consecutive pieces whose concatenation is the file:
//   Declaration  one top-level declaration (a function with its body, a constant, a #define or a
//                #if ... #endif group) together with the comment lines directly above it (no blank
//                line between), from the start of its first line to the end of its last line;
//   Comment      comment lines followed by a blank line: a file's header, or a heading for the
//                declarations after it;
//   Space        blank lines.
// What a module needs is the transitive closure, over the identifiers in the code (comments and
// number literals excluded, whole tokens only), of what the material code refers to.
#pragma once

#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "graph/glsl/kernel_sources.h"

namespace lamina::glsl {

struct KernelPiece {
  enum class Kind { Declaration, Comment, Space };
  Kind kind = Kind::Space;
  std::string_view text;             // verbatim: a view into the file's text
  size_t line = 0;                   // the file's line its text starts on, from 1
  std::vector<std::string> defines;  // the names a Declaration declares
  std::set<std::string> uses;        // the identifiers its code mentions
};

struct KernelSource {
  std::string name;  // e.g. "fresnel.glsl"
  std::vector<KernelPiece> pieces;
};

// The identifiers of GLSL code: comments, number literals (1.0e-20f) and preprocessor keywords
// after '#' are skipped; "d_ggx" is one token, never also "d" or "ggx".
std::set<std::string> identifiers(std::string_view code);

// Cuts `text` into pieces as above. Throws std::logic_error, naming `name` and the line, for what
// the cut does not support: code after a declaration on its last line, code inside #if groups,
// unbalanced brackets, or a declaration whose name cannot be found.
KernelSource split_kernel(std::string_view name, std::string_view text);

// The embedded kernel files (kernel_files()), split once.
std::span<const KernelSource> kernel_sources();

// The kernel text `code` needs, in the files' order: for every file with a needed declaration,
// the line "// ---- kernels: nodes/kernels/NAME", then its needed pieces verbatim in their order,
// then a blank line. A needed piece is a Declaration in the closure, a file's leading Comment when
// anything of the file is needed, or a later Comment when a Declaration between it and the next
// Comment is. Pieces that were neighbours in the file keep the blank lines between them; elsewhere
// one blank line separates them.
std::string needed_kernels(std::span<const KernelSource> sources, std::string_view code);

}  // namespace lamina::glsl
