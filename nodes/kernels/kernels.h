// The BRDF leaf kernels for C++: the same nodes/kernels/*.glsl files the GLSL back end embeds,
// compiled here as C++ through GLM, so CPU and shader evaluate one text of every formula.
// The API (names, argument order, conventions) is documented in the .glsl files themselves;
// common.glsl states the frame: z is the normal, wi and wo point away from the surface, BRDFs
// exclude the cosine, directions below the horizon give 0 and nothing returns NaN or inf.
//
// Macros the .glsl files rely on; both are #undef'd at the end of this header:
//   LAMINA_FN      written before every kernel function. Here `inline` (the functions live in a
//                  header); the GLSL prelude defines it empty.
//   LAMINA_OUT(T)  an output parameter of type T. Here `T&`; in GLSL `out T`.
// The GLSL prelude is `#define LAMINA_OUT(T) out T` and `#define LAMINA_FN` (plus
// `precision highp float;` for ES), followed by the files in the order included below.
//
// Everything lands in lamina::kernels, which also sees all of glm (`using namespace glm`), as GLSL
// code sees its built-ins: kernels::d_ggx(c, a), kernels::vec3, kernels::LAMINA_PI.
#pragma once

#include <glm/glm.hpp>

#define LAMINA_FN inline
#define LAMINA_OUT(T) T&

namespace lamina::kernels {
using namespace glm;

// clang-format off
// The order matters: each file uses only what the files before it define.
#include "nodes/kernels/common.glsl"
#include "nodes/kernels/fresnel.glsl"
#include "nodes/kernels/microfacet.glsl"
#include "nodes/kernels/diffuse.glsl"
#include "nodes/kernels/layer.glsl"
#include "nodes/kernels/texture.glsl"
#include "nodes/kernels/preview.glsl"
#include "nodes/kernels/stack.glsl"
// clang-format on

}  // namespace lamina::kernels

#undef LAMINA_FN
#undef LAMINA_OUT
