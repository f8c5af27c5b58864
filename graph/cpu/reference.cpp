#include "graph/cpu/reference.h"

#include "graph/cpu/microsurface.h"
#include "graph/cpu/pcg32.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace lamina::cpu {

namespace k = kernels;
using glm::dvec3;
using glm::mat3;
using glm::vec3;

namespace {

// SplitMix64's finaliser (Steele, Lea and Flood 2014): every input bit affects every output bit.
uint64_t mix64(uint64_t x) {
  x = (x ^ (x >> 30u)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27u)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31u);
}

uint64_t hash_directions(vec3 a, vec3 b, uint64_t seed) {
  uint64_t h = mix64(seed + 0x9e3779b97f4a7c15ull);
  for (float x : {a.x, a.y, a.z, b.x, b.y, b.z}) h = mix64(h ^ std::bit_cast<uint32_t>(x));
  return h;
}

// A boundary the walk meets: a layer's interface from above or below, or a substrate from above.
struct Vertex {
  int entry = -1;
  bool from_below = false;
};

// Per-walk contributions summed in double by Welford's method (Welford 1962): the spread stays
// exact when every walk returns the same value, however many there are.
struct Tally {
  dvec3 mean{0.0}, m2{0.0}, truncated{0.0};
  int64_t walks = 0, truncated_walks = 0;
  void add(vec3 x) {
    ++walks;
    const dvec3 d = dvec3(x) - mean;
    mean += d / double(walks);
    m2 += d * (dvec3(x) - mean);
  }
  ReferenceEstimate result() const {
    ReferenceEstimate r;
    r.walks = walks;
    r.truncated_walks = truncated_walks;
    if (walks == 0) return r;
    const double n = double(walks);
    r.value = mean;
    r.truncated = truncated / n;
    if (walks > 1) r.std_error = glm::sqrt(glm::max(m2 / (n - 1.0), dvec3(0.0)) / n);
    return r;
  }
};

// Walks a stack at one shading point. Directions are in the stack's frame (z up) and, at a
// vertex, point away from it: e back along the walk (toward the viewer's side), l toward the
// light's.
class Walk {
 public:
  Walk(const ShadingPoint::Stack& stack, Pcg32& rng) : s_(stack), rng_(rng) {}

  const k::LaminaEntry& entry(int i) const { return s_.entries[i]; }
  const k::LaminaParams& params(int i) const { return s_.params[i]; }
  bool is_layer(int i) const { return entry(i).kind == k::LAMINA_LAYER; }
  // An interface between equal indices neither reflects nor bends: light passes straight through.
  bool invisible(int layer) const { return params(layer).eta == 1.0f; }
  // The absolute index of a medium (-1: the outside, 1).
  float index(int medium) const { return medium < 0 ? 1.0f : params(medium).ior; }

  // The entry below medium `medium` (-1: the outside) that light going down meets, each mix it
  // passes resolved by a fresh random choice.
  int resolve_down(int medium) {
    int c = medium < 0 ? 0 : entry(medium).first;
    while (c >= 0 && entry(c).kind == k::LAMINA_MIX)
      c = rng_.uniform() < params(c).weight ? entry(c).second : entry(c).first;
    return c;
  }

  // The medium above a layer's interface: its nearest layer ancestor, -1 for the outside.
  int medium_above(int layer) const {
    int p = entry(layer).parent;
    while (p >= 0 && !is_layer(p)) p = entry(p).parent;
    return p;
  }

  vec3 crossing(int medium, vec3 w) const {
    if (medium < 0) return vec3(1.0f);
    return k::lamina_crossing_transmittance(params(medium).absorption, params(medium).thickness, w.z);
  }

  MicrosurfaceBoundary boundary(int layer) const {
    const k::LaminaEntry& x = entry(layer);
    const k::LaminaParams& p = params(layer);
    return MicrosurfaceBoundary{p.eta, x.distribution, x.fresnel, p.m};
  }

