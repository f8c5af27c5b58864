#include "graph/cpu/evaluator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "graph/cpu/image.h"
#include "graph/hammersley.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

using glm::vec2;
using glm::vec3;
namespace k = lamina::kernels;

namespace {

enum class Kind { Layer, Mix, Lambert, OrenNayar, Conductor };

// A stack node with every parameter read at the shading point. Linked values are clamped to
// their declared ranges, so a texture cannot push the model outside its domain.
struct Node {
  Kind kind;
  // layer: absolute index below the interface, slope, distribution, absorption, base
  float ior;
  float m;
  int distribution;
  vec3 absorption;
  float thickness;
  int base;
  // mix
  float weight;
  int a, b;
  // substrates
  vec3 albedo;
  float sigma;
  vec3 n, k;
};

const float kPi = k::LAMINA_PI;

vec3 clamp01(vec3 c) { return glm::clamp(c, vec3(0.0f), vec3(1.0f)); }

}  // namespace

struct Evaluator::Resolved {
  std::array<float, kMaxSlots> regs;
  std::array<Node, kMaxStackNodes> nodes;
  bool clamp = true;

  float read(const ScalarRef& s) const { return s.slot < 0 ? s.constant : regs[s.slot]; }
  vec3 read(const ColorRef& c) const {
    return c.slot < 0 ? c.constant : vec3(regs[c.slot], regs[c.slot + 1], regs[c.slot + 2]);
  }
};

// wo as seen by one lobe: refracted through the layers above it.
struct Evaluator::LobeFrame {
  vec3 v{0.0f};
  float n_above = 1.0f;  // absolute index of the medium the lobe's directions travel in
  float m = 0.0f;        // the lobe's slope after clamping to the layers above
  bool valid = false;
};

Evaluator::Evaluator(Program program) : program_(std::move(program)) {
  if (program_.slot_count > kMaxSlots || int(program_.stack.size()) > kMaxStackNodes)
    throw std::length_error("material '" + program_.name + "' is too large for the CPU evaluator");
  lobes_ = collect_lobes(program_);
  if (int(lobes_.size()) > kMaxLobes)
    throw std::length_error("material '" + program_.name + "' has too many lobes for the CPU evaluator");
}

