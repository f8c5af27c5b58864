#include "graph/lobes.h"

namespace lamina {

namespace {

void collect(const Program& program, int node, std::vector<LobeStep>& path, int depth, std::vector<Lobe>& out) {
  const StackNode& s = program.stack[size_t(node)];
  if (const auto* layer = std::get_if<LayerNode>(&s)) {
    out.push_back({node, path, "interface " + std::to_string(depth)});
    path.push_back({node, -1});
    collect(program, layer->base, path, depth + 1, out);
    path.pop_back();
  } else if (const auto* mix = std::get_if<MixNode>(&s)) {
    path.push_back({node, 0});
    collect(program, mix->a, path, depth, out);
    path.back().side = 1;
    collect(program, mix->b, path, depth, out);
    path.pop_back();
  } else {
    const char* kind = std::holds_alternative<LambertNode>(s)     ? "lambert"
                       : std::holds_alternative<OrenNayarNode>(s) ? "oren_nayar"
                                                                  : "conductor";
    out.push_back({node, path, "substrate " + std::to_string(depth) + " (" + kind + ")"});
  }
}

}  // namespace

std::vector<Lobe> collect_lobes(const Program& program) {
  std::vector<Lobe> lobes;
  std::vector<LobeStep> path;
  if (program.root >= 0) collect(program, program.root, path, 0, lobes);
  return lobes;
}

}  // namespace lamina