  // What a vertex reflects toward e of light `light` arriving from l, RGB: an interface's f by one
  // walk over its microsurface (an unbiased estimate), a substrate's exactly (a fluorescent one's
  // matrix, lamina_substrate_response).
  vec3 f(const Vertex& v, vec3 l, vec3 e, vec3 light) {
    const k::LaminaEntry& x = entry(v.entry);
    if (x.kind == k::LAMINA_LAYER)
      return vec3(microsurface_eval(boundary(v.entry), l, e, rng_) / std::abs(e.z)) * light;
    if (l.z <= 0.0f || e.z <= 0.0f) return vec3(0.0f);
    return k::lamina_substrate_response(x, params(v.entry), l, e, light, false, true);
  }

  // What the balance heuristic weighs a vertex's draws by: a substrate's exact density; for an
  // interface, whose walks have no closed-form density, its single-scattering density
  // (lamina_boundary_pdf), which is close to it where it matters (narrow lobes). Any weights that
  // sum to 1 over the strategies keep the estimate unbiased (Veach 1997, sec. 9.2).
  float weighing_density(const Vertex& v, vec3 y, vec3 x) const {
    const k::LaminaEntry& e = entry(v.entry);
    const k::LaminaParams& p = params(v.entry);
    if (e.kind == k::LAMINA_LAYER) return k::lamina_boundary_pdf(y, x, p.eta, e.distribution, e.fresnel, p.m);
    if (y.z <= 0.0f || x.z <= 0.0f) return 0.0f;
    if (e.model == k::LAMINA_SUBSTRATE_CONDUCTOR) return k::lamina_reflection_density(e.distribution, p.m, x, y);
    // A flake paint's glitter drawn as a conductor's lobe, its shade cosine-weighted.
    const float glitter = k::lamina_flake_share(e, p);
    if (glitter > 0.0f)
      return glitter * k::lamina_reflection_density(e.distribution, p.m, x, y) + (1.0f - glitter) * k::pdf_cosine(y.z);
    return k::pdf_cosine(y.z);
  }

  struct Scatter {
    vec3 y{0.0f};          // the light's side, pointing away from the vertex; 0 if the draw is lost
    vec3 weight{0.0f};     // f(y, x) |y.z| / density: what the viewer's path is multiplied by
    bool glowing = false;  // a fluorescent base: the weight is the matrix
    mat3 matrix{0.0f};
  };

  // A direction the vertex scatters x (the viewer's side) into, and the path's weight. An
  // interface's walk from x averages f(x, y) |y.z|; radiance from y to x is f(y, x) =
  // f(x, y) n_x^2 / n_y^2 (boundary.glsl), hence the ratio of the squared indices.
  Scatter scatter(const Vertex& v, vec3 x) {
    Scatter out;
    const k::LaminaEntry& e = entry(v.entry);
    const k::LaminaParams& p = params(v.entry);
    if (e.kind == k::LAMINA_LAYER) {
      const MicrosurfaceSample drawn = microsurface_sample(boundary(v.entry), x, rng_);
      if (drawn.direction == vec3(0.0f)) return out;
      const float n_x = k::lamina_side_index(x, p.eta), n_y = k::lamina_side_index(drawn.direction, p.eta);
      out.y = drawn.direction;
      out.weight = vec3(drawn.weight * (n_x * n_x) / (n_y * n_y));
      return out;
    }
    if (x.z <= 0.0f) return out;
    const vec3 u = rng_.uniform3();
    vec3 y = k::sample_cosine(glm::vec2(u.x, u.y));
    if (e.model == k::LAMINA_SUBSTRATE_CONDUCTOR || u.z < k::lamina_flake_share(e, p)) {
      const vec3 h = k::sample_microfacet_normal(e.distribution, p.m, glm::vec2(u.x, u.y));
      const float x_h = glm::dot(x, h);
      y = x_h > 0.0f ? 2.0f * x_h * h - x : vec3(0.0f);
      if (!(y.z > 0.0f)) return out;
      y = glm::normalize(y);
    }
    const float density = weighing_density(v, y, x);
    if (!(density > 0.0f)) return out;
    out.y = y;
    out.weight = k::lamina_substrate_eval(e, p, y, x) * y.z / density;
    out.glowing = p.glowing;
    out.matrix = p.glow * (y.z / density);
    return out;
  }