void Evaluator::resolve(const ShadingContext& ctx, Resolved& r) const {
  r.clamp = program_.clamp_lower_roughness;
  for (const TextureOp& op : program_.ops) {
    if (const auto* c = std::get_if<CheckerOp>(&op)) {
      float v = k::checker_value(ctx.uv, c->scale);
      vec3 color = glm::mix(r.read(c->color_a), r.read(c->color_b), v);
      r.regs[c->color_slot] = color.x;
      r.regs[c->color_slot + 1] = color.y;
      r.regs[c->color_slot + 2] = color.z;
      r.regs[c->value_slot] = v;
    } else if (const auto* img = std::get_if<ImageOp>(&op)) {
      vec2 uv = k::lamina_image_uv(ctx.uv, img->uv_rotation_deg, img->uv_scale, img->uv_offset);
      glm::vec4 texel = sample_bilinear(*img->image, uv, Wrap(img->wrap));
      r.regs[img->color_slot] = texel.x;
      r.regs[img->color_slot + 1] = texel.y;
      r.regs[img->color_slot + 2] = texel.z;
      r.regs[img->value_slot] = k::lamina_luminance(vec3(texel));
      r.regs[img->alpha_slot] = texel.w;
    } else if (const auto* remap = std::get_if<RemapOp>(&op)) {
      r.regs[remap->value_slot] = k::remap_value(r.read(remap->value), remap->in_min, remap->in_max, remap->out_min,
                                                 remap->out_max, remap->clamp);
    }
  }
  for (size_t i = 0; i < program_.stack.size(); ++i) {
    Node& n = r.nodes[i];
    const StackNode& s = program_.stack[i];
    if (const auto* layer = std::get_if<LayerNode>(&s)) {
      const auto& d = std::get<DielectricInterface>(layer->interface);
      n.kind = Kind::Layer;
      n.ior = std::clamp(r.read(d.ior), 1.0f, 4.0f);
      n.m = k::lamina_slope(r.read(d.roughness.value), d.roughness.degrees);
      n.distribution = int(d.distribution);
      n.absorption = vec3(0.0f);
      n.thickness = 0.0f;
      if (const auto* a = std::get_if<AbsorbingMedium>(&layer->medium)) {
        n.absorption = glm::max(r.read(a->absorption), vec3(0.0f));
        n.thickness = std::max(r.read(a->thickness), 0.0f);
      }
      n.base = layer->base;
    } else if (const auto* mix = std::get_if<MixNode>(&s)) {
      n.kind = Kind::Mix;
      n.weight = std::clamp(r.read(mix->weight), 0.0f, 1.0f);
      n.a = mix->a;
      n.b = mix->b;
    } else if (const auto* lambert = std::get_if<LambertNode>(&s)) {
      n.kind = Kind::Lambert;
      n.albedo = clamp01(r.read(lambert->albedo));
    } else if (const auto* on = std::get_if<OrenNayarNode>(&s)) {
      n.kind = Kind::OrenNayar;
      n.albedo = clamp01(r.read(on->albedo));
      n.sigma = std::clamp(r.read(on->sigma), 0.0f, kPi / 2.0f);
    } else if (const auto* c = std::get_if<ConductorNode>(&s)) {
      n.kind = Kind::Conductor;
      n.n = glm::max(r.read(c->n), vec3(1.0e-3f));
      n.k = glm::max(r.read(c->k), vec3(0.0f));
      n.m = k::lamina_slope(r.read(c->roughness.value), c->roughness.degrees);
      n.distribution = int(c->distribution);
    }
  }
}

// Elek's Algorithm 1 generalised to any depth (course sec. 3.1, Elek eq. 2):
//   f(i)(L, V) = f_i(L, V) + T_i f(i+1)(L', V') a_i t_i
// with f_i the Torrance-Sparrow lobe of interface i, relative index eta_i = n_i / n_(i-1), F_i
// evaluated at V.H, T_i = 1 - F_i (so T21 = T12), L' and V' refracted through the macro normal,
// a_i the Beer-Lambert absorption (Elek eq. 3) and t_i = (1 - G_i) + T_i G_i (Elek eq. 4).
vec3 Evaluator::eval_node(const Resolved& r, int index, vec3 l, vec3 v, float n_above, float m_above) const {
  const Node& n = r.nodes[size_t(index)];
  switch (n.kind) {
    case Kind::Layer: {
      float m = k::lamina_effective_slope(n.m, m_above, r.clamp);
      vec3 l_below, v_below, carry;
      vec3 f = k::lamina_interface_eval(l, v, n.ior / n_above, n.distribution, m, n.absorption, n.thickness, l_below,
                                        v_below, carry);
      if (l_below.z <= 0.0f || v_below.z <= 0.0f) return f;  // total internal reflection: nothing below
      return f + eval_node(r, n.base, l_below, v_below, n.ior, m) * carry;
    }
    case Kind::Mix:
      return glm::mix(eval_node(r, n.a, l, v, n_above, m_above), eval_node(r, n.b, l, v, n_above, m_above), n.weight);
    case Kind::Lambert: return k::lamina_lambert_eval(l, v, n.albedo);
    case Kind::OrenNayar: return k::oren_nayar(l, v, n.albedo, n.sigma);
    case Kind::Conductor: {
      float m = k::lamina_effective_slope(n.m, m_above, r.clamp);
      // The metal's index relative to the layer above it (Elek's shader uses the absolute one).
      return k::lamina_conductor_eval(l, v, n.n / n_above, n.k / n_above, n.distribution, m);
    }
  }
  return vec3(0.0f);
}

vec3 Evaluator::eval_resolved(const Resolved& r, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return vec3(0.0f);
  vec3 f = eval_node(r, program_.root, wi, wo, 1.0f, 0.0f);
  return glm::max(f, vec3(0.0f));
}

