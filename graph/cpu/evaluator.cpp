#include "graph/cpu/evaluator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "graph/cpu/image.h"
#include "graph/hammersley.h"
#include "nodes/kernels/kernels.h"
#include "nodes/metals.h"

// The layered model's pinned choices are stated beside the functions that make them (eval_instance,
// select_lobes, pdf_at). What is done once: the stack is expanded into a tree of instances (Plan),
// constant roughness is turned into slopes, and a material without texture nodes has every
// instance's parameters resolved, so that its queries run the kernels and nothing else. Results
// are bit for bit those of resolving the parameters at every query.
namespace lamina::cpu {

using glm::vec2;
using glm::vec3;
namespace k = lamina::kernels;

namespace {

enum class Kind { Layer, Mix, Lambert, OrenNayar, Conductor };

// A stack has at most kMaxLobes lobes; every mix instance has a lobe on each side, so the
// instances (lobes plus mixes) are fewer than twice that.
constexpr int kMaxInstances = 2 * kMaxLobes;

const float kPi = k::LAMINA_PI;

vec3 clamp01(vec3 c) { return glm::clamp(c, vec3(0.0f), vec3(1.0f)); }

bool is_microfacet(Kind kind) { return kind == Kind::Layer || kind == Kind::Conductor; }

// One stack node as reached along one path from the root. A node that two stacks of a mix share
// is reached twice, under different layers, so what depends on the layers above it (its relative
// index, its clamped slope) belongs to the instance, not to the node.
struct Instance {
  Kind kind = Kind::Lambert;
  int node = -1;         // index into Program::stack
  int parent = -1;       // the instance above it; -1 for the root
  int base = -1;         // layer: the instance below
  int a = -1, b = -1;    // mix: the instances of its two stacks
  int distribution = 0;  // layer, conductor: the kernels' distribution
  int fresnel = 0;       // layer, conductor: the kernels' fresnel_mode
};

// An instance's parameters at one shading point, read from constants or texture registers and
// clamped to their declared ranges (a texture cannot push the model outside its domain), with
// what the instances above it pass down. Trivial on purpose: arrays of it cost nothing to declare.
struct Params {
  float n_above;    // absolute index of the medium above the instance (1 at the top)
  float m_above;    // the slope the instance above passes down (Elek sec. 3), 0 at the top
  float ior;        // layer: absolute index below its interface
  float eta;        // layer: the relative index ior / n_above
  float m;          // layer, conductor: the slope after clamping to the layers above
  float thickness;  // layer
  float weight;     // mix
  float sigma;      // oren_nayar
  vec3 absorption;  // layer
  vec3 albedo;      // lambert, oren_nayar
  vec3 n, k;        // conductor: the complex index relative to the medium above
};

// wo as one instance sees it: refracted through the layers above it, with what they let through
// (lamina_selection_step) times the mix weights on the way; valid when wo reaches the instance.
struct Reach {
  vec3 v;
  float throughput;
  bool valid;
};

// The lobe selection at one wo (course sec. 3.2.3).
struct Selection {
  std::array<Reach, kMaxInstances> reach;
  std::array<float, kMaxLobes> weight;
};

int count_lobes(const Program& program, int node, std::vector<int>& memo) {
  int& count = memo[size_t(node)];
  if (count >= 0) return count;
  const StackNode& s = program.stack[size_t(node)];
  if (const auto* layer = std::get_if<LayerNode>(&s))
    count = 1 + count_lobes(program, layer->base, memo);
  else if (const auto* mix = std::get_if<MixNode>(&s))
    count = count_lobes(program, mix->a, memo) + count_lobes(program, mix->b, memo);
  else
    count = 1;
  count = std::min(count, kMaxLobes + 1);  // saturates: a stack shared by many mixes doubles per level
  return count;
}

}  // namespace

struct Evaluator::Plan {
  std::vector<Instance> instances;  // depth first, parents before children; 0 is the root
  std::vector<int> lobe_instance;   // lobe j is instances[lobe_instance[j]]
  std::vector<float> slope;         // per stack node with constant roughness: lamina_slope of it
  bool clamp = true;                // Elek's clamping of lower slopes
  bool textured = false;            // texture operations feed the stack
  std::vector<Params> fixed;        // untextured: every instance's parameters, resolved once
};

namespace {

using Plan = Evaluator::Plan;

// Numbers instances as collect_lobes numbers lobes: a layer before its base, a mix's a before its
// b. So the lobes are the instances that are not mixes, in order.
int add_instances(Plan& plan, const Program& program, int node, int parent) {
  int index = int(plan.instances.size());
  Instance in;
  in.node = node;
  in.parent = parent;
  const StackNode& s = program.stack[size_t(node)];
  if (const auto* layer = std::get_if<LayerNode>(&s)) {
    const auto& d = std::get<DielectricInterface>(layer->interface);
    in.kind = Kind::Layer;
    in.distribution = int(d.distribution);
    in.fresnel = int(d.fresnel);
    plan.instances.push_back(in);
    plan.lobe_instance.push_back(index);
    int base = add_instances(plan, program, layer->base, index);
    plan.instances[size_t(index)].base = base;
  } else if (const auto* mix = std::get_if<MixNode>(&s)) {
    in.kind = Kind::Mix;
    plan.instances.push_back(in);
    int a = add_instances(plan, program, mix->a, index);
    int b = add_instances(plan, program, mix->b, index);
    plan.instances[size_t(index)].a = a;
    plan.instances[size_t(index)].b = b;
  } else {
    if (const auto* c = std::get_if<ConductorNode>(&s)) {
      in.kind = Kind::Conductor;
      in.distribution = int(c->distribution);
      in.fresnel = int(c->fresnel);
    } else {
      in.kind = std::holds_alternative<LambertNode>(s) ? Kind::Lambert : Kind::OrenNayar;
    }
    plan.instances.push_back(in);
    plan.lobe_instance.push_back(index);
  }
  return index;
}

struct Registers {
  const float* regs;
  float read(const ScalarRef& s) const { return s.slot < 0 ? s.constant : regs[s.slot]; }
  vec3 read(const ColorRef& c) const {
    return c.slot < 0 ? c.constant : vec3(regs[c.slot], regs[c.slot + 1], regs[c.slot + 2]);
  }
};

// Runs the texture operations at ctx, filling the registers.
void run_texture_ops(const Program& program, const ShadingContext& ctx, float* regs) {
  Registers r{regs};
  for (const TextureOp& op : program.ops) {
    if (const auto* c = std::get_if<CheckerOp>(&op)) {
      float v = k::checker_value(ctx.uv, c->scale);
      vec3 color = glm::mix(r.read(c->color_a), r.read(c->color_b), v);
      regs[c->color_slot] = color.x;
      regs[c->color_slot + 1] = color.y;
      regs[c->color_slot + 2] = color.z;
      regs[c->value_slot] = v;
    } else if (const auto* img = std::get_if<ImageOp>(&op)) {
      vec2 uv = k::lamina_image_uv(ctx.uv, img->uv_rotation_deg, img->uv_scale, img->uv_offset);
      glm::vec4 texel = sample_bilinear(*img->image, uv, Wrap(img->wrap));
      regs[img->color_slot] = texel.x;
      regs[img->color_slot + 1] = texel.y;
      regs[img->color_slot + 2] = texel.z;
      regs[img->value_slot] = k::lamina_luminance(vec3(texel));
      regs[img->alpha_slot] = texel.w;
    } else if (const auto* remap = std::get_if<RemapOp>(&op)) {
      regs[remap->value_slot] = k::remap_value(r.read(remap->value), remap->in_min, remap->in_max, remap->out_min,
                                               remap->out_max, remap->clamp);
    }
  }
}

float own_slope(const Plan& plan, const Registers& r, int node, const RoughnessRef& roughness) {
  if (roughness.value.slot < 0) return plan.slope[size_t(node)];
  return k::lamina_slope(r.read(roughness.value), roughness.degrees);
}

// Every instance's parameters from the registers, top down: a layer passes its index and clamped
// slope to the instance below it, a mix passes on what it received.
void resolve_params(const Plan& plan, const Program& program, const float* regs, Params* out) {
  Registers r{regs};
  for (size_t i = 0; i < plan.instances.size(); ++i) {
    const Instance& in = plan.instances[i];
    Params& p = out[i];
    p = Params{1.0f, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, vec3(0.0f), vec3(0.0f), vec3(1.0f), vec3(0.0f)};
    if (in.parent >= 0) {
      const Params& up = out[size_t(in.parent)];
      bool layer = plan.instances[size_t(in.parent)].kind == Kind::Layer;
      p.n_above = layer ? up.ior : up.n_above;
      p.m_above = layer ? up.m : up.m_above;
    }
    const StackNode& s = program.stack[size_t(in.node)];
    if (const auto* layer = std::get_if<LayerNode>(&s)) {
      const auto& d = std::get<DielectricInterface>(layer->interface);
      p.ior = std::clamp(r.read(d.ior), 1.0f, 4.0f);
      p.eta = p.ior / p.n_above;
      p.m = k::lamina_effective_slope(own_slope(plan, r, in.node, d.roughness), p.m_above, plan.clamp);
      if (const auto* a = std::get_if<AbsorbingMedium>(&layer->medium)) {
        p.absorption = glm::max(r.read(a->absorption), vec3(0.0f));
        p.thickness = std::max(r.read(a->thickness), 0.0f);
      }
    } else if (const auto* mix = std::get_if<MixNode>(&s)) {
      p.weight = std::clamp(r.read(mix->weight), 0.0f, 1.0f);
    } else if (const auto* lambert = std::get_if<LambertNode>(&s)) {
      p.albedo = clamp01(r.read(lambert->albedo));
    } else if (const auto* on = std::get_if<OrenNayarNode>(&s)) {
      p.albedo = clamp01(r.read(on->albedo));
      p.sigma = std::clamp(r.read(on->sigma), 0.0f, kPi / 2.0f);
    } else if (const auto* c = std::get_if<ConductorNode>(&s)) {
      // The metal's index relative to the layer above it (Elek's shader uses the absolute one).
      p.n = glm::clamp(r.read(c->n), vec3(1.0e-3f), vec3(float(kMaxConductorIndex))) / p.n_above;
      p.k = glm::clamp(r.read(c->k), vec3(0.0f), vec3(float(kMaxConductorIndex))) / p.n_above;
      p.m = k::lamina_effective_slope(own_slope(plan, r, in.node, c->roughness), p.m_above, plan.clamp);
    }
  }
}

// The parameters at a shading point: the plan's fixed ones for an untextured material, or ones
// resolved at ctx. Declaring one costs nothing until a textured material resolves into it.
class Point {
 public:
  Point(const Plan& plan, const Program& program) : plan_(plan), program_(program) {}

