#include "nodes/normal_param.h"

namespace lamina {

void add_normal_param(NodeDecl& decl) {
  decl.params.push_back(
      param("normal", ValueType::Vec3)
          .range(-1.0, 1.0)
          .or_default(Vec3d{0.0, 0.0, 1.0})
          .links()
          .described("the normal this boundary or base is tilted to, in tangent space (+z the surface's own normal; "
                     "normalised, z raised to at least 0.05): a flake, a glitter cell, a normal map. Only this "
                     "entry and what lies below it see the tilt"));
}

void lower_normal_param(NodeLowering& node) { node.entry().normal = node.input("normal"); }

}  // namespace lamina