// Selection probabilities (course sec. 3.2.3): each lobe's estimated share of the reflected
// energy at wo: the Fresnel reflectance of its interface (or the albedo of its substrate) times
// what the layers above let through twice, (1 - F)^2 and the absorption along the refracted wo,
// times the mix weights on its path. A floor of 1% of the mean keeps every lobe reachable.
int Evaluator::weights_resolved(const Resolved& r, vec3 wo, float* weights, LobeFrame* frames) const {
  int count = int(lobes_.size());
  float total = 0.0f;
  for (int j = 0; j < count; ++j) {
    const Lobe& lobe = lobes_[size_t(j)];
    LobeFrame& frame = frames[j];
    frame = LobeFrame{};
    vec3 v = wo;
    float n_above = 1.0f, m_above = 0.0f, throughput = 1.0f;
    bool valid = wo.z > 0.0f;
    for (const LobeStep& step : lobe.path) {
      const Node& n = r.nodes[size_t(step.node)];
      if (n.kind == Kind::Mix) {
        throughput *= step.side == 0 ? 1.0f - n.weight : n.weight;
        continue;
      }
      float factor = 0.0f;
      vec3 below = k::lamina_selection_step(v, n.ior / n_above, n.absorption, n.thickness, factor);
      if (below.z <= 0.0f) {
        valid = false;
        break;
      }
      throughput *= factor;
      m_above = r.clamp ? std::max(n.m, m_above) : n.m;
      n_above = n.ior;
      v = below;
    }
    float estimate = 0.0f;
    const Node& n = r.nodes[size_t(lobe.node)];
    if (valid) {
      switch (n.kind) {
        case Kind::Layer: estimate = k::fresnel_dielectric(v.z, n.ior / n_above); break;
        case Kind::Conductor:
          estimate = k::lamina_luminance(k::fresnel_conductor(v.z, n.n / n_above, n.k / n_above));
          break;
        case Kind::Lambert:
        case Kind::OrenNayar: estimate = k::lamina_luminance(n.albedo); break;
        case Kind::Mix: break;
      }
      estimate *= throughput;
    }
    frame.v = v;
    frame.n_above = n_above;
    float own_m = (n.kind == Kind::Layer || n.kind == Kind::Conductor) ? n.m : 0.0f;
    frame.m = k::lamina_effective_slope(own_m, m_above, r.clamp);
    frame.valid = valid;
    weights[j] = estimate;
    total += estimate;
  }
  int valid_count = 0;
  for (int j = 0; j < count; ++j) valid_count += frames[j].valid ? 1 : 0;
  if (valid_count == 0) {
    for (int j = 0; j < count; ++j) weights[j] = 0.0f;
    return count;
  }
  float floor = total > 0.0f ? 0.01f * total / float(valid_count) : 1.0f;
  float sum = 0.0f;
  for (int j = 0; j < count; ++j) {
    if (frames[j].valid) weights[j] += floor;
    sum += weights[j];
  }
  for (int j = 0; j < count; ++j) weights[j] /= sum;
  return count;
}

namespace {

bool is_microfacet(Kind kind) { return kind == Kind::Layer || kind == Kind::Conductor; }

}  // namespace