  const Params* at(const ShadingContext& ctx) {
    if (!plan_.textured) return plan_.fixed.data();
    run_texture_ops(program_, ctx, regs_.data());
    resolve_params(plan_, program_, regs_.data(), params_.data());
    return params_.data();
  }
  // For the batch forms: resolves again only when uv changes.
  const Params* at_uv(vec2 uv) {
    if (!plan_.textured) return plan_.fixed.data();
    if (!resolved_ || uv != uv_) {
      ShadingContext ctx;
      ctx.uv = uv;
      at(ctx);
      uv_ = uv;
      resolved_ = true;
    }
    return params_.data();
  }
  const float* registers() const { return regs_.data(); }

 private:
  const Plan& plan_;
  const Program& program_;
  std::array<float, kMaxSlots> regs_;
  std::array<Params, kMaxInstances> params_;
  vec2 uv_{0.0f};
  bool resolved_ = false;
};

// --- eval ----------------------------------------------------------------------------------------

// Elek's Algorithm 1 generalised to any depth (course sec. 3.1, Elek eq. 2):
//   f(i)(L, V) = f_i(L, V) + T_i f(i+1)(L', V') a_i t_i
// with f_i the Torrance-Sparrow lobe of interface i, relative index eta_i = n_i / n_(i-1), F_i
// evaluated at V.H, T_i = 1 - F_i (so T21 = T12), L' and V' refracted through the macro normal,
// a_i the Beer-Lambert absorption (Elek eq. 3) and t_i = (1 - G_i) + T_i G_i (Elek eq. 4).
vec3 eval_instance(const Plan& plan, const Params* params, int index, vec3 l, vec3 v) {
  const Instance& in = plan.instances[size_t(index)];
  const Params& p = params[index];
  switch (in.kind) {
    case Kind::Layer: {
      vec3 l_below, v_below, carry;
      vec3 f = k::lamina_interface_eval(l, v, p.eta, in.distribution, in.fresnel, p.m, p.absorption, p.thickness,
                                        l_below, v_below, carry);
      if (l_below.z <= 0.0f || v_below.z <= 0.0f) return f;  // total internal reflection: nothing below
      return f + eval_instance(plan, params, in.base, l_below, v_below) * carry;
    }
    case Kind::Mix:
      return glm::mix(eval_instance(plan, params, in.a, l, v), eval_instance(plan, params, in.b, l, v), p.weight);
    case Kind::Lambert: return k::lamina_lambert_eval(l, v, p.albedo);
    case Kind::OrenNayar: return k::oren_nayar(l, v, p.albedo, p.sigma);
    case Kind::Conductor: return k::lamina_conductor_eval(l, v, p.n, p.k, in.distribution, in.fresnel, p.m);
  }
  return vec3(0.0f);
}

vec3 eval_at(const Plan& plan, const Params* params, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0f || wo.z <= 0.0f || plan.instances.empty()) return vec3(0.0f);
  return glm::max(eval_instance(plan, params, 0, wi, wo), vec3(0.0f));
}

// --- lobe selection --------------------------------------------------------------------------------

// Selection probabilities (course sec. 3.2.3): each lobe's estimated share of the reflected
// energy at wo: the Fresnel reflectance of its interface (or the albedo of its substrate) times
// what the layers above let through twice, (1 - F)^2 and the absorption along the refracted wo,
// times the mix weights on its path. A floor of 1% of the mean keeps every lobe reachable.
void select_lobes(const Plan& plan, const Params* params, vec3 wo, Selection& s) {
  for (size_t i = 0; i < plan.instances.size(); ++i) {
    const Instance& in = plan.instances[i];
    Reach& r = s.reach[i];
    if (in.parent < 0) {
      r = Reach{wo, 1.0f, wo.z > 0.0f};
      continue;
    }
    const Instance& parent = plan.instances[size_t(in.parent)];
    const Params& up = params[in.parent];
    const Reach& above = s.reach[size_t(in.parent)];
    if (parent.kind == Kind::Mix) {
      float share = int(i) == parent.a ? 1.0f - up.weight : up.weight;
      r = Reach{above.v, above.throughput * share, above.valid};
      continue;
    }
    r = Reach{above.v, 0.0f, false};
    if (!above.valid) continue;
    float factor = 0.0f;
    vec3 below = k::lamina_selection_step(above.v, up.eta, parent.fresnel, up.absorption, up.thickness, factor);
    if (below.z > 0.0f) r = Reach{below, above.throughput * factor, true};
  }
  size_t count = plan.lobe_instance.size();
  float total = 0.0f;
  int valid_count = 0;
  for (size_t j = 0; j < count; ++j) {
    int index = plan.lobe_instance[j];
    const Instance& in = plan.instances[size_t(index)];
    const Params& p = params[index];
    const Reach& r = s.reach[size_t(index)];
    float estimate = 0.0f;
    if (r.valid) {
      ++valid_count;
      switch (in.kind) {
        case Kind::Layer: estimate = k::lamina_fresnel_dielectric(in.fresnel, r.v.z, p.eta); break;
        case Kind::Conductor:
          estimate = k::lamina_luminance(k::lamina_fresnel_conductor(in.fresnel, r.v.z, p.n, p.k));
          break;
        case Kind::Lambert:
        case Kind::OrenNayar: estimate = k::lamina_luminance(p.albedo); break;
        case Kind::Mix: break;
      }
      estimate *= r.throughput;
    }
    s.weight[j] = estimate;
    total += estimate;
  }
  if (valid_count == 0) {
    for (size_t j = 0; j < count; ++j) s.weight[j] = 0.0f;
    return;
  }
  float floor = total > 0.0f ? 0.01f * total / float(valid_count) : 1.0f;
  float sum = 0.0f;
  for (size_t j = 0; j < count; ++j) {
    if (s.reach[size_t(plan.lobe_instance[j])].valid) s.weight[j] += floor;
    sum += s.weight[j];
  }
  for (size_t j = 0; j < count; ++j) s.weight[j] /= sum;
}

// --- pdf -------------------------------------------------------------------------------------------

// A lobe draws directions in its own frame, below the layers above it. Directions inside the
// exit cone (sin < 1/n, n the frame's absolute index) are carried up by Snell's law, with the
// solid-angle Jacobian; a microfacet lobe's directions outside the cone, which cannot leave the
// stack, are spread over the outer hemisphere by cos_out = cos_in / cos_critical (Jacobian
// cos_critical), so every lobe's density integrates to exactly 1. Diffuse lobes draw cosine-
// weighted directions inside the cone only, which is the cosine distribution outside.
float pdf_at(const Plan& plan, const Params* params, const Selection& s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  // wi refracted down to every instance, with d omega_below / d omega_outside along the way.
  std::array<vec3, kMaxInstances> w;
  std::array<float, kMaxInstances> jacobian;
  for (size_t i = 0; i < plan.instances.size(); ++i) {
    int parent = plan.instances[i].parent;
    if (parent < 0) {
      w[i] = wi;
      jacobian[i] = 1.0f;
    } else if (plan.instances[size_t(parent)].kind == Kind::Mix) {
      w[i] = w[size_t(parent)];
      jacobian[i] = jacobian[size_t(parent)];
    } else {
      float eta = params[parent].eta;
      vec3 below = k::refract_down(w[size_t(parent)], eta);
      jacobian[i] = jacobian[size_t(parent)] * k::refraction_jacobian(w[size_t(parent)].z, below.z, eta);
      w[i] = below;
    }
  }
  float pdf = 0.0f;
  for (size_t j = 0; j < plan.lobe_instance.size(); ++j) {
    size_t index = size_t(plan.lobe_instance[j]);
    if (s.weight[j] <= 0.0f || !s.reach[index].valid || w[index].z <= 0.0f) continue;
    const Instance& in = plan.instances[index];
    const Params& p = params[index];
    float density = is_microfacet(in.kind) ? k::lamina_microfacet_lobe_pdf(in.distribution, p.m, s.reach[index].v,
                                                                           w[index], jacobian[index], wi, p.n_above)
                                           : k::lamina_diffuse_lobe_pdf(w[index], jacobian[index], p.n_above);
    pdf += s.weight[j] * density;
  }
  return pdf;
}

// --- sample ----------------------------------------------------------------------------------------

// The lobe u_lobe picks from the selection probabilities; -1 if none can be drawn.
int choose_lobe(const Plan& plan, const Selection& s, float u_lobe) {
  int chosen = -1;
  float cumulative = 0.0f;
  for (size_t j = 0; j < plan.lobe_instance.size(); ++j) {
    if (s.weight[j] <= 0.0f) continue;
    chosen = int(j);
    cumulative += s.weight[j];
    if (u_lobe < cumulative) break;
  }
  return chosen;
}

// Carries a direction drawn below the layers above `index` back up to the outside (refract_up
// through those layers, bottom to top); vec3(0) if it cannot leave.
vec3 carry_up(const Plan& plan, const Params* params, int index, vec3 w) {
  for (int i = plan.instances[size_t(index)].parent; i >= 0; i = plan.instances[size_t(i)].parent) {
    if (plan.instances[size_t(i)].kind != Kind::Layer) continue;
    w = k::refract_up(w, params[i].eta);
    if (w.z <= 0.0f) return vec3(0.0f);
  }
  return w;
}

// Draws from lobe `chosen` (of the selection s at wo) and evaluates f and the mixture pdf there.
Sample sample_lobe(const Plan& plan, const Params* params, const Selection& s, int chosen, vec3 wo, vec2 u) {
  Sample out;
  if (chosen < 0) return out;
  int index = plan.lobe_instance[size_t(chosen)];
  const Instance& in = plan.instances[size_t(index)];
  const Params& p = params[index];
  const Reach& r = s.reach[size_t(index)];
  vec3 wi(0.0f);
  if (is_microfacet(in.kind)) {
    bool inside_cone = true;
    vec3 w = k::lamina_sample_microfacet_lobe(in.distribution, p.m, r.v, u, p.n_above, inside_cone);
    if (w.z <= 0.0f) return out;
    wi = inside_cone ? carry_up(plan, params, index, w) : w;
  } else {
    wi = carry_up(plan, params, index, k::lamina_sample_diffuse_lobe(u, p.n_above));
  }
  if (wi.z <= 0.0f) return out;
  wi = glm::normalize(wi);
  out.wi = wi;
  out.lobe = chosen;
  out.f = eval_at(plan, params, wi, wo);
  out.pdf = pdf_at(plan, params, s, wi, wo);
  return out;
}

Sample sample_at(const Plan& plan, const Params* params, vec3 wo, vec2 u, float u_lobe) {
  if (wo.z <= 0.0f) return Sample{};
  Selection s;
  select_lobes(plan, params, wo, s);
  return sample_lobe(plan, params, s, choose_lobe(plan, s, u_lobe), wo, u);
}

float pdf_at(const Plan& plan, const Params* params, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  Selection s;
  select_lobes(plan, params, wo, s);
  return pdf_at(plan, params, s, wi, wo);
}

// --- batches ---------------------------------------------------------------------------------------

struct SpanLength {
  const char* name;
  size_t length;
};

// Every span of a batch has the output's length; uv may also be empty.
void check_lengths(const char* function, std::initializer_list<SpanLength> spans, size_t uv) {
  size_t n = spans.begin()->length;
  bool ok = uv == 0 || uv == n;
  for (const SpanLength& s : spans) ok = ok && s.length == n;
  if (ok) return;
  std::string message = std::string("lamina::cpu::Evaluator::") + function + ": spans of different lengths:";
  for (const SpanLength& s : spans) message += " " + std::string(s.name) + " " + std::to_string(s.length) + ",";
  message += " uv " + std::to_string(uv) + " (every span needs the output's length " + std::to_string(n) +
             "; uv may also be empty)";
  throw std::invalid_argument(message);
}

vec2 uv_at(std::span<const vec2> uv, size_t i) { return uv.empty() ? vec2(0.0f) : uv[i]; }

}  // namespace

