// What a texture or math node's emit_glsl (graph/node_decl.h) writes its op with: the resolve
// function of one material in a GLSL module, where the op's inputs are expressions (literals,
// uniform block members, or the variables of earlier ops' outputs, clamped to the declared range)
// and its outputs become local variables that later ops and the stack read.
#pragma once

#include <string>

#include "graph/program.h"

namespace lamina::glsl {

class OpWriter {
 public:
  virtual ~OpWriter() = default;

  // Input i of the op (TextureOp::inputs) as a GLSL expression of its type.
  virtual std::string input(const TextureOp& op, size_t i) = 0;
  // A member of the shading context the resolve function receives (a LaminaContext, texture.glsl):
  // "uv", "position", ...
  virtual std::string context(const std::string& member) = 0;
  // Declares output k of the op (its declaration's k-th output) as a local of the output's type,
  // initialised with `expression`; returns the local's name.
  virtual std::string output(const TextureOp& op, size_t k, const std::string& expression) = 0;
  // A local for an intermediate value, named after the node and `what`; returns its name.
  virtual std::string local(const TextureOp& op, const std::string& what, const std::string& type,
                            const std::string& expression) = 0;
  // A sampler2D uniform bound to the op's image (listed in the module's interface); returns its name.
  virtual std::string sampler(const TextureOp& op) = 0;
  // GLSL the module needs once, before its materials (helpers with GLSL-only features, such as
  // texelFetch on a sampler), under `name`: a second request with the same name adds nothing.
  virtual void module_code(const std::string& name, const std::string& text) = 0;
  // A comment line in the resolve function.
  virtual void comment(const std::string& text) = 0;
};

}  // namespace lamina::glsl
