// A node type declares its parameters and outputs once, as data. The checker, the JSON Schema,
// `lamina nodes` and the reference tables are all derived from these declarations.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "graph/file_access.h"
#include "graph/value.h"

namespace lamina {

class Diagnostics;
class Graph;
class NodeLowering;
struct Node;
struct ShadingContext;
struct TextureOp;
namespace glsl {
class OpWriter;
}

enum class NodeKind { Interface, Medium, Substrate, Layer, Mix, Select, Texture, Math };

std::string_view kind_name(NodeKind kind);

struct ParamDecl {
  std::string name;
  ValueType type = ValueType::Float;
  std::string unit;  // "" for unitless; stated in the doc tables
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;                  // lo < value instead of lo <= value
  bool hi_open = false;                  // value < hi instead of value <= hi
  double min_magnitude = 0.0;            // each number's |value| at least this; 0: no such bound
  size_t max_length = 0;                 // String: at most this many characters (Unicode code points); 0: any
  std::optional<Value> fallback;         // the default; none: required unless optional or part of an Alternatives
  bool omissible = false;                // may be left out though it has no default (absent means none)
  std::vector<std::string> choices;      // for ValueType::Enum
  std::vector<std::string> choice_docs;  // empty, or one line per choice for the references
  bool linkable = false;                 // may be "@node.output" instead of a constant
  std::string doc;

  // Builders, so that a declaration reads as one expression.
  ParamDecl& range(double low, double high);
  ParamDecl& above(double low);     // low < value, no upper bound
  ParamDecl& at_least(double low);  // low <= value, no upper bound
  ParamDecl& at_most(double high);  // value <= high, keeping the lower bound
  ParamDecl& below(double high);    // value < high, keeping the lower bound
  ParamDecl& magnitude_at_least(double m);
  ParamDecl& at_most_characters(size_t n);
  ParamDecl& in_unit(std::string u);
  ParamDecl& or_default(Value v);
  ParamDecl& optional();  // no default, and none needed: e.g. an infinite far plane when left out
  ParamDecl& one_of(std::vector<std::string> options);
  // The choices with a line each (what the value means, its constants, their source).
  ParamDecl& one_of_described(std::vector<std::pair<std::string, std::string>> options);
  ParamDecl& links();
  ParamDecl& described(std::string text);

  bool required() const { return !fallback.has_value() && !omissible; }
  bool has_range() const;
  bool in_range(double v) const;   // within lo and hi, and of at least min_magnitude
  std::string range_text() const;  // "1 <= ior <= 4"
  // The range with `label` for the name ("-1e+09 <= scale[1] <= 1e+09, |scale[1]| >= 1e-06").
  std::string range_text(std::string_view label) const;
  // What a value of the declared type looks like, for "expected ..." messages: "a number", "an RGB
  // colour [r, g, b]", "one of a, b or c".
  std::string expected_text() const;
};

ParamDecl param(std::string name, ValueType type);

// The declaration called `name` in `params`; nullptr when there is none.
const ParamDecl* find_param(const std::vector<ParamDecl>& params, std::string_view name);
std::vector<std::string> param_names(const std::vector<ParamDecl>& params);

struct OutputDecl {
  std::string name;
  ValueType type;
  std::string doc;
};

// Sets of parameters of which exactly one set is given (or at most one, when optional):
// e.g. {roughness_deg} or {alpha}; {metal} or {n, k}.
struct Alternatives {
  std::vector<std::vector<std::string>> sets;
  bool optional = false;
};

// What a node-specific rule sees: the node's constants and a way to report against them.
struct NodeCheckContext {
  const Node& node;
  const std::string& file;          // the material file, for messages and relative paths
  const std::string& node_pointer;  // "/materials/0/nodes/3"
  Diagnostics& diagnostics;
  const AssetPolicy& policy;  // how file parameters are followed (file_access.h)

  const Value* get(std::string_view name) const;
  // A constant parameter's value in one channel (a single number counts for all three), `fallback`
  // when the file leaves it out; nullopt when it is linked (a texture's values are taken in range at
  // shading time instead).
  std::optional<double> constant_channel(std::string_view name, int channel, double fallback) const;
  void error(std::string_view param, std::string message, std::string hint = {}) const;
};

using NodeCheck = void (*)(const NodeCheckContext&);

// A node's behaviour in every back end (DESIGN.md, "A node owns its behaviour"); its file sets
// these next to its declaration.
//   lower      every node: how it becomes part of a Program (graph/lowering.h): a texture or math
//              node fills its TextureOp; an interface, medium, substrate, layer or mix fills its
//              part of a stack entry with the kernels' model codes and inputs.
//   run        texture and math nodes: their op on the CPU, from and into the register file.
//   emit_glsl  texture and math nodes: their op as GLSL (graph/glsl/op_writer.h).
// Stack nodes need no run or emit_glsl: the kernels' composition evaluates their entries in every
// back end. The glTF export writes every node losslessly in LAMINA_materials_layered and bakes the
// material into its fitted PBR fallback; `gltf` says what a node adds to that.
using NodeLower = void (*)(NodeLowering&);
using NodeRun = void (*)(const TextureOp&, const ShadingContext&, float* registers);
using NodeEmitGlsl = void (*)(const TextureOp&, glsl::OpWriter&);
// A texture node's finest detail over uv, in features per uv unit (cells, checks, a noise's
// highest octave, an image's texels): what the glTF fallback's bake resolution follows. 0 for a
// pattern over position, which no uv image holds.
using NodeUvDetail = float (*)(const TextureOp&);

// What classification (graph/classify.h) asks of a medium: whether it tints what passes through
// it, and why, in words for the reason line.
struct Tint {
  bool tinted = false;
  std::string why;
};
using NodeTint = Tint (*)(const Graph&, size_t node);

struct NodeDecl {
  std::string type;  // "kind/name", or "layer" and "mix"
  NodeKind kind = NodeKind::Texture;
  std::string doc;
  std::vector<ParamDecl> params;
  std::vector<OutputDecl> outputs;  // the first is the default output of a link "@id"
  std::vector<Alternatives> alternatives;
  NodeCheck check = nullptr;  // rules beyond single values (files exist, in_min != in_max, ...)

  NodeLower lower = nullptr;
  NodeRun run = nullptr;
  NodeEmitGlsl emit_glsl = nullptr;
  NodeUvDetail uv_detail = nullptr;  // texture nodes with detail of their own over uv
  // A texture node whose outputs depend on the shading point, not only on its inputs: never folded
  // into constants at compile time, even when every input is constant.
  bool varies = false;
  // Facts for classification: a substrate that is a metal base (the course's metal classes d to g),
  // what the reason calls it ("metal", or "flake" for a paint of metal or mica flakes); a medium's
  // tint (none: clear).
  bool metal = false;
  std::string metal_noun = "metal";
  NodeTint tint = nullptr;
  // How glTF carries the node beyond the lossless extension (README, "glTF 2.0").
  std::string gltf = "baked into the fitted PBR fallback";

  const ParamDecl* find_param(std::string_view name) const;
  const OutputDecl* find_output(std::string_view name) const;  // "" is the default output
  bool in_alternative(std::string_view name) const;
  std::vector<std::string> param_names() const;
  std::vector<std::string> output_names() const;
};

}  // namespace lamina
