// What a GL test pass needs from a generated material besides its source: the decoded image of
// every sampler the module declares, its tables, and the uniform block when parameters are uniforms.
#pragma once

#include "glsl/gl_runner.h"
#include "graph/cpu/image.h"
#include "graph/glsl/generator.h"
#include "graph/program.h"

namespace lamina::test {

inline void bind_material(gltest::Pass& pass, const Program& program, const glsl::Module& module,
                          const glsl::MaterialInterface& mi, bool uniforms) {
  for (const glsl::TableBinding& t : module.tables) pass.textures.push_back({t.name, t.width, t.height, {}, t.texels});
  for (const glsl::SamplerBinding& b : mi.samplers)
    for (const TextureOp& op : program.ops)
      if (op.image && op.node == b.node)
        pass.textures.push_back({b.name, op.image->width, op.image->height, op.image->texels, {}});
  if (uniforms) {
    pass.uniform_block_name = mi.block;
    pass.uniform_block_data = glsl::pack_uniforms(mi);
  }
}

}  // namespace lamina::test