Evaluator::Evaluator(Program program) : program_(std::move(program)) {
  if (program_.slot_count > kMaxSlots || int(program_.stack.size()) > kMaxStackNodes)
    throw std::length_error("material '" + program_.name + "' is too large for the CPU evaluator");
  if (program_.root >= 0) {
    std::vector<int> memo(program_.stack.size(), -1);
    if (count_lobes(program_, program_.root, memo) > kMaxLobes)
      throw std::length_error("material '" + program_.name + "' has too many lobes for the CPU evaluator");
  }
  lobes_ = collect_lobes(program_);

  auto plan = std::make_shared<Plan>();
  plan->clamp = program_.clamp_lower_roughness;
  plan->textured = !program_.ops.empty();
  if (program_.root >= 0) add_instances(*plan, program_, program_.root, -1);
  if (plan->lobe_instance.size() != lobes_.size())
    throw std::logic_error("Evaluator: the instances do not match the lobes of '" + program_.name + "'");
  for (size_t j = 0; j < lobes_.size(); ++j)
    if (plan->instances[size_t(plan->lobe_instance[j])].node != lobes_[j].node)
      throw std::logic_error("Evaluator: the instances do not match the lobes of '" + program_.name + "'");
  // Constant roughness is converted to a slope once (lamina_slope calls tan).
  plan->slope.assign(program_.stack.size(), 0.0f);
  for (size_t i = 0; i < program_.stack.size(); ++i) {
    const RoughnessRef* roughness = nullptr;
    if (const auto* layer = std::get_if<LayerNode>(&program_.stack[i]))
      roughness = &std::get<DielectricInterface>(layer->interface).roughness;
    else if (const auto* c = std::get_if<ConductorNode>(&program_.stack[i]))
      roughness = &c->roughness;
    if (roughness && roughness->value.slot < 0)
      plan->slope[i] = k::lamina_slope(roughness->value.constant, roughness->degrees);
  }
  if (!plan->textured) {
    plan->fixed.resize(plan->instances.size());
    resolve_params(*plan, program_, nullptr, plan->fixed.data());
  }
  plan_ = std::move(plan);
}

