// Named metals: complex index of refraction n + ik per RGB channel.
#pragma once

#include <span>
#include <string_view>

#include "graph/value.h"

namespace lamina {

struct Metal {
  std::string_view name;
  Vec3d n;
  Vec3d k;
  std::string_view source;
};

std::span<const Metal> metals();
const Metal* find_metal(std::string_view name);

}  // namespace lamina
