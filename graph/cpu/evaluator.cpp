#include "graph/cpu/evaluator.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "graph/hammersley.h"
#include "graph/kernel_stack.h"
#include "graph/lobes.h"
#include "graph/node_decl.h"

// Everything about the model lives in the kernels' composition (nodes/kernels/stack.glsl): this
// file turns a Program into the arrays it walks, resolves a material's parameters once when
// nothing is textured, runs the texture operations at a shading point when something is, and
// converts directions between the context's space and the local frame.
namespace lamina::cpu {

using glm::vec2;
using glm::vec3;
namespace k = lamina::kernels;

namespace {

bool default_frame(const ShadingContext& ctx) {
  return ctx.normal == vec3(0.0f, 0.0f, 1.0f) && ctx.tangent == vec3(1.0f, 0.0f, 0.0f);
}

// The lobe selection at one wo, per entry (lamina_stack_select).
struct Selection {
  std::array<float, kMaxStackEntries> weight;
  std::array<vec3, kMaxStackEntries> v;
  std::array<bool, kMaxStackEntries> valid;
};

struct SpanLength {
  const char* name;
  size_t length;
};

// Every span of a batch has the output's length; ctx may also be empty.
void check_lengths(const char* function, std::initializer_list<SpanLength> spans, size_t ctx) {
  size_t n = spans.begin()->length;
  bool ok = ctx == 0 || ctx == n;
  for (const SpanLength& s : spans) ok = ok && s.length == n;
  if (ok) return;
  std::string message = std::string("lamina::cpu::Evaluator::") + function + ": spans of different lengths:";
  for (const SpanLength& s : spans) message += " " + std::string(s.name) + " " + std::to_string(s.length) + ",";
  message += " ctx " + std::to_string(ctx) + " (every span needs the output's length " + std::to_string(n) +
             "; ctx may also be empty)";
  throw std::invalid_argument(message);
}

const ShadingContext& context_at(std::span<const ShadingContext> ctx, size_t i) {
  static const ShadingContext kDefault{};
  return ctx.empty() ? kDefault : ctx[i];
}

// Runs a program's texture operations for ctx into its registers (Program::slot_count floats).
void run_textures(const Program& program, const ShadingContext& ctx, float* registers) {
  for (const TextureOp& op : program.ops) op.decl->run(op, ctx, registers);
}

// Runs `query(point, i)` for every i, binding a point once per run of equal contexts (each bound
// in place: a point is tens of kilobytes, not worth copying).
template <typename Query>
void for_each_bound(const Evaluator& evaluator, std::span<const ShadingContext> ctx, size_t n, Query query) {
  size_t i = 0;
  while (i < n) {
    const ShadingPoint point = evaluator.bind(context_at(ctx, i));
    do {
      query(point, i);
      ++i;
    } while (i < n && (ctx.empty() || ctx[i] == ctx[i - 1]));
  }
}

}  // namespace

// --- construction ----------------------------------------------------------------------------------

Evaluator::Evaluator(Program program) : program_(std::move(program)) {
  count_ = int(program_.stack.size());
  if (program_.slot_count > kMaxSlots || count_ > kMaxStackEntries)
    throw std::length_error("material '" + program_.name + "' is too large for the CPU evaluator");
  entries_.resize(size_t(count_));
  constants_.resize(size_t(count_));
  entry_lobe_.assign(size_t(count_), -1);
  for (int i = 0; i < count_; ++i) {
    entries_[size_t(i)] = kernel_entry(program_.stack[size_t(i)], true);
    constants_[size_t(i)] = kernel_constants(program_.stack[size_t(i)], true);
  }
  glows_ = k::lamina_stack_glows(count_, entries_.data());
  for (const Lobe& lobe : collect_lobes(program_)) {
    entry_lobe_[size_t(lobe.entry)] = int(lobe_entry_.size());
    lobe_entry_.push_back(lobe.entry);
    lobe_names_.push_back(lobe.name);
  }
  if (int(lobe_entry_.size()) > kMaxLobes)
    throw std::length_error("material '" + program_.name + "' has too many lobes for the CPU evaluator");
  for (const TextureOp& op : program_.ops)
    if (!op.decl || !op.decl->run)
      throw std::logic_error("Evaluator: an operation of '" + program_.name + "' cannot run");
  if (!program_.textured() && count_ > 0) {
    fixed_.resize(static_cast<size_t>(count_));
    k::lamina_stack_resolve(count_, entries_.data(), constants_.data(), 1.0f, program_.clamp_lower_roughness,
                            program_.model, fixed_.data());
    std::vector<k::LaminaEntry> entries(static_cast<size_t>(count_));
    std::vector<k::LaminaParams> params(static_cast<size_t>(count_));
    std::vector<int> whole(static_cast<size_t>(count_));
    const int shown = shown_stack(count_, entries_.data(), fixed_.data(), entries.data(), params.data(), whole.data());
    if (shown > 0) {
      entries.resize(size_t(shown));
      params.resize(size_t(shown));
      whole.resize(size_t(shown));
      fixed_shown_ = Shown{std::move(entries), std::move(params), std::move(whole)};
    }
  }
}

void Evaluator::resolve_params(const float* registers, bool untilted, int model, k::LaminaParams* params) const {
  std::array<k::LaminaInputs, kMaxStackEntries> inputs;
  for (int i = 0; i < count_; ++i) {
    k::LaminaInputs& x = inputs[size_t(i)];
    x = kernel_inputs(program_.stack[size_t(i)], constants_[size_t(i)], registers);
    if (untilted) x.normal = vec3(0.0f, 0.0f, glm::length(x.normal));
  }
  k::lamina_stack_resolve(count_, entries_.data(), inputs.data(), 1.0f, program_.clamp_lower_roughness, model, params);
}

void Evaluator::resolve(const ShadingContext& ctx, ShadingPoint& point, bool untilted) const {
  run_textures(program_, ctx, point.registers_.data());
  resolve_params(point.registers_.data(), untilted, program_.model, point.params_.data());
  point.own_params_ = true;
  point.shown_count_ = shown_stack(count_, entries_.data(), point.params_.data(), point.shown_entries_.data(),
                                   point.shown_params_.data(), point.shown_whole_.data());
}

ShadingPoint Evaluator::bind_point(const ShadingContext& ctx, bool untilted) const {
  ShadingPoint point(*this);
  point.identity_frame_ = default_frame(ctx);
  if (!point.identity_frame_) point.frame_ = Frame::from_normal_tangent(ctx.normal, ctx.tangent);
  // An untextured material's parameters were resolved once; only turning its normals needs its own.
  if (program_.textured() || untilted) resolve(ctx, point, untilted);
  return point;
}

ShadingPoint Evaluator::bind(const ShadingContext& ctx) const { return bind_point(ctx, false); }

ShadingPoint Evaluator::bind_untilted(const ShadingContext& ctx) const { return bind_point(ctx, true); }

// --- a bound point ---------------------------------------------------------------------------------

const k::LaminaParams* ShadingPoint::params() const { return own_params_ ? params_.data() : evaluator_->fixed_.data(); }

std::span<const float> ShadingPoint::registers() const {
  return std::span<const float>(registers_.data(), size_t(evaluator_->program_.slot_count));
}

// The kernels' composition, one function per query. Each is flattened: every kernel it calls is
// inlined into it, so that the composition's loops meet the leaf formulas (a substrate's model, a
// Fresnel mode) as code rather than as calls, as the recursion they replaced did; left to itself the
// compiler keeps the larger leaves out of line, which costs a layered eval 4% to 5% of its
// instructions. Kept out of line so that each query is compiled on its own. `Count` > 0 compiles
// the query for stacks of that many entries (the count folded into the loops); 0 for any count.
namespace {
// White light on a stack without a fluorescent base (lamina_stack_glows false, a constant here).
template <int Count>
[[gnu::flatten, gnu::noinline]] vec3 stack_eval(int count, const k::LaminaEntry* entries, const k::LaminaParams* params,
                                                vec3 wi, vec3 wo) {
  return k::lamina_stack_response(Count > 0 ? Count : count, entries, params, wi, wo, vec3(1.0f), false, false);
}
template <int Count>
[[gnu::flatten, gnu::noinline]] vec3 stack_eval_conserving(int count, const k::LaminaEntry* entries,
                                                           const k::LaminaParams* params, vec3 wi, vec3 wo) {
  return k::lamina_stack_response_conserving(Count > 0 ? Count : count, entries, params, wi, wo, vec3(1.0f), false,
                                             false);
}
// Light of a colour (lamina_stack_glows): off the hot path, for any count.
[[gnu::noinline]] vec3 stack_response(int model, int count, const k::LaminaEntry* entries,
                                      const k::LaminaParams* params, vec3 wi, vec3 wo, vec3 light, bool adjoint,
                                      bool glows) {
  if (model == k::LAMINA_MODEL_ENERGY_CONSERVING)
    return k::lamina_stack_response_conserving(count, entries, params, wi, wo, light, adjoint, glows);
  return k::lamina_stack_response(count, entries, params, wi, wo, light, adjoint, glows);
}
[[gnu::flatten, gnu::noinline]] void stack_select(int count, const k::LaminaEntry* entries,
                                                  const k::LaminaParams* params, vec3 wo, Selection& s) {
  k::lamina_stack_select(count, entries, params, wo, s.weight.data(), s.v.data(), s.valid.data());
}
[[gnu::flatten, gnu::noinline]] float stack_pdf(int count, const k::LaminaEntry* entries, const k::LaminaParams* params,
                                                const Selection& s, vec3 wi, vec3 wo) {
  return k::lamina_stack_pdf(count, entries, params, s.weight.data(), s.v.data(), s.valid.data(), wi, wo);
}
[[gnu::flatten, gnu::noinline]] vec3 stack_sample(int count, const k::LaminaEntry* entries,
                                                  const k::LaminaParams* params, const Selection& s, int chosen,
                                                  vec2 u) {
  return k::lamina_stack_sample(count, entries, params, s.v.data(), chosen, u);
}
}  // namespace

// The queries in the local frame, on an evaluator's arrays and one point's parameters.
struct Local {
  int count;
  const k::LaminaEntry* entries;
  const k::LaminaParams* params;
  int model;                   // the program's LAMINA_MODEL_*
  bool glows;                  // the material has a fluorescent base (lamina_stack_glows): f is a matrix
  const int* whole = nullptr;  // a shown stack's entries' indices in the whole stack (shown_stack)

