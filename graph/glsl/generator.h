// The GLSL back end: compiled materials to one self-contained GLSL module (DESIGN.md, graph/glsl).
//
// A module is the #version line, a header comment, a prelude, the pieces of nodes/kernels/ that
// the materials need (the functions they call with the constants and macros those use, each
// verbatim: the text the CPU evaluator compiles as C++; see kernel_items.h) and, per material NAME:
//   vec3  lamina_NAME_eval(vec3 wi, vec3 wo, vec2 uv)     the BRDF f, no cosine
//   float lamina_NAME_pdf(vec3 wi, vec3 wo, vec2 uv)      the density sample() draws wi with
//   vec3  lamina_NAME_sample(vec3 wo, vec2 u, float u_layer, vec2 uv, out vec3 wi, out float pdf)
//                                                         draws wi, returns f(wi, wo); pdf 0: none
// in the local frame of the CPU evaluator (z the normal, directions away from the surface), with
// the layer stack unrolled into one function per stack node (GLSL has no recursion) and the lobe
// loops of sampling unrolled. Output is deterministic: same Program and options, same text.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "graph/program.h"

namespace lamina::glsl {

enum class Target { Glsl330, Glsl450, Es300 };

// "330", "450", "es300" <-> Target; parse returns false for anything else.
const char* target_name(Target target);
bool parse_target(const std::string& text, Target& target);

struct Options {
  Target target = Target::Glsl330;
  // false: every constant parameter is folded into a literal (smallest, fastest code).
  // true: constant parameters live in one std140 uniform block per material, for live editing.
  bool uniforms = false;
  // Append a fragment shader main() that draws the first material: on an analytic sphere
  // (sphere_shader.h) or on a ground plane receding to the horizon (plane_shader.h).
  enum class Shader { None, Sphere, Plane };
  Shader shader = Shader::None;
  std::string lamina_version = LAMINA_VERSION;
};

// One member of a material's uniform block (std140).
struct UniformField {
  std::string name;          // member name, "<node id>_<parameter>"
  std::string type;          // "float", "vec2" or "vec3"
  size_t offset = 0;         // bytes from the start of the block
  std::vector<float> value;  // the value from the material file (1, 2 or 3 floats)
  std::string node, parameter;
};

// A texture/image node's sampler: the host binds the image so that texelFetch returns linear
// RGBA, row 0 being the top row of the file: an RGBA32F texture of the texels as lamina decodes
// them (sRGB files with the CPU's own curve). An SRGB8_ALPHA8 texture of the file's bytes is not
// exact enough to match the CPU: Mesa llvmpipe's decoding is off by up to 2.5%.
struct SamplerBinding {
  std::string name;  // "lamina_<material>_image_<node id>"
  std::string node, file;
  int width = 0, height = 0;
};

struct MaterialInterface {
  std::string material;   // as in the file
  std::string prefix;     // "lamina_<material>" (the GLSL-safe form)
  std::string block;      // uniform block name ("<prefix>_block"), empty without --uniforms
  std::string instance;   // its instance name ("<prefix>_u")
  size_t block_size = 0;  // bytes, a multiple of 16
  std::vector<UniformField> uniforms;
  std::vector<SamplerBinding> samplers;
};

// A table the module's kernels read: the dielectric albedo of nodes/kernels/energy.glsl, which the
// energy-conserving model needs. The host binds it to `uniform highp usampler2D <name>` as an
// R16UI 2D texture of these texels, row 0 first, so that texelFetch returns them unchanged.
struct TableBinding {
  std::string name;    // "lamina_dielectric_albedo_table"
  std::string format;  // "R16UI"
  int width = 0, height = 0;
  std::vector<uint16_t> texels;  // width * height, row 0 first
  std::string contents;          // what the texels are, for the side file and the header
};

struct Module {
  std::string source;
  std::vector<MaterialInterface> materials;
  std::vector<TableBinding> tables;  // shared by the module's materials
};

// Throws std::invalid_argument for an empty list or a Program that is not valid.
Module generate(std::span<const Program> programs, const Options& options);

// The kernel a material's eval returns for its Program::model: the model's composition, as the
// CPU evaluator chooses it.
const char* composition_function(int model);

// Whether a material's GLSL evaluates its stack as its blend of parts (nodes/kernels/stack.glsl),
// one part at a time: when the stack has more entries than GLSL compilers unroll a loop for
// (kGlslUnrolledEntries, graph/limits.h) and more than one part.
bool evaluates_by_parts(const Program& program);

// The length of the loops over entries that a material's GLSL runs: its stack's entries, or its
// longest part's when it evaluates by parts.
int unrolled_entries(const Program& program);

// The uniform side file: materials, their block names, sizes, members (name, type, offset,
// value, node, parameter) and samplers, and the module's tables with their texels, as JSON text.
std::string interface_json(const Module& module, const Options& options);

// The std140 bytes of a material's block holding the file's values.
std::vector<std::byte> pack_uniforms(const MaterialInterface& material);

}  // namespace lamina::glsl
