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
                     "entry and what lies below it see the tilt. A linked normal shorter than 1 is a filtered "
                     "mean and widens the entry's lobe (Toksvig 2005; README, Textures)"));
}

// A constant is a direction, normalised here, so that only a texture's mean normal (shorter than 1
// where the normals it averages differ) widens the lobe (lamina_widened_slope); (0, 0, 0) is +z.
void lower_normal_param(NodeLowering& node) {
  InputRef normal = node.input("normal");
  if (!normal.linked()) {
    const float length = glm::length(normal.constant);
    normal.constant = length > 0.0f ? normal.constant / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  node.entry().normal = normal;
}

}  // namespace lamina
