// The reference solver: light followed through a material's stack by Monte Carlo random walks,
// with no approximation beyond the slab model itself (flat, parallel boundaries; position-free).
// Each layer's interface is a rough dielectric boundary that reflects and transmits in both
// directions (nodes/kernels/boundary.glsl), each medium attenuates by Beer-Lambert along every
// crossing, each substrate is its own BRDF, and a mix is a fine-grained blend: every time light
// reaches it, it meets one side or the other in proportion to the weight. The layered model
// approximates exactly this; `lamina compare` measures by how much.
//
// The BRDF estimator is a path traced from the viewer (wo) with two ways to finish at the light:
// the top interface evaluated toward wi when the walk reaches it from below, or a direction drawn
// through the top interface from wi and joined to the walk at the boundary underneath, combined by
// the balance heuristic (Veach 1997, ch. 9; the position-free connection of Guo, Hasan and Zhao
// 2018, used by pbrt-v4's LayeredBxDF for two boundaries, here for any stack). Every density in
// the weights is exact, so the estimate is unbiased. Walks are ended by Russian roulette (unbiased)
// and at max_depth (whose leftover weight is reported). Each estimate's random numbers come from
// PCG32 streams seeded by a hash of the directions and the seed: the same call gives the same bits.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "graph/cpu/evaluator.h"

namespace lamina::cpu {

struct ReferenceOptions {
  int64_t walks = 1 << 16;  // random walks per estimate
  int max_depth = 1000;     // scattering events after which a walk is cut off
  uint64_t seed = 0;        // mixed into the seed hashed from the directions
  // The incident light's colour: the estimates are of what is reflected of it. White gives f itself;
  // another colour f times it, unless a fluorescent base moves light between channels.
  glm::vec3 light{1.0f};
};

// A Monte Carlo estimate per channel with its standard error (the walks' sample standard deviation
// over sqrt(walks)).
struct ReferenceEstimate {
  glm::dvec3 value{0.0};
  glm::dvec3 std_error{0.0};
  glm::dvec3 truncated{0.0};  // the weight walks still carried when max_depth cut them off, per walk
  int64_t walks = 0;
  int64_t truncated_walks = 0;
};

// The first entry of the point's stack whose frame a normal input tilts, or -1. The slab model has
// flat, parallel boundaries only, so reference_eval and reference_albedo refuse a tilted point
// (std::domain_error); `lamina reference` and `lamina compare` name the node first.
int tilted_entry(const ShadingPoint& point);

// f(wi, wo) at the bound point, directions as ShadingPoint::eval takes them (0 below the horizon).
ReferenceEstimate reference_eval(const ShadingPoint& point, glm::vec3 wi, glm::vec3 wo,
                                 const ReferenceOptions& options = {});

// The directional albedo seen from wo, the integral of f(wi, wo) cos(theta_i) over wi: the mean
// weight with which walks from wo leave the stack.
ReferenceEstimate reference_albedo(const ShadingPoint& point, glm::vec3 wo, const ReferenceOptions& options = {});

}  // namespace lamina::cpu
