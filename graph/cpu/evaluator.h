// The CPU evaluator of a compiled material: the layered BRDF of Weidlich and Wilkie as Elek's
// Algorithm 1 evaluates it, generalised to stacks of any depth, with importance sampling.
//
// Conventions (DESIGN.md): local frame with the normal along z; wi (light) and wo (view) point
// away from the surface; f excludes the cosine; directions below the horizon give exactly 0.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "graph/limits.h"
#include "graph/lobes.h"
#include "graph/program.h"

namespace lamina::cpu {

struct Sample {
  glm::vec3 wi{0.0f};
  glm::vec3 f{0.0f};  // the BRDF at (wi, wo)
  float pdf = 0.0f;   // solid-angle density of wi; 0 when no direction could be drawn
  int lobe = -1;      // which lobe drew it (lobe_name)
};

struct EvalPdf {
  glm::vec3 f{0.0f};
  float pdf = 0.0f;
};

// Immutable once built: every member function is const and safe to call from many threads at once.
// A material without texture nodes has its parameters resolved once, at construction; a textured
// one resolves them at each shading point (once per run of equal uvs in the batch forms).
class Evaluator {
 public:
  // Throws std::length_error when the program exceeds the stack limits of graph/limits.h (so that a
  // query allocates nothing); lamina's checker refuses such materials first (graph/stack_size.h).
  explicit Evaluator(Program program);

  const Program& program() const { return program_; }

  glm::vec3 eval(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  float pdf(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  // eval and pdf together, bit for bit what the two return apart, sharing the work at one point.
  EvalPdf eval_pdf(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  // u: two uniform numbers for the lobe's direction; u_lobe: one for choosing the lobe.
  Sample sample(const ShadingContext& ctx, glm::vec3 wo, glm::vec2 u, float u_lobe) const;
  // Directional albedo: the integral of f cos(theta_i) over the hemisphere, by deterministic
  // quadrature: each lobe's sampler driven by a Hammersley point set, combined as the mixture.
  glm::vec3 albedo(const ShadingContext& ctx, glm::vec3 wo, int points_per_lobe = 1024) const;

  // Batches over structure-of-arrays spans: query i is (wi[i], wo[i]) at uv[i] (the other fields
  // of the ShadingContext at their defaults). Every span has the length of the output; uv may
  // also be empty (uv = 0 for all). Other lengths throw std::invalid_argument. Each result is
  // bit for bit the single-query form's.
  void eval(std::span<const glm::vec3> wi, std::span<const glm::vec3> wo, std::span<const glm::vec2> uv,
            std::span<glm::vec3> f) const;
  void pdf(std::span<const glm::vec3> wi, std::span<const glm::vec3> wo, std::span<const glm::vec2> uv,
           std::span<float> pdf) const;
  void eval_pdf(std::span<const glm::vec3> wi, std::span<const glm::vec3> wo, std::span<const glm::vec2> uv,
                std::span<EvalPdf> out) const;
  void sample(std::span<const glm::vec3> wo, std::span<const glm::vec2> u, std::span<const float> u_lobe,
              std::span<const glm::vec2> uv, std::span<Sample> out) const;

  // The lobes sampling chooses between: one per interface and one per substrate, per path
  // through the mixes. Named by node kind and depth, e.g. "interface 0", "substrate 1 (conductor)".
  size_t lobe_count() const { return lobes_.size(); }
  const std::string& lobe_name(size_t i) const { return lobes_[i].name; }
  // The selection probabilities at wo (they sum to 1).
  std::vector<float> lobe_weights(const ShadingContext& ctx, glm::vec3 wo) const;
  // The texture registers at a shading point (Program::slot_count floats): two points with equal
  // registers have the same BRDF, which back ends that bake textures use to group texels.
  std::vector<float> texture_registers(const ShadingContext& ctx) const;

  struct Plan;  // the stack as the evaluator walks it, built once (evaluator.cpp)

 private:
  Program program_;
  std::vector<Lobe> lobes_;
  std::shared_ptr<const Plan> plan_;
};

}  // namespace lamina::cpu