  Pcg32& rng() { return rng_; }

 private:
  const ShadingPoint::Stack& s_;
  Pcg32& rng_;
};

// What a walk sees above its top interface: the index-matched layers it passed on the way in
// (their media attenuate each crossing but nothing reflects there) and the first boundary that
// does. With a mix on the way, each walk resolves its own.
struct Top {
  int entry = -1;  // a visible layer or a substrate
  std::array<int, kMaxStackEntries> clear_media{};
  int clear_count = 0;

  vec3 outside_crossing(const Walk& w, vec3 dir) const {
    vec3 t(1.0f);
    for (int i = 0; i < clear_count; ++i) t *= w.crossing(clear_media[size_t(i)], dir);
    return t;
  }
};

Top find_top(Walk& w) {
  Top top;
  int c = w.resolve_down(-1);
  while (c >= 0 && w.is_layer(c) && w.invisible(c)) {
    top.clear_media[size_t(top.clear_count++)] = c;
    c = w.resolve_down(c);
  }
  top.entry = c;
  return top;
}

// A walk's throughput: per channel (vec3) where every vertex keeps each channel to itself, or the
// matrix product of its vertices (mat3) through a fluorescent base, which moves light between
// channels. What the path delivers of light L reaching its last vertex is throughput(L).
void attenuate(vec3& beta, vec3 w) { beta *= w; }
void attenuate(mat3& beta, vec3 w) {
  beta[0] *= w.x;
  beta[1] *= w.y;
  beta[2] *= w.z;
}
void attenuate(vec3& beta, const Walk::Scatter& s) { beta *= s.weight; }
void attenuate(mat3& beta, const Walk::Scatter& s) {
  if (s.glowing)
    beta = beta * s.matrix;
  else
    attenuate(beta, s.weight);
}
vec3 deliver(vec3 beta, vec3 light) { return beta * light; }
vec3 deliver(const mat3& beta, vec3 light) { return beta * light; }
// What the throughput delivers of white light, for roulette and the truncation tally.
vec3 white(vec3 beta) { return beta; }
vec3 white(const mat3& beta) { return beta * vec3(1.0f); }

// Where a walk travelling along d in `medium` meets its next vertex, passing index-matched
// interfaces (and attenuating by the media it crosses on the way). Returns the vertex; `medium`
// becomes the medium the vertex is met from and beta takes the crossings.
template <class Beta>
Vertex next_vertex(Walk& w, int& medium, vec3 d, Beta& beta) {
  attenuate(beta, w.crossing(medium, d));
  if (d.z > 0.0f) {
    while (w.invisible(medium)) {
      medium = w.medium_above(medium);
      attenuate(beta, w.crossing(medium, d));
    }
    return Vertex{medium, true};
  }
  int c = w.resolve_down(medium);
  while (w.is_layer(c) && w.invisible(c)) {
    medium = c;
    attenuate(beta, w.crossing(medium, d));
    c = w.resolve_down(medium);
  }
  return Vertex{c, false};
}

// The medium a vertex sends y into.
int medium_after(const Walk& w, const Vertex& v, int medium, vec3 y) {
  if (!w.is_layer(v.entry)) return medium;
  if (v.from_below) return y.z > 0.0f ? w.medium_above(v.entry) : medium;
  return y.z < 0.0f ? v.entry : medium;
}

// Whether light leaving vertex v upward (in the medium above it) reaches the top interface from
// below without meeting another boundary, and the transmittance along direction `up` if so.
bool reaches_top(const Walk& w, const Vertex& v, int medium, int top, vec3 up, vec3& transmittance) {
  int m = v.from_below ? w.medium_above(v.entry) : medium;
  transmittance = vec3(1.0f);
  while (m != top) {
    if (m < 0 || !w.invisible(m)) return false;
    transmittance *= w.crossing(m, up);
    m = w.medium_above(m);
  }
  transmittance *= w.crossing(top, up);
  return true;
}