// A lobe draws directions in its own frame, below the layers above it. Directions inside the
// exit cone (sin < 1/n, n the frame's absolute index) are carried up by Snell's law, with the
// solid-angle Jacobian; a microfacet lobe's directions outside the cone, which cannot leave the
// stack, are spread over the outer hemisphere by cos_out = cos_in / cos_critical (Jacobian
// cos_critical), so every lobe's density integrates to exactly 1. Diffuse lobes draw cosine-
// weighted directions inside the cone only, which is the cosine distribution outside.
float Evaluator::pdf_resolved(const Resolved& r, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  std::array<float, kMaxLobes> weights;
  std::array<LobeFrame, kMaxLobes> frames;
  int count = weights_resolved(r, wo, weights.data(), frames.data());
  float pdf = 0.0f;
  for (int j = 0; j < count; ++j) {
    if (weights[size_t(j)] <= 0.0f || !frames[size_t(j)].valid) continue;
    const Lobe& lobe = lobes_[size_t(j)];
    const LobeFrame& frame = frames[size_t(j)];
    vec3 w = wi;
    float jacobian = 1.0f, n_above = 1.0f;
    for (const LobeStep& step : lobe.path) {
      const Node& n = r.nodes[size_t(step.node)];
      if (n.kind == Kind::Mix) continue;
      float eta = n.ior / n_above;
      vec3 below = k::refract_down(w, eta);
      jacobian *= k::refraction_jacobian(w.z, below.z, eta);
      w = below;
      n_above = n.ior;
    }
    if (w.z <= 0.0f) continue;
    const Node& n = r.nodes[size_t(lobe.node)];
    float density = 0.0f;
    if (is_microfacet(n.kind))
      density = k::lamina_microfacet_lobe_pdf(n.distribution, frame.m, frame.v, w, jacobian, wi, n_above);
    else
      density = k::lamina_diffuse_lobe_pdf(w, jacobian, n_above);
    pdf += weights[size_t(j)] * density;
  }
  return pdf;
}

namespace {

// Carries a direction drawn below the lobe's path back up to the outside (refract_up through
// the path's layers, bottom to top); vec3(0) if it cannot leave.
template <typename Path, typename Nodes>
vec3 carry_up(vec3 w, const Path& path, const Nodes& nodes) {
  std::array<float, kMaxStackNodes> etas;
  int layers = 0;
  float n_above = 1.0f;
  for (const auto& step : path) {
    const Node& n = nodes[size_t(step.node)];
    if (n.kind == Kind::Mix) continue;
    etas[size_t(layers++)] = n.ior / n_above;
    n_above = n.ior;
  }
  for (int i = layers - 1; i >= 0; --i) {
    w = k::refract_up(w, etas[size_t(i)]);
    if (w.z <= 0.0f) return vec3(0.0f);
  }
  return w;
}

}  // namespace

Sample Evaluator::sample(const ShadingContext& ctx, vec3 wo, vec2 u, float u_lobe) const {
  Sample s;
  if (wo.z <= 0.0f) return s;
  Resolved r;
  resolve(ctx, r);
  std::array<float, kMaxLobes> weights;
  std::array<LobeFrame, kMaxLobes> frames;
  int count = weights_resolved(r, wo, weights.data(), frames.data());
  int chosen = -1;
  float cumulative = 0.0f;
  for (int j = 0; j < count; ++j) {
    if (weights[size_t(j)] <= 0.0f) continue;
    chosen = j;
    cumulative += weights[size_t(j)];
    if (u_lobe < cumulative) break;
  }
  if (chosen < 0) return s;
  const Lobe& lobe = lobes_[size_t(chosen)];
  const LobeFrame& frame = frames[size_t(chosen)];
  const Node& n = r.nodes[size_t(lobe.node)];
  float n_frame = frame.n_above;
  vec3 wi(0.0f);
  if (is_microfacet(n.kind)) {
    bool inside_cone = true;
    vec3 w = k::lamina_sample_microfacet_lobe(n.distribution, frame.m, frame.v, u, n_frame, inside_cone);
    if (w.z <= 0.0f) return s;
    wi = inside_cone ? carry_up(w, lobe.path, r.nodes) : w;
  } else {
    wi = carry_up(k::lamina_sample_diffuse_lobe(u, n_frame), lobe.path, r.nodes);
  }
  if (wi.z <= 0.0f) return s;
  wi = glm::normalize(wi);
  s.wi = wi;
  s.lobe = chosen;
  s.f = eval_resolved(r, wi, wo);
  s.pdf = pdf_resolved(r, wi, wo);
  return s;
}

