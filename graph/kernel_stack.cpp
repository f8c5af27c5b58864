#include "graph/kernel_stack.h"

namespace lamina {

namespace {

bool folds_slope(const StackEntry& e, bool fold_slopes) { return fold_slopes && e.degrees && !e.scalar_y.linked(); }

}  // namespace

kernels::LaminaEntry kernel_entry(const StackEntry& s, bool fold_slopes) {
  kernels::LaminaEntry e;
  e.kind = s.kind;
  e.model = s.model;
  e.medium = s.medium;
  e.distribution = s.distribution;
  e.fresnel = s.fresnel;
  e.degrees = s.degrees && !folds_slope(s, fold_slopes) ? 1 : 0;
  e.parent = s.parent;
  e.side = s.side;
  e.first = s.first;
  e.second = s.second;
  return e;
}

kernels::LaminaInputs kernel_constants(const StackEntry& s, bool fold_slopes) {
  kernels::LaminaInputs x;
  x.colour0 = s.colour0.constant;
  x.colour1 = s.colour1.constant;
  x.colour2 = s.colour2.constant;
  x.scalars = glm::vec4(s.scalar_x.constant.x, s.scalar_y.constant.x, s.scalar_z.constant.x, s.scalar_w.constant.x);
  x.normal = s.normal.constant;
  if (folds_slope(s, fold_slopes)) x.scalars.y = kernels::lamina_slope(x.scalars.y, true);
  return x;
}

}  // namespace lamina
