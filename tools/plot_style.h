// The colours of `lamina plot`, in display-referred sRGB values as written to the file: the
// figure, the slice panels, the sphere's panel and the text share them.
#pragma once

#include <array>
#include <glm/glm.hpp>

#include "nodes/kernels/kernels.h"

namespace lamina::cli::plot {

inline constexpr glm::vec3 kFigureBackground(0.105f, 0.108f, 0.118f);
inline constexpr glm::vec3 kPlotBackground(0.028f, 0.029f, 0.034f);
// The preview's own background (nodes/kernels/preview.glsl), so that the sphere's square merges
// into its panel.
inline const glm::vec3 kSphereBackground = kernels::LAMINA_PREVIEW_BACKGROUND;
inline constexpr glm::vec3 kGrid(0.19f, 0.195f, 0.215f);
inline constexpr glm::vec3 kFrame(0.42f, 0.43f, 0.46f);
inline constexpr glm::vec3 kMirror(0.62f, 0.62f, 0.66f);
inline constexpr glm::vec3 kText(0.9f, 0.9f, 0.92f);
inline constexpr glm::vec3 kTextDim(0.62f, 0.63f, 0.67f);
// The channel curves add up, so where they coincide red + green + blue is white and red + green
// is yellow; blue and red are lifted a little so that they read on the dark background.
inline constexpr std::array<glm::vec3, 3> kChannel = {glm::vec3(1.0f, 0.12f, 0.08f), glm::vec3(0.0f, 0.95f, 0.0f),
                                                      glm::vec3(0.12f, 0.3f, 1.0f)};

}  // namespace lamina::cli::plot