vec3 Evaluator::eval(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return vec3(0.0f);
  if (!plan_->textured) return eval_at(*plan_, plan_->fixed.data(), wi, wo);
  Point point(*plan_, program_);
  return eval_at(*plan_, point.at(ctx), wi, wo);
}

float Evaluator::pdf(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  Point point(*plan_, program_);
  return pdf_at(*plan_, point.at(ctx), wi, wo);
}

EvalPdf Evaluator::eval_pdf(const ShadingContext& ctx, vec3 wi, vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return {};
  Point point(*plan_, program_);
  const Params* params = point.at(ctx);
  return {eval_at(*plan_, params, wi, wo), pdf_at(*plan_, params, wi, wo)};
}

Sample Evaluator::sample(const ShadingContext& ctx, vec3 wo, vec2 u, float u_lobe) const {
  if (wo.z <= 0.0f) return {};
  Point point(*plan_, program_);
  return sample_at(*plan_, point.at(ctx), wo, u, u_lobe);
}

std::vector<float> Evaluator::lobe_weights(const ShadingContext& ctx, vec3 wo) const {
  Point point(*plan_, program_);
  Selection s;
  select_lobes(*plan_, point.at(ctx), wo, s);
  return std::vector<float>(s.weight.begin(), s.weight.begin() + long(lobes_.size()));
}

