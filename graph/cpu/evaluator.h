// The CPU evaluator of a compiled material: the layered BRDF of Weidlich and Wilkie as Elek's
// Algorithm 1 evaluates it, generalised to stacks of any depth, with importance sampling. The
// composition is the kernels' (nodes/kernels/stack.glsl), the same text the GLSL back end runs.
//
// Conventions (DESIGN.md): wi (light) and wo (view) point away from the surface; f excludes the
// cosine; directions below the horizon give exactly 0. A shading point is bound once per hit
// (bind): it runs the material's textures for the whole context and turns world-space directions
// into its local frame (z along the normal, x along the tangent). The default context's frame is
// the identity, so directions may also be given in the local frame directly.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "graph/cpu/frame.h"
#include "graph/limits.h"
#include "graph/program.h"
#include "nodes/kernels/kernels.h"

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

// What a lobe is, for a renderer deciding how to treat it.
struct LobeFlags {
  bool diffuse = false;   // a diffuse substrate's lobe
  bool glossy = false;    // a microfacet lobe (an interface or a conductor)
  bool specular = false;  // a microfacet lobe smoother than kSpecularSlope at this point: it acts as
                          // a mirror, so light sampling rarely finds it and BRDF sampling should
};

// A microfacet lobe whose slope (after Elek's clamp) is below this is flagged specular: 0.06
// degrees, far smoother than any viewer resolves (the course's smoothest varnish is 0.01 degrees).
inline constexpr float kSpecularSlope = 1.0e-3f;

class Evaluator;
struct Local;  // the local-frame queries on one point's parameters (evaluator.cpp)

// A material bound to one shading context, valid while its Evaluator lives. It holds its texture
// registers and parameters inline (66 KB at the stack limits, no allocation; a bind writes only what
// its stack uses): bind once per hit, in place, and pass it by reference.
class ShadingPoint {
 public:
  // Directions in the space of the context's normal and tangent (world space for a renderer; the
  // local frame with the default context).
  glm::vec3 eval(glm::vec3 wi, glm::vec3 wo) const;
  // What is reflected toward wo of light of colour `light` arriving from wi. eval(wi, wo) is its
  // white light, (1, 1, 1); every channel is its own, eval(wi, wo) * light, unless a fluorescent
  // base moves light between channels (substrate/fluorescent), whose F is a 3 x 3 matrix.
  glm::vec3 eval(glm::vec3 wi, glm::vec3 wo, glm::vec3 light) const;
  // F^T(wi, wo) weight: what a path traced from the viewer carries on past a bounce whose weight
  // was `weight` (so that weight . eval(wi, wo, L) = eval_adjoint(wi, wo, weight) . L). Without
  // fluorescence, eval(wi, wo) * weight.
  glm::vec3 eval_adjoint(glm::vec3 wi, glm::vec3 wo, glm::vec3 weight) const;
  // Whether the material has a fluorescent base anywhere (substrate/fluorescent): then F may be a
  // matrix, and a renderer should use eval with the light's colour and eval_adjoint.
  bool fluorescent() const;
  float pdf(glm::vec3 wi, glm::vec3 wo) const;
  // eval and pdf together, bit for bit what the two return apart, sharing the work.
  EvalPdf eval_pdf(glm::vec3 wi, glm::vec3 wo) const;
  // u: two uniform numbers for the lobe's direction; u_lobe: one for choosing the lobe.
  Sample sample(glm::vec3 wo, glm::vec2 u, float u_lobe) const;
  // Directional albedo: the integral of f cos(theta_i) over the hemisphere, by deterministic
  // quadrature: each lobe's sampler and a cosine-weighted one driven by Hammersley point sets,
  // combined as their mixture.
  glm::vec3 albedo(glm::vec3 wo, int points_per_lobe = 1024) const;
  // Energy conservation's measure: per channel, the energy that light of that channel arriving from
  // wi leaves with, over every direction and channel (at most 1). The albedo seen from wi, by
  // reciprocity, unless fluorescence moves light between channels (then a channel's albedo may
  // exceed 1 under white light while no channel gives back more than it receives).
  glm::vec3 energy(glm::vec3 wi, int points_per_lobe = 1024) const;
  // The lobe selection probabilities at wo (they sum to 1; all 0 when wo reaches no lobe: below the
  // horizon, or behind the horizon of every tilted entry it meets).
  std::vector<float> lobe_weights(glm::vec3 wo) const;
  LobeFlags lobe_flags(size_t lobe) const;