float max_component(vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

// Russian roulette after a few events: survive with probability max(beta) n^2 (at most 1), weight
// divided by it, so the expectation is unchanged. beta carries radiance, which a ray entering a
// medium of index n divides by n^2 and gets back on leaving it; beta n^2 is the energy still
// travelling. (Rouletting on beta alone killed every other lossless walk in a medium of index 1.35
// and sent the survivors out with weight 1.82: four times the albedo's variance.)
template <class Beta>
bool survives(Walk& w, int depth, int medium, Beta& beta) {
  if (depth < 8) return true;
  const float n = w.index(medium);
  const float q = std::min(max_component(white(beta)) * n * n, 1.0f);
  if (!(q > 0.0f) || w.rng().uniform() >= q) return false;
  beta /= q;
  return true;
}

// One walk's estimate of what is reflected of light `incident` from wi toward wo (both in the upper
// hemisphere, in the stack's frame). Beta: the throughput's type (vec3, or mat3 through a fluorescent base).
template <class Beta>
vec3 walk_eval(Walk& w, vec3 wi, vec3 wo, vec3 incident, int max_depth, Tally& tally) {
  const Top top = find_top(w);
  if (top.entry < 0) return vec3(0.0f);
  // The clear media above the top attenuate the light on its way in and out.
  const vec3 light_in = top.outside_crossing(w, wi) * incident;
  const vec3 outside = top.outside_crossing(w, wo);
  const Vertex top_above{top.entry, false};
  // Reflection at the top boundary: one walk over its microsurface, or a substrate's exact value.
  vec3 f = w.f(top_above, wi, wo, light_in);
  if (!w.is_layer(top.entry)) return outside * f;
  const int t = top.entry;

  // The light's side: a direction d into the top medium drawn by a walk from wi over the top's
  // microsurface. Its weight averages f(wi, d) |d.z|, so f(wi, d) is estimated by weight / |d.z|.
  const MicrosurfaceSample light = microsurface_sample(w.boundary(t), wi, w.rng());
  const bool joinable = light.direction.z < 0.0f;
  const float light_density = joinable ? w.weighing_density(top_above, light.direction, wi) : 0.0f;
  const float light_weight = joinable ? light.weight / std::abs(light.direction.z) : 0.0f;

  // The viewer's side: into the top medium from wo (a reflection is the top's, counted above).
  const Walk::Scatter enter = w.scatter(top_above, wo);
  if (!(enter.y.z < 0.0f)) return outside * f;
  Beta beta(1.0f);
  attenuate(beta, enter);
  vec3 d = enter.y;
  int medium = t;
  float last_density = 0.0f;  // the weighing density of the last vertex's draw of d

  for (int depth = 0;; ++depth) {
    if (depth >= max_depth) {
      tally.truncated += dvec3(white(beta));
      ++tally.truncated_walks;
      break;
    }
    const Vertex v = next_vertex(w, medium, d, beta);
    const vec3 e = -d;
    if (v.entry == t && v.from_below) {
      // Reached the top from below: leave toward wi, weighed against the light side's draw of d.
      const float light_here = w.weighing_density(top_above, e, wi);
      const float weight = last_density + light_here > 0.0f ? last_density / (last_density + light_here) : 1.0f;
      f += deliver(beta, w.f(v, wi, e, light_in * weight));
    } else if (joinable) {
      // Join the light side's direction here if nothing lies between this vertex and the top.
      const vec3 up = -light.direction;
      vec3 transmittance;
      if (reaches_top(w, v, medium, t, up, transmittance)) {
        const float own = w.weighing_density(v, up, e);
        const float weight = light_density + own > 0.0f ? light_density / (light_density + own) : 0.0f;
        if (weight > 0.0f)
          f += deliver(beta, w.f(v, up, e, light_in * (std::abs(up.z) * light_weight * weight) * transmittance));
      }
    }
    const Walk::Scatter next = w.scatter(v, e);
    if (next.y == vec3(0.0f)) break;
    attenuate(beta, next);
    if (v.entry == t && v.from_below && next.y.z > 0.0f) break;  // left through the top: counted above
    medium = medium_after(w, v, medium, next.y);
    last_density = w.weighing_density(v, next.y, e);
    d = next.y;
    if (!survives(w, depth, medium, beta)) break;
  }
  return outside * f;
}

// One walk's estimate of the albedo seen from wo under light `light` from every direction: the weight
// with which it leaves.
template <class Beta>
vec3 walk_albedo(Walk& w, vec3 wo, vec3 light, int max_depth, Tally& tally) {
  const Top top = find_top(w);
  if (top.entry < 0) return vec3(0.0f);
  const vec3 in = top.outside_crossing(w, wo);
  const Walk::Scatter enter = w.scatter(Vertex{top.entry, false}, wo);
  if (enter.y == vec3(0.0f)) return vec3(0.0f);
  Beta beta(1.0f);
  attenuate(beta, enter);
  if (enter.y.z > 0.0f) return in * deliver(beta, top.outside_crossing(w, enter.y) * light);
  vec3 d = enter.y;
  int medium = top.entry;
  for (int depth = 0;; ++depth) {
    if (depth >= max_depth) {
      tally.truncated += dvec3(in * white(beta));
      ++tally.truncated_walks;
      return vec3(0.0f);
    }
    const Vertex v = next_vertex(w, medium, d, beta);
    const Walk::Scatter next = w.scatter(v, -d);
    if (next.y == vec3(0.0f)) return vec3(0.0f);
    attenuate(beta, next);
    if (v.entry == top.entry && v.from_below && next.y.z > 0.0f)
      return in * deliver(beta, top.outside_crossing(w, next.y) * light);
    medium = medium_after(w, v, medium, next.y);
    d = next.y;
    if (!survives(w, depth, medium, beta)) return vec3(0.0f);
  }
}

template <class OneWalk>
ReferenceEstimate run(const ShadingPoint& point, uint64_t seed, const ReferenceOptions& options, OneWalk one) {
  const ShadingPoint::Stack stack = point.stack();
  Tally tally;
  for (int64_t i = 0; i < options.walks; ++i) {
    Pcg32 rng(seed, uint64_t(i));
    Walk w(stack, rng);
    tally.add(one(w, tally));
  }
  return tally.result();
}

}  // namespace

