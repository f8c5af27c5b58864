// The CPU evaluator of a compiled material: the layered BRDF of Weidlich and Wilkie as Elek's
// Algorithm 1 evaluates it, generalised to stacks of any depth, with importance sampling.
//
// Conventions (DESIGN.md): local frame with the normal along z; wi (light) and wo (view) point
// away from the surface; f excludes the cosine; directions below the horizon give exactly 0.
#pragma once

#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

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

// Limits of one Program, so that a query allocates nothing.
inline constexpr int kMaxStackNodes = 64;
inline constexpr int kMaxSlots = 256;
inline constexpr int kMaxLobes = 64;

class Evaluator {
 public:
  // Throws std::length_error when the program exceeds the limits above.
  explicit Evaluator(Program program);

  const Program& program() const { return program_; }

  glm::vec3 eval(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  float pdf(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  EvalPdf eval_pdf(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  // u: two uniform numbers for the lobe's direction; u_lobe: one for choosing the lobe.
  Sample sample(const ShadingContext& ctx, glm::vec3 wo, glm::vec2 u, float u_lobe) const;
  // Directional albedo: the integral of f cos(theta_i) over the hemisphere, by deterministic
  // quadrature: each lobe's sampler driven by a Hammersley point set, combined as the mixture.
  glm::vec3 albedo(const ShadingContext& ctx, glm::vec3 wo, int points_per_lobe = 1024) const;

  // Batches over structure-of-arrays spans of equal length; uv may be empty (uv = 0).
  void eval(std::span<const glm::vec3> wi, std::span<const glm::vec3> wo, std::span<const glm::vec2> uv,
            std::span<glm::vec3> f) const;
  void pdf(std::span<const glm::vec3> wi, std::span<const glm::vec3> wo, std::span<const glm::vec2> uv,
           std::span<float> pdf) const;
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

  struct Resolved;  // parameters at one shading point (evaluator.cpp)

 private:
  struct LobeFrame;  // wo and indices seen in a lobe's own frame (evaluator.cpp)

  void resolve(const ShadingContext& ctx, Resolved& r) const;
  glm::vec3 eval_resolved(const Resolved& r, glm::vec3 wi, glm::vec3 wo) const;
  float pdf_resolved(const Resolved& r, glm::vec3 wi, glm::vec3 wo) const;
  int weights_resolved(const Resolved& r, glm::vec3 wo, float* weights, LobeFrame* frames) const;
  glm::vec3 eval_node(const Resolved& r, int node, glm::vec3 l, glm::vec3 v, float n_above, float m_above) const;

  Program program_;
  std::vector<Lobe> lobes_;
};

}  // namespace lamina::cpu
