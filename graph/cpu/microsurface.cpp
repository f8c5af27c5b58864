#include "graph/cpu/microsurface.h"

#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace k = kernels;
using glm::vec3;

namespace {

// Walks end after this many events; light left on the microsurface after so many is far below the
// reference's noise (each event lets it escape with a chance of at least a few percent).
constexpr int kMaxEvents = 256;

// The state of a walk. The kernels work on the upper side: on the lower side every direction is
// turned around and the height negated, and the relative index is 1 / eta.
struct State {
  bool above = true;
  vec3 travel{0.0f};  // the direction the light travels, in the side's frame
  float height = 2.0f;

  vec3 to_side(vec3 w) const { return above ? w : -w; }
  float eta(const MicrosurfaceBoundary& b) const { return above ? b.eta : 1.0f / b.eta; }
};

State start(vec3 from) {
  State s;
  s.above = from.z > 0.0f;
  s.travel = -s.to_side(from);
  return s;
}

// One scattering event at the current height: the next direction, or false if the draw is lost.
bool scatter(const MicrosurfaceBoundary& b, State& s, float& weight, Pcg32& rng) {
  float w = 0.0f;
  bool refracted = false;
  const vec3 out =
      k::lamina_phase_sample(-s.travel, s.eta(b), b.distribution, b.fresnel, b.m, rng.uniform3(), w, refracted);
  if (!(w > 0.0f)) return false;
  weight *= w;
  if (refracted) {
    s.above = !s.above;
    s.travel = -out;  // into the other side's frame
    s.height = -s.height;
  } else {
    s.travel = out;
  }
  return true;
}

}  // namespace

MicrosurfaceSample microsurface_sample(const MicrosurfaceBoundary& b, vec3 x, Pcg32& rng) {
  MicrosurfaceSample result;
  if (x.z == 0.0f) return result;
  State s = start(x);
  float weight = 1.0f;
  for (int event = 0; event < kMaxEvents; ++event) {
    s.height = k::lamina_next_height(b.distribution, s.travel, s.height, b.m, rng.uniform());
    if (s.height > 1.0f) {
      result.direction = s.to_side(s.travel);
      result.weight = weight;
      result.events = event;
      return result;
    }
    if (!scatter(b, s, weight, rng)) return result;
  }
  return result;
}

float microsurface_eval(const MicrosurfaceBoundary& b, vec3 l, vec3 e, Pcg32& rng) {
  if (l.z == 0.0f || e.z == 0.0f) return 0.0f;
  State s = start(l);
  float weight = 1.0f;
  float sum = 0.0f;
  for (int event = 0; event < kMaxEvents; ++event) {
    s.height = k::lamina_next_height(b.distribution, s.travel, s.height, b.m, rng.uniform());
    if (s.height > 1.0f) break;
    // Toward e from here: the phase function, then escaping on e's side from this height.
    const vec3 toward = s.to_side(e);
    const float phase = k::lamina_phase_eval(-s.travel, toward, s.eta(b), b.distribution, b.fresnel, b.m);
    if (phase > 0.0f) {
      const float escape = toward.z > 0.0f ? k::lamina_escape_probability(b.distribution, toward, s.height, b.m)
                                           : k::lamina_escape_probability(b.distribution, -toward, -s.height, b.m);
      sum += weight * phase * escape;
    }
    if (!scatter(b, s, weight, rng)) break;
  }
  return sum;
}

}  // namespace lamina::cpu