  // The compiled stack at this point as the kernels read it: the entries (the same for every
  // point) and their parameters here. For walks that need more than the model's queries (the
  // reference solver, graph/cpu/reference.h).
  struct Stack {
    int count = 0;
    const kernels::LaminaEntry* entries = nullptr;
    const kernels::LaminaParams* params = nullptr;
  };
  Stack stack() const;
  // How many entries the queries walk here: the stack's, less the stacks no mix shows at this point
  // (a select's chain over one cell shows one of its stacks), which add nothing to any query.
  int walked_entries() const;
  // A direction given as the queries take it, in the local frame the stack's kernels work in.
  glm::vec3 local(glm::vec3 w) const { return identity_frame_ ? w : frame_.to_local(w); }

  const Frame& frame() const { return frame_; }
  // The texture registers (Program::slot_count floats): two points with equal registers have the
  // same BRDF, which back ends that bake textures use to group texels.
  std::span<const float> registers() const;

 private:
  friend class Evaluator;
  explicit ShadingPoint(const Evaluator& evaluator) : evaluator_(&evaluator) {}
  glm::vec3 world(glm::vec3 w) const { return identity_frame_ ? w : frame_.to_world(w); }
  // albedo's quadrature at wo; adjoint: of F^T with white weight, energy's.
  glm::vec3 integrate(glm::vec3 wo, int points_per_lobe, bool adjoint) const;
  const kernels::LaminaParams* params() const;
  Local queries() const;

  const Evaluator* evaluator_;
  Frame frame_;
  bool identity_frame_ = true;
  bool own_params_ = false;  // textured: params resolved here; otherwise the evaluator's
  std::array<float, kMaxSlots> registers_;
  std::array<kernels::LaminaParams, kMaxStackEntries> params_;
  // When some mix hides entries here (a select's chain over one cell), the queries run on the stack
  // without them (graph/kernel_stack.h, shown_stack): bit for bit the same results, in fewer steps.
  int shown_count_ = 0;  // 0: the whole stack
  std::array<kernels::LaminaEntry, kMaxStackEntries> shown_entries_;
  std::array<kernels::LaminaParams, kMaxStackEntries> shown_params_;
  std::array<int, kMaxStackEntries> shown_whole_;
};

// Immutable once built: every member function is const and safe to call from many threads at once.
// A material without texture nodes has its parameters resolved once, at construction.
class Evaluator {
 public:
  // Throws std::length_error when the program exceeds the stack limits of graph/limits.h (so that a
  // query allocates nothing); lamina's checker refuses such materials first (graph/stack_size.h).
  explicit Evaluator(Program program);

  const Program& program() const { return program_; }

  ShadingPoint bind(const ShadingContext& ctx) const;
  // The point as its flat equivalent: every entry's normal turned to +z, keeping its length (a
  // filtered mean of tilted normals still widens its lobe, lamina_widened_slope). For back ends that
  // cannot tilt a lobe, such as a glTF fallback without normal maps: a tilted facet then shows its
  // own lobe about the mirror direction, as a normal map would tilt it.
  ShadingPoint bind_untilted(const ShadingContext& ctx) const;