std::vector<float> Evaluator::texture_registers(const ShadingContext& ctx) const {
  Point point(*plan_, program_);
  point.at(ctx);
  return std::vector<float>(point.registers(), point.registers() + program_.slot_count);
}

vec3 Evaluator::albedo(const ShadingContext& ctx, vec3 wo, int points_per_lobe) const {
  if (wo.z <= 0.0f || points_per_lobe <= 0) return vec3(0.0f);
  // The parameters and the selection at wo are the same for every point: computed once.
  Point point(*plan_, program_);
  const Params* params = point.at(ctx);
  Selection s;
  select_lobes(*plan_, params, wo, s);
  // Stratified over lobes: lobe j's share is weight_j times the mean of f cos / pdf over its own
  // samples, where pdf is the full mixture density; the shares add up to the integral.
  vec3 total(0.0f);
  for (size_t j = 0; j < lobes_.size(); ++j) {
    if (s.weight[j] <= 0.0f) continue;
    float lo = 0.0f;
    for (size_t i = 0; i < j; ++i) lo += s.weight[i];
    float u_lobe = std::min(lo + 0.5f * s.weight[j], 1.0f - 1.0e-7f);
    // Rounding may let u_lobe pick a neighbour of a tiny lobe; those samples are not lobe j's.
    int chosen = choose_lobe(*plan_, s, u_lobe);
    if (chosen != int(j)) continue;
    vec3 sum(0.0f);
    for (int i = 0; i < points_per_lobe; ++i) {
      vec2 u = hammersley(uint32_t(i), uint32_t(points_per_lobe));
      Sample sample = sample_lobe(*plan_, params, s, chosen, wo, u);
      if (sample.pdf > 0.0f) sum += sample.f * sample.wi.z / sample.pdf;
    }
    total += s.weight[j] * sum / float(points_per_lobe);
  }
  return total;
}

