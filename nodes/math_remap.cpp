// math/remap: maps [in_min, in_max] linearly onto [out_min, out_max], optionally clamped.
#include "graph/diagnostics.h"
#include "graph/node_decl.h"

namespace lamina {

static void check_remap(const NodeCheckContext& ctx) {
  const Value* lo = ctx.get("in_min");
  const Value* hi = ctx.get("in_max");
  double in_min = lo && std::holds_alternative<double>(*lo) ? std::get<double>(*lo) : 0.0;
  double in_max = hi && std::holds_alternative<double>(*hi) ? std::get<double>(*hi) : 1.0;
  if (in_min == in_max)
    ctx.error(hi ? "in_max" : "in_min", "in_min and in_max are equal, so the input range is empty",
              "make in_max differ from in_min");
}

NodeDecl declare_math_remap() {
  NodeDecl d;
  d.type = "math/remap";
  d.kind = NodeKind::Math;
  d.doc = "out_min + (value - in_min) / (in_max - in_min) * (out_max - out_min)";
  d.params.push_back(param("value", ValueType::Float).links().described("the input"));
  d.params.push_back(param("in_min", ValueType::Float).or_default(0.0).described("input mapped to out_min"));
  d.params.push_back(param("in_max", ValueType::Float).or_default(1.0).described("input mapped to out_max"));
  d.params.push_back(param("out_min", ValueType::Float).or_default(0.0).described("output at in_min"));
  d.params.push_back(param("out_max", ValueType::Float).or_default(1.0).described("output at in_max"));
  d.params.push_back(param("clamp", ValueType::Bool)
                         .or_default(true)
                         .described("clamp the output to [min(out_min, out_max), max(out_min, out_max)]"));
  d.outputs.push_back({"value", ValueType::Float, "the remapped value"});
  d.check = check_remap;
  return d;
}

}  // namespace lamina
