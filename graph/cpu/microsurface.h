// Random walks over the Smith microsurface of a rough dielectric boundary (the kernels of
// nodes/kernels/microsurface.glsl): light may scatter on the boundary's facets any number of times
// before it leaves above or below (Heitz, Hanika, d'Eon and Dachsbacher 2016). Nothing is lost on
// the way, so the boundary reflects and transmits all the light it receives. The reference solver's
// interfaces.
#pragma once

#include <glm/glm.hpp>

#include "graph/cpu/pcg32.h"

namespace lamina::cpu {

// A boundary in its own frame (z the macro normal): eta = n_below / n_above, the slope m and the
// microfacet distribution and Fresnel term of the kernels.
struct MicrosurfaceBoundary {
  float eta = 1.5f;
  int distribution = 0;
  int fresnel = 0;
  float m = 0.1f;
};

struct MicrosurfaceSample {
  glm::vec3 direction{0.0f};  // where the light leaves, pointing away from the boundary; 0 if lost
  float weight = 0.0f;        // the walk's sampling weight
  int events = 0;             // how many times it scattered on the microsurface before leaving
};

// Follows light arriving from x (pointing away from the boundary, either side) over the
// microsurface until it leaves. Over many draws, weight times the indicator of a set of directions
// averages to the integral of f(x, y) |y.z| over the set, f the boundary's BSDF for radiance
// arriving from x.
MicrosurfaceSample microsurface_sample(const MicrosurfaceBoundary& b, glm::vec3 x, Pcg32& rng);

// An unbiased estimate of f(l, e) |e.z|, the boundary's BSDF for radiance arriving from l and
// leaving along e times e's cosine (sec. 5.1 of the paper: a walk from l that at every event adds
// the chance of scattering toward e and escaping).
float microsurface_eval(const MicrosurfaceBoundary& b, glm::vec3 l, glm::vec3 e, Pcg32& rng);

}  // namespace lamina::cpu