  // The same as bind(ctx) and the call, without keeping the bound point.
  glm::vec3 eval(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  float pdf(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  EvalPdf eval_pdf(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo) const;
  Sample sample(const ShadingContext& ctx, glm::vec3 wo, glm::vec2 u, float u_lobe) const;
  glm::vec3 albedo(const ShadingContext& ctx, glm::vec3 wo, int points_per_lobe = 1024) const;
  glm::vec3 energy(const ShadingContext& ctx, glm::vec3 wi, int points_per_lobe = 1024) const;
  glm::vec3 eval(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo, glm::vec3 light) const;
  glm::vec3 eval_adjoint(const ShadingContext& ctx, glm::vec3 wi, glm::vec3 wo, glm::vec3 weight) const;
  std::vector<float> lobe_weights(const ShadingContext& ctx, glm::vec3 wo) const;
  std::vector<float> texture_registers(const ShadingContext& ctx) const;

  // Where each stack entry lies at ctx: its share of the surface (the product of the mix weights
  // above it; 0 where no mix shows it) and its normal in the local frame, as bind(ctx) resolves them,
  // without the model's per-point coefficients (the energy-conserving model's quadratures). For
  // back ends that bake the geometry of a surface, such as the glTF fallback's normal texture.
  struct EntryCover {
    float share = 0.0f;
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
  };
  std::vector<EntryCover> entry_covers(const ShadingContext& ctx) const;

  // Batches over structure-of-arrays spans: query i is (wi[i], wo[i]) at context ctx[i]. Every
  // span has the length of the output; ctx may also be empty (the default context for all).
  // Other lengths throw std::invalid_argument. Each result is bit for bit the single-query form's;
  // a run of equal contexts is bound once.
  void eval(std::span<const ShadingContext> ctx, std::span<const glm::vec3> wi, std::span<const glm::vec3> wo,
            std::span<glm::vec3> f) const;
  void pdf(std::span<const ShadingContext> ctx, std::span<const glm::vec3> wi, std::span<const glm::vec3> wo,
           std::span<float> pdf) const;
  void eval_pdf(std::span<const ShadingContext> ctx, std::span<const glm::vec3> wi, std::span<const glm::vec3> wo,
                std::span<EvalPdf> out) const;
  void sample(std::span<const ShadingContext> ctx, std::span<const glm::vec3> wo, std::span<const glm::vec2> u,
              std::span<const float> u_lobe, std::span<Sample> out) const;

  // The lobes sampling chooses between: one per interface and one per substrate, per path
  // through the mixes (the stack entries that are not mixes, in order). Named by kind and depth,
  // e.g. "interface 0", "substrate 1 (conductor)".
  size_t lobe_count() const { return lobe_entry_.size(); }
  const std::string& lobe_name(size_t i) const { return lobe_names_[i]; }

 private:
  friend class ShadingPoint;
  // Fills the point's registers and parameters for ctx (textured materials only).
  ShadingPoint bind_point(const ShadingContext& ctx, bool untilted) const;
  void resolve(const ShadingContext& ctx, ShadingPoint& point, bool untilted) const;
  // The queries on the untextured stack's parameters (resolved once) in the local frame.
  Local fixed_queries() const;
  // The stack's parameters at ctx from its registers (lamina_stack_resolve) for `model`.
  void resolve_params(const float* registers, bool untilted, int model, kernels::LaminaParams* params) const;

  Program program_;
  int count_ = 0;                                 // stack entries
  bool glows_ = false;                            // a fluorescent base (lamina_stack_glows)
  std::vector<kernels::LaminaEntry> entries_;     // Program::stack as the kernels read it
  std::vector<kernels::LaminaInputs> constants_;  // every entry's inputs with its constants
  std::vector<kernels::LaminaParams> fixed_;      // untextured: every entry's parameters, resolved once
  struct Shown {                                  // and the stack its mixes show (ShadingPoint's shown_*)
    std::vector<kernels::LaminaEntry> entries;    // empty: every entry
    std::vector<kernels::LaminaParams> params;
    std::vector<int> whole;
  } fixed_shown_;
  std::vector<int> lobe_entry_;  // lobe j is entry lobe_entry_[j]
  std::vector<int> entry_lobe_;  // and entry i is lobe entry_lobe_[i] (-1: a mix)
  std::vector<std::string> lobe_names_;
};

}  // namespace lamina::cpu