void Evaluator::eval(std::span<const vec3> wi, std::span<const vec3> wo, std::span<const vec2> uv,
                     std::span<vec3> f) const {
  check_lengths("eval", {{"f", f.size()}, {"wi", wi.size()}, {"wo", wo.size()}}, uv.size());
  Point point(*plan_, program_);
  for (size_t i = 0; i < f.size(); ++i) f[i] = eval_at(*plan_, point.at_uv(uv_at(uv, i)), wi[i], wo[i]);
}

void Evaluator::pdf(std::span<const vec3> wi, std::span<const vec3> wo, std::span<const vec2> uv,
                    std::span<float> out) const {
  check_lengths("pdf", {{"pdf", out.size()}, {"wi", wi.size()}, {"wo", wo.size()}}, uv.size());
  Point point(*plan_, program_);
  for (size_t i = 0; i < out.size(); ++i) out[i] = pdf_at(*plan_, point.at_uv(uv_at(uv, i)), wi[i], wo[i]);
}

void Evaluator::eval_pdf(std::span<const vec3> wi, std::span<const vec3> wo, std::span<const vec2> uv,
                         std::span<EvalPdf> out) const {
  check_lengths("eval_pdf", {{"out", out.size()}, {"wi", wi.size()}, {"wo", wo.size()}}, uv.size());
  Point point(*plan_, program_);
  for (size_t i = 0; i < out.size(); ++i) {
    if (wi[i].z <= 0.0f || wo[i].z <= 0.0f) {
      out[i] = EvalPdf{};
      continue;
    }
    const Params* params = point.at_uv(uv_at(uv, i));
    out[i] = EvalPdf{eval_at(*plan_, params, wi[i], wo[i]), pdf_at(*plan_, params, wi[i], wo[i])};
  }
}

void Evaluator::sample(std::span<const vec3> wo, std::span<const vec2> u, std::span<const float> u_lobe,
                       std::span<const vec2> uv, std::span<Sample> out) const {
  check_lengths("sample", {{"out", out.size()}, {"wo", wo.size()}, {"u", u.size()}, {"u_lobe", u_lobe.size()}},
                uv.size());
  Point point(*plan_, program_);
  for (size_t i = 0; i < out.size(); ++i) out[i] = sample_at(*plan_, point.at_uv(uv_at(uv, i)), wo[i], u[i], u_lobe[i]);
}

}  // namespace lamina::cpu
