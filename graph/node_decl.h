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
struct Node;

enum class NodeKind { Interface, Medium, Substrate, Layer, Mix, Texture, Math };

std::string_view kind_name(NodeKind kind);

struct ParamDecl {
  std::string name;
  ValueType type = ValueType::Float;
  std::string unit;  // "" for unitless; stated in the doc tables
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;                  // lo < value instead of lo <= value
  std::optional<Value> fallback;         // the default; none: required unless part of an Alternatives
  std::vector<std::string> choices;      // for ValueType::Enum
  std::vector<std::string> choice_docs;  // empty, or one line per choice for the references
  bool linkable = false;                 // may be "@node.output" instead of a constant
  std::string doc;

  // Builders, so that a declaration reads as one expression.
  ParamDecl& range(double low, double high);
  ParamDecl& above(double low);     // low < value, no upper bound
  ParamDecl& at_least(double low);  // low <= value, no upper bound
  ParamDecl& at_most(double high);  // value <= high, keeping the lower bound
  ParamDecl& in_unit(std::string u);
  ParamDecl& or_default(Value v);
  ParamDecl& one_of(std::vector<std::string> options);
  // The choices with a line each (what the value means, its constants, their source).
  ParamDecl& one_of_described(std::vector<std::pair<std::string, std::string>> options);
  ParamDecl& links();
  ParamDecl& described(std::string text);

  bool required() const { return !fallback.has_value(); }
  bool has_range() const;
  std::string range_text() const;  // "1 <= ior <= 4"
};

ParamDecl param(std::string name, ValueType type);

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
  void error(std::string_view param, std::string message, std::string hint = {}) const;
};

using NodeCheck = void (*)(const NodeCheckContext&);

struct NodeDecl {
  std::string type;  // "kind/name", or "layer" and "mix"
  NodeKind kind = NodeKind::Texture;
  std::string doc;
  std::vector<ParamDecl> params;
  std::vector<OutputDecl> outputs;  // the first is the default output of a link "@id"
  std::vector<Alternatives> alternatives;
  NodeCheck check = nullptr;  // rules beyond single values (files exist, in_min != in_max, ...)

  const ParamDecl* find_param(std::string_view name) const;
  const OutputDecl* find_output(std::string_view name) const;  // "" is the default output
  bool in_alternative(std::string_view name) const;
  std::vector<std::string> param_names() const;
  std::vector<std::string> output_names() const;
};

}  // namespace lamina