  // Entry i's index in the whole stack, which lobes are numbered by.
  int whole_entry(int i) const { return whole ? whole[i] : i; }

  // lamina_stack_eval returns 0 below the horizon itself.
  // A bare substrate, the only one-entry stack, has an instance of its own: a lone lobe then costs
  // no more than its formula (the general instance is about 8% slower there, in time).
  vec3 eval(vec3 wi, vec3 wo) const {
    // A fluorescent stack's white light goes through the split of the light's way down and up.
    if (glows) return respond(wi, wo, vec3(1.0f), false);
    const bool bare = count == 1;
    if (model == k::LAMINA_MODEL_ENERGY_CONSERVING)
      return bare ? stack_eval_conserving<1>(count, entries, params, wi, wo)
                  : stack_eval_conserving<0>(count, entries, params, wi, wo);
    return bare ? stack_eval<1>(count, entries, params, wi, wo) : stack_eval<0>(count, entries, params, wi, wo);
  }
  vec3 respond(vec3 wi, vec3 wo, vec3 light, bool adjoint) const {
    return stack_response(model, count, entries, params, wi, wo, light, adjoint, glows);
  }
  void select(vec3 wo, Selection& s) const { stack_select(count, entries, params, wo, s); }
  float pdf(const Selection& s, vec3 wi, vec3 wo) const { return stack_pdf(count, entries, params, s, wi, wo); }
  float pdf(vec3 wi, vec3 wo) const {
    if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
    Selection s;
    select(wo, s);
    return pdf(s, wi, wo);
  }
  // Draws from the lobe of entry `chosen` and evaluates f and the mixture pdf there.
  Sample draw(const Selection& s, int chosen, vec3 wo, vec2 u, const std::vector<int>& entry_lobe) const {
    Sample out;
    if (chosen < 0) return out;
    const vec3 wi = stack_sample(count, entries, params, s, chosen, u);
    if (wi.z <= 0.0f) return out;
    out.wi = wi;
    out.lobe = entry_lobe[size_t(whole_entry(chosen))];
    out.f = eval(wi, wo);
    out.pdf = pdf(s, wi, wo);
    return out;
  }
};

ShadingPoint::Stack ShadingPoint::stack() const {
  return Stack{evaluator_->count_, evaluator_->entries_.data(), params()};
}

int ShadingPoint::walked_entries() const { return queries().count; }

Local ShadingPoint::queries() const {
  const int model = evaluator_->program_.model;
  if (shown_count_ > 0)
    return Local{shown_count_, shown_entries_.data(), shown_params_.data(),
                 model,        evaluator_->glows_,    shown_whole_.data()};
  if (!own_params_) return evaluator_->fixed_queries();
  return Local{evaluator_->count_, evaluator_->entries_.data(), params_.data(), model, evaluator_->glows_};
}

// Inlined: it is the hot path of an untextured material's queries.
[[gnu::always_inline]] inline Local Evaluator::fixed_queries() const {
  const Shown& shown = fixed_shown_;
  if (!shown.entries.empty())
    return Local{int(shown.entries.size()), shown.entries.data(), shown.params.data(), program_.model, glows_,
                 shown.whole.data()};
  return Local{count_, entries_.data(), fixed_.data(), program_.model, glows_};
}

vec3 ShadingPoint::eval(vec3 wi, vec3 wo) const { return queries().eval(local(wi), local(wo)); }

vec3 ShadingPoint::eval(vec3 wi, vec3 wo, vec3 light) const {
  return queries().respond(local(wi), local(wo), light, false);
}

vec3 ShadingPoint::eval_adjoint(vec3 wi, vec3 wo, vec3 weight) const {
  // F^T(wi, wo) is F with the directions exchanged and every matrix transposed (stack.glsl).
  return queries().respond(local(wo), local(wi), weight, true);
}

bool ShadingPoint::fluorescent() const { return queries().glows; }

float ShadingPoint::pdf(vec3 wi, vec3 wo) const { return queries().pdf(local(wi), local(wo)); }

EvalPdf ShadingPoint::eval_pdf(vec3 wi, vec3 wo) const {
  const Local q = queries();
  wi = local(wi);
  wo = local(wo);
  if (wi.z <= 0.0f || wo.z <= 0.0f) return {};
  return {q.eval(wi, wo), q.pdf(wi, wo)};
}

Sample ShadingPoint::sample(vec3 wo, vec2 u, float u_lobe) const {
  const Local q = queries();
  wo = local(wo);
  if (wo.z <= 0.0f) return {};
  Selection s;
  q.select(wo, s);
  Sample out = q.draw(s, k::lamina_stack_choose(q.count, s.weight.data(), u_lobe), wo, u, evaluator_->entry_lobe_);
  out.wi = world(out.wi);
  return out;
}

std::vector<float> ShadingPoint::lobe_weights(vec3 wo) const {
  const Local q = queries();
  std::vector<float> weights(evaluator_->lobe_count(), 0.0f);
  wo = local(wo);
  if (wo.z <= 0.0f) return weights;
  Selection s;
  q.select(wo, s);
  // A shown stack's stand-ins for hidden stacks (which may stand in for a mix) have weight 0.
  for (int i = 0; i < q.count; ++i) {
    const int lobe = evaluator_->entry_lobe_[size_t(q.whole_entry(i))];
    if (lobe >= 0 && s.weight[size_t(i)] > 0.0f) weights[size_t(lobe)] = s.weight[size_t(i)];
  }
  return weights;
}

LobeFlags ShadingPoint::lobe_flags(size_t lobe) const {
  const int i = evaluator_->lobe_entry_.at(lobe);
  LobeFlags flags;
  const k::LaminaEntry& e = evaluator_->entries_[size_t(i)];
  // A flake paint is both: its glitter a glossy lobe, its shade diffuse.
  if (k::lamina_is_microfacet_lobe(e) || k::lamina_is_flake_paint(e)) {
    flags.glossy = true;
    flags.specular = params()[i].m < kSpecularSlope;
  }
  if (!k::lamina_is_microfacet_lobe(e)) flags.diffuse = true;
  return flags;
}

vec3 ShadingPoint::albedo(vec3 wo, int points_per_lobe) const { return integrate(wo, points_per_lobe, false); }

vec3 ShadingPoint::energy(vec3 wi, int points_per_lobe) const {
  // Without fluorescence each channel is its own and the BRDF reciprocal: the albedo seen from wi.
  return integrate(wi, points_per_lobe, queries().glows);
}

vec3 ShadingPoint::integrate(vec3 wo, int points_per_lobe, bool adjoint) const {
  const Local q = queries();
  wo = local(wo);
  if (wo.z <= 0.0f || points_per_lobe <= 0) return vec3(0.0f);
  // The selection at wo is the same for every point: computed once.
  Selection s;
  q.select(wo, s);
  // Every lobe's sampler and a cosine-weighted one, each on its own Hammersley set, weighed as the
  // mixture p = (1 - a) pdf + a cos / pi (pdf: the lobe selection's mixture; the balance
  // heuristic). Technique t's share is its weight times the mean of f cos / p over its points; the
  // shares add up to the integral. The cosine technique covers what no lobe samples: the
  // energy-conserving model's light leaving far from every lobe (a coat's trapped light over a
  // smooth metal), which the lobes alone reach only with rare huge weights, or never where their
  // pdf is 0. Without it that model's coats over metal read up to 28% low.
  constexpr float kCosineShare = 0.25f;
  const auto weight_of = [&](vec3 wi, vec3 f, float lobe_pdf) {
    const float p = (1.0f - kCosineShare) * lobe_pdf + kCosineShare * wi.z * k::LAMINA_INV_PI;
    return p > 0.0f ? f * wi.z / p : vec3(0.0f);
  };
  vec3 total(0.0f);
  float lo = 0.0f;
  for (int entry = 0; entry < q.count; ++entry) {
    const float w = s.weight[size_t(entry)];
    if (!k::lamina_is_lobe(q.entries[entry]) || w <= 0.0f) continue;
    const float u_lobe = std::min(lo + 0.5f * w, 1.0f - 1.0e-7f);
    lo += w;
    // Rounding may let u_lobe pick a neighbour of a tiny lobe; those samples are not this lobe's.
    if (k::lamina_stack_choose(q.count, s.weight.data(), u_lobe) != entry) continue;
    vec3 sum(0.0f);
    for (int i = 0; i < points_per_lobe; ++i) {
      const Sample sample =
          q.draw(s, entry, wo, hammersley(uint32_t(i), uint32_t(points_per_lobe)), evaluator_->entry_lobe_);
      const vec3 f = adjoint ? q.respond(sample.wi, wo, vec3(1.0f), true) : sample.f;
      if (sample.pdf > 0.0f) sum += weight_of(sample.wi, f, sample.pdf);
    }
    total += (1.0f - kCosineShare) * w * sum / float(points_per_lobe);
  }
  vec3 sum(0.0f);
  for (int i = 0; i < points_per_lobe; ++i) {
    const vec3 wi = k::sample_cosine(hammersley(uint32_t(i), uint32_t(points_per_lobe)));
    if (wi.z > 0.0f)
      sum += weight_of(wi, adjoint ? q.respond(wi, wo, vec3(1.0f), true) : q.eval(wi, wo), q.pdf(s, wi, wo));
  }
  return total + kCosineShare * sum / float(points_per_lobe);
}

// --- single queries ----------------------------------------------------------------------------------

// The general paths of eval and pdf, out of line: a bound point is kilobytes of stack that the hot
// path below should not set up.
namespace {
[[gnu::noinline]] vec3 bound_eval(const Evaluator& e, const ShadingContext& ctx, vec3 wi, vec3 wo) {
  return e.bind(ctx).eval(wi, wo);
}
[[gnu::noinline]] float bound_pdf(const Evaluator& e, const ShadingContext& ctx, vec3 wi, vec3 wo) {
  return e.bind(ctx).pdf(wi, wo);
}
}  // namespace

vec3 Evaluator::eval(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  // The hot path: an untextured material in the local frame needs no bound point.
  if (!program_.textured() && default_frame(ctx)) return fixed_queries().eval(wi, wo);
  return bound_eval(*this, ctx, wi, wo);
}

float Evaluator::pdf(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (!program_.textured() && default_frame(ctx)) return fixed_queries().pdf(wi, wo);
  return bound_pdf(*this, ctx, wi, wo);
}

EvalPdf Evaluator::eval_pdf(const ShadingContext& ctx, vec3 wi, vec3 wo) const { return bind(ctx).eval_pdf(wi, wo); }

Sample Evaluator::sample(const ShadingContext& ctx, vec3 wo, vec2 u, float u_lobe) const {
  return bind(ctx).sample(wo, u, u_lobe);
}

vec3 Evaluator::albedo(const ShadingContext& ctx, vec3 wo, int points_per_lobe) const {
  return bind(ctx).albedo(wo, points_per_lobe);
}

vec3 Evaluator::energy(const ShadingContext& ctx, vec3 wi, int points_per_lobe) const {
  return bind(ctx).energy(wi, points_per_lobe);
}

vec3 Evaluator::eval(const ShadingContext& ctx, vec3 wi, vec3 wo, vec3 light) const {
  if (!program_.textured() && default_frame(ctx)) return fixed_queries().respond(wi, wo, light, false);
  return bind(ctx).eval(wi, wo, light);
}

vec3 Evaluator::eval_adjoint(const ShadingContext& ctx, vec3 wi, vec3 wo, vec3 weight) const {
  if (!program_.textured() && default_frame(ctx)) return fixed_queries().respond(wo, wi, weight, true);
  return bind(ctx).eval_adjoint(wi, wo, weight);
}

std::vector<float> Evaluator::lobe_weights(const ShadingContext& ctx, vec3 wo) const {
  return bind(ctx).lobe_weights(wo);
}

std::vector<float> Evaluator::texture_registers(const ShadingContext& ctx) const {
  // Only the texture operations: a back end grouping texels by their registers (the glTF bake
  // visits every texel) need not resolve the stack at each.
  std::vector<float> registers(size_t(program_.slot_count));
  run_textures(program_, ctx, registers.data());
  return registers;
}

std::vector<Evaluator::EntryCover> Evaluator::entry_covers(const ShadingContext& ctx) const {
  // The first pass of lamina_stack_resolve places every entry; the original model's resolve is
  // that pass alone.
  std::array<float, kMaxSlots> registers;
  run_textures(program_, ctx, registers.data());
  std::array<k::LaminaParams, kMaxStackEntries> params;
  resolve_params(registers.data(), false, k::LAMINA_MODEL_WEIDLICH_WILKIE, params.data());
  std::vector<EntryCover> covers(static_cast<size_t>(count_));
  for (size_t i = 0; i < covers.size(); ++i) covers[i] = EntryCover{params[i].share, params[i].normal};
  return covers;
}

// --- batches -------------------------------------------------------------------------------------------

void Evaluator::eval(std::span<const ShadingContext> ctx, std::span<const vec3> wi, std::span<const vec3> wo,
                     std::span<vec3> f) const {
  check_lengths("eval", {{"f", f.size()}, {"wi", wi.size()}, {"wo", wo.size()}}, ctx.size());
  for_each_bound(*this, ctx, f.size(), [&](const ShadingPoint& p, size_t i) { f[i] = p.eval(wi[i], wo[i]); });
}

void Evaluator::pdf(std::span<const ShadingContext> ctx, std::span<const vec3> wi, std::span<const vec3> wo,
                    std::span<float> out) const {
  check_lengths("pdf", {{"pdf", out.size()}, {"wi", wi.size()}, {"wo", wo.size()}}, ctx.size());
  for_each_bound(*this, ctx, out.size(), [&](const ShadingPoint& p, size_t i) { out[i] = p.pdf(wi[i], wo[i]); });
}

void Evaluator::eval_pdf(std::span<const ShadingContext> ctx, std::span<const vec3> wi, std::span<const vec3> wo,
                         std::span<EvalPdf> out) const {
  check_lengths("eval_pdf", {{"out", out.size()}, {"wi", wi.size()}, {"wo", wo.size()}}, ctx.size());
  for_each_bound(*this, ctx, out.size(), [&](const ShadingPoint& p, size_t i) { out[i] = p.eval_pdf(wi[i], wo[i]); });
}

void Evaluator::sample(std::span<const ShadingContext> ctx, std::span<const vec3> wo, std::span<const vec2> u,
                       std::span<const float> u_lobe, std::span<Sample> out) const {
  check_lengths("sample", {{"out", out.size()}, {"wo", wo.size()}, {"u", u.size()}, {"u_lobe", u_lobe.size()}},
                ctx.size());
  for_each_bound(*this, ctx, out.size(),
                 [&](const ShadingPoint& p, size_t i) { out[i] = p.sample(wo[i], u[i], u_lobe[i]); });
}

}  // namespace lamina::cpu
