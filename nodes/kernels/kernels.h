// The BRDF leaf kernels for C++: the same nodes/kernels/*.glsl files the GLSL back end embeds,
// compiled here as C++ through GLM, so CPU and shader evaluate one text of every formula.
// The API (names, argument order, conventions) is documented in the .glsl files themselves;
// common.glsl states the frame: z is the normal, wi and wo point away from the surface, BRDFs
// exclude the cosine, directions below the horizon give 0 and nothing returns NaN or inf.
//
// The macros the .glsl files are written with (common.glsl lists them with their GLSL meaning) are
// defined here for C++ and #undef'd at the end of this header:
//   LAMINA_FN             inline (the functions live in a header)
//   LAMINA_OUT(T)         T&
//   LAMINA_IN(T)          const T&
//   LAMINA_IN_ARRAY(T)    const T (an array parameter `const T name[N]` is a pointer to const)
//   LAMINA_OUT_ARRAY(T)   T
//   LAMINA_STACK          kMaxStackEntries (graph/limits.h), the length of the stack's arrays
//   LAMINA_PARTS          kMaxLobes, the parts a blend may have (each part has a lobe)
//   LAMINA_BLEND          kMaxStackEntries, the length of a blend's array of mixes and parts
//   LAMINA_FILM_FRESNEL   lamina_fresnel_film, a thin film's Fresnel term (film.glsl)
//   LAMINA_FLAKE_FILM     lamina_fresnel_film, a coated flake's (flakes.glsl)
//   LAMINA_FLUORESCENCE   true: a stack may have a fluorescent base (stack.glsl, lamina_stack_glows)
// The GLSL back end embeds the files in the order included below, after `#define LAMINA_STACK`,
// `LAMINA_PARTS`, `LAMINA_BLEND`, `LAMINA_FILM_FRESNEL`, `LAMINA_FLAKE_FILM` and `LAMINA_FLUORESCENCE` and
// `precision highp float;` for ES.
//
// Everything lands in lamina::kernels, which also sees all of glm (`using namespace glm`), as GLSL
// code sees its built-ins: kernels::d_ggx(c, a), kernels::vec3, kernels::LAMINA_PI.
#pragma once

#include <glm/glm.hpp>

#include "graph/limits.h"

#define LAMINA_FN inline
#define LAMINA_OUT(T) T&
#define LAMINA_IN(T) const T&
#define LAMINA_IN_ARRAY(T) const T
#define LAMINA_OUT_ARRAY(T) T
#define LAMINA_STACK lamina::kMaxStackEntries
#define LAMINA_PARTS lamina::kMaxLobes
#define LAMINA_BLEND lamina::kMaxStackEntries
#define LAMINA_FILM_FRESNEL lamina_fresnel_film
#define LAMINA_FLAKE_FILM lamina_fresnel_film
#define LAMINA_FLUORESCENCE true

namespace lamina::kernels {
using namespace glm;

// clang-format off
// The order matters: each file uses only what the files before it define.
#include "nodes/kernels/common.glsl"
#include "nodes/kernels/fresnel.glsl"
#include "nodes/kernels/film.glsl"
#include "nodes/kernels/microfacet.glsl"
#include "nodes/kernels/diffuse.glsl"
#include "nodes/kernels/flakes.glsl"
#include "nodes/kernels/layer.glsl"
#include "nodes/kernels/albedo_grid.glsl"
// clang-format on

// The dielectric albedo table (energy.glsl), every combination, in LAMINA_ALBEDO_COMBOS blocks.
inline constexpr int LAMINA_DIELECTRIC_ALBEDO[] = {
#include "nodes/kernels/dielectric_albedo.inc"
};
static_assert(sizeof(LAMINA_DIELECTRIC_ALBEDO) / sizeof(int) == size_t(LAMINA_ALBEDO_COMBOS) * LAMINA_ALBEDO_COMBO_SIZE,
              "nodes/kernels/dielectric_albedo.inc does not match the grid of albedo_grid.glsl");
inline constexpr int LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[LAMINA_ALBEDO_COMBOS] = {
    0 * LAMINA_ALBEDO_ETAS, 1 * LAMINA_ALBEDO_ETAS, 2 * LAMINA_ALBEDO_ETAS,
    3 * LAMINA_ALBEDO_ETAS, 4 * LAMINA_ALBEDO_ETAS, 5 * LAMINA_ALBEDO_ETAS};
inline float lamina_albedo_texel(int x, int y) {
  return float(LAMINA_DIELECTRIC_ALBEDO[y * LAMINA_ALBEDO_TABLE_WIDTH + x]);
}

// clang-format off
#include "nodes/kernels/energy.glsl"
#include "nodes/kernels/boundary.glsl"
#include "nodes/kernels/microsurface.glsl"
#include "nodes/kernels/texture.glsl"
#include "nodes/kernels/procedural.glsl"
#include "nodes/kernels/preview.glsl"
#include "nodes/kernels/stack.glsl"
// clang-format on

}  // namespace lamina::kernels

#undef LAMINA_FN
#undef LAMINA_OUT
#undef LAMINA_IN
#undef LAMINA_IN_ARRAY
#undef LAMINA_OUT_ARRAY
#undef LAMINA_STACK
#undef LAMINA_PARTS
#undef LAMINA_BLEND
#undef LAMINA_FILM_FRESNEL
#undef LAMINA_FLAKE_FILM
#undef LAMINA_FLUORESCENCE