int tilted_entry(const ShadingPoint& point) {
  const ShadingPoint::Stack stack = point.stack();
  for (int i = 0; i < stack.count; ++i)
    if (!k::lamina_entry_flat(stack.params[i])) return i;
  return -1;
}

static void refuse_tilted(const ShadingPoint& point) {
  if (tilted_entry(point) >= 0)
    throw std::domain_error("the reference solver walks flat boundaries; this point's stack has a tilted entry");
}

ReferenceEstimate reference_eval(const ShadingPoint& point, vec3 wi, vec3 wo, const ReferenceOptions& options) {
  refuse_tilted(point);
  wi = point.local(wi);
  wo = point.local(wo);
  if (!(wi.z > 0.0f && wo.z > 0.0f)) return ReferenceEstimate{.walks = options.walks};
  const uint64_t seed = hash_directions(wi, wo, options.seed);
  if (point.fluorescent())
    return run(point, seed, options,
               [&](Walk& w, Tally& t) { return walk_eval<mat3>(w, wi, wo, options.light, options.max_depth, t); });
  return run(point, seed, options,
             [&](Walk& w, Tally& t) { return walk_eval<vec3>(w, wi, wo, options.light, options.max_depth, t); });
}

ReferenceEstimate reference_albedo(const ShadingPoint& point, vec3 wo, const ReferenceOptions& options) {
  refuse_tilted(point);
  wo = point.local(wo);
  if (!(wo.z > 0.0f)) return ReferenceEstimate{.walks = options.walks};
  const uint64_t seed = hash_directions(vec3(0.0f), wo, options.seed ^ 0xa1bed0ull);
  if (point.fluorescent())
    return run(point, seed, options,
               [&](Walk& w, Tally& t) { return walk_albedo<mat3>(w, wo, options.light, options.max_depth, t); });
  return run(point, seed, options,
             [&](Walk& w, Tally& t) { return walk_albedo<vec3>(w, wo, options.light, options.max_depth, t); });
}

}  // namespace lamina::cpu
