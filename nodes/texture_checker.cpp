// texture/checker: alternating squares in uv, the classic test pattern.
#include "graph/node_decl.h"

namespace lamina {

NodeDecl declare_texture_checker() {
  NodeDecl d;
  d.type = "texture/checker";
  d.kind = NodeKind::Texture;
  d.doc = "checkerboard in uv: color_a where floor(u*sx) + floor(v*sy) is even, color_b elsewhere";
  d.params.push_back(param("color_a", ValueType::Color)
                         .range(0.0, 1.0)
                         .or_default(Vec3d{0.0, 0.0, 0.0})
                         .links()
                         .described("colour of the squares that contain uv (0, 0)"));
  d.params.push_back(param("color_b", ValueType::Color)
                         .range(0.0, 1.0)
                         .or_default(Vec3d{1.0, 1.0, 1.0})
                         .links()
                         .described("colour of the other squares"));
  d.params.push_back(param("scale", ValueType::Vec2)
                         .above(0.0)
                         .or_default(Vec2d{8.0, 8.0})
                         .described("squares per unit of u and of v"));
  d.outputs.push_back({"color", ValueType::Color, "color_a or color_b"});
  d.outputs.push_back({"value", ValueType::Float, "0 on color_a squares, 1 on color_b squares"});
  return d;
}

}  // namespace lamina