vec3 Evaluator::eval(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return vec3(0.0f);
  Resolved r;
  resolve(ctx, r);
  return eval_resolved(r, wi, wo);
}

float Evaluator::pdf(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  Resolved r;
  resolve(ctx, r);
  return pdf_resolved(r, wi, wo);
}

EvalPdf Evaluator::eval_pdf(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return {};
  Resolved r;
  resolve(ctx, r);
  return {eval_resolved(r, wi, wo), pdf_resolved(r, wi, wo)};
}

std::vector<float> Evaluator::lobe_weights(const ShadingContext& ctx, vec3 wo) const {
  Resolved r;
  resolve(ctx, r);
  std::array<float, kMaxLobes> weights;
  std::array<LobeFrame, kMaxLobes> frames;
  int count = weights_resolved(r, wo, weights.data(), frames.data());
  return std::vector<float>(weights.begin(), weights.begin() + count);
}

std::vector<float> Evaluator::texture_registers(const ShadingContext& ctx) const {
  Resolved r;
  resolve(ctx, r);
  return std::vector<float>(r.regs.begin(), r.regs.begin() + program_.slot_count);
}

vec3 Evaluator::albedo(const ShadingContext& ctx, vec3 wo, int points_per_lobe) const {
  if (wo.z <= 0.0f || points_per_lobe <= 0) return vec3(0.0f);
  std::vector<float> weights = lobe_weights(ctx, wo);
  // Stratified over lobes: lobe j's share is weight_j times the mean of f cos / pdf over its own
  // samples, where pdf is the full mixture density; the shares add up to the integral.
  vec3 total(0.0f);
  for (size_t j = 0; j < weights.size(); ++j) {
    if (weights[j] <= 0.0f) continue;
    float lo = 0.0f;
    for (size_t i = 0; i < j; ++i) lo += weights[i];
    float u_lobe = std::min(lo + 0.5f * weights[j], 1.0f - 1.0e-7f);
    vec3 sum(0.0f);
    for (int i = 0; i < points_per_lobe; ++i) {
      vec2 u = hammersley(uint32_t(i), uint32_t(points_per_lobe));
      Sample s = sample(ctx, wo, u, u_lobe);
      if (s.pdf > 0.0f && s.lobe == int(j)) sum += s.f * s.wi.z / s.pdf;
    }
    total += weights[j] * sum / float(points_per_lobe);
  }
  return total;
}

void Evaluator::eval(std::span<const vec3> wi, std::span<const vec3> wo, std::span<const vec2> uv,
                     std::span<vec3> f) const {
  ShadingContext ctx;
  Resolved r;
  bool constant = program_.ops.empty();
  if (constant) resolve(ctx, r);
  for (size_t i = 0; i < f.size(); ++i) {
    if (!constant) {
      ctx.uv = uv.empty() ? vec2(0.0f) : uv[i];
      resolve(ctx, r);
    }
    f[i] = eval_resolved(r, wi[i], wo[i]);
  }
}

void Evaluator::pdf(std::span<const vec3> wi, std::span<const vec3> wo, std::span<const vec2> uv,
                    std::span<float> out) const {
  ShadingContext ctx;
  Resolved r;
  bool constant = program_.ops.empty();
  if (constant) resolve(ctx, r);
  for (size_t i = 0; i < out.size(); ++i) {
    if (!constant) {
      ctx.uv = uv.empty() ? vec2(0.0f) : uv[i];
      resolve(ctx, r);
    }
    out[i] = pdf_resolved(r, wi[i], wo[i]);
  }
}

void Evaluator::sample(std::span<const vec3> wo, std::span<const vec2> u, std::span<const float> u_lobe,
                       std::span<const vec2> uv, std::span<Sample> out) const {
  ShadingContext ctx;
  for (size_t i = 0; i < out.size(); ++i) {
    ctx.uv = uv.empty() ? vec2(0.0f) : uv[i];
    out[i] = sample(ctx, wo[i], u[i], u_lobe[i]);
  }
}

}  // namespace lamina::cpu
