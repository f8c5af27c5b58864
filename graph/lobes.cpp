#include "graph/lobes.h"

#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

std::vector<Lobe> collect_lobes(const Program& program) {
  std::vector<Lobe> lobes;
  for (size_t i = 0; i < program.stack.size(); ++i) {
    const StackEntry& e = program.stack[i];
    if (e.kind == kernels::LAMINA_MIX) continue;
    // The depth is the number of layers above the entry.
    int depth = 0;
    for (int p = e.parent; p >= 0; p = program.stack[size_t(p)].parent)
      depth += program.stack[size_t(p)].kind == kernels::LAMINA_LAYER ? 1 : 0;
    std::string name;
    if (e.kind == kernels::LAMINA_LAYER) {
      name = "interface " + std::to_string(depth);
    } else {
      const std::string type = e.decl ? e.decl->type : "substrate";
      name = "substrate " + std::to_string(depth) + " (" + type.substr(type.find('/') + 1) + ")";
    }
    lobes.push_back({int(i), std::move(name)});
  }
  return lobes;
}

}  // namespace lamina
