// GLSL/CPU parity: runs the generated GLSL of every material given on the command line on a
// real OpenGL implementation (Mesa llvmpipe through headless EGL) over a grid of (wi, wo, uv)
// with grazing directions, and compares eval, pdf and sample with the CPU evaluator.
//
//   lamina_glsl_parity [--targets 330,450,es300] [--modes inline,uniforms] [--entries point|uv]
//                      [--perturb eval_scale|eval_nan|kernel_constant|sample_direction]
//                      [--random N [--seed S]] [FILE...]
//
// --entries: the shader calls eval, pdf and sample with a LaminaPoint resolved once per query
// (point, the default: how a renderer calls them) or with the shading context (uv: each call
// resolves the point again, through the entry points at a context and at a point).
//
// --random N adds N random valid materials (tests/random_stacks.h, seed S, default 1): nested
// layers and mixes over every substrate with every distribution and Fresnel term, some parameters
// textured, so that the composition is compared on stacks nobody wrote by hand.
//
// Tolerances (issue 4): eval and pdf within 1e-3 relative with an absolute floor of 1e-5, i.e.
// |gpu - cpu| <= max(1e-3 |cpu|, 1e-5); sampled directions within 1e-4 per component for the same
// random numbers; the sample's f and pdf within the eval and pdf tolerance of the CPU's eval and
// pdf at the direction the GPU drew. Every error is printed as a fraction of its tolerance, the
// number the pass/fail rule uses: a check passes when its worst error is at most 1. A NaN or an
// infinity on either side is an error of infinity.
//
// Where the CPU's own answer is ill-conditioned, no implementation can be expected to match it to
// 1e-3: a pdf near its integrable singularity (a folded microfacet lobe at the mirror direction),
// grazing cancellation, or the sampling map at a discontinuity (u_layer at the boundary between
// two lobes, u where a draw crosses the horizon). There, and only when the plain tolerance fails,
// a check's tolerance widens to the CPU's own spread under inputs nudged as far as the two sides'
// roundings differ: each direction component by +-1e-6 (renormalised) for eval and pdf, each of
// u and u_layer by +-1e-5 for the sampled direction. Such queries are counted and printed ("ill-
// conditioned"), and a run fails when they exceed 1% of its queries, so that the widening cannot
// hide a broad error. Exits 1 on any failure.
//
// Image textures are bound as the module's header says: RGBA32F textures of the decoded texels.
//
// --perturb KIND turns the program into a test of the comparator: each module is deliberately
// broken before it runs, and the program exits 0 only when every run fails the check KIND must
// break (eval_scale: eval times 1.01, breaks eval; eval_nan: eval NaN, breaks eval;
// kernel_constant: LAMINA_INV_PI in the embedded kernels 0.5% too large, breaks eval;
// sample_direction: sampled directions tilted by about 1e-3, breaks the sample direction).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "glsl/gl_runner.h"
#include "glsl/material_pass.h"
#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu/image.h"
#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/load.h"
#include "random_stacks.h"

using glm::vec2;
using glm::vec3;
using glm::vec4;
using namespace lamina;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kRelTol = 1e-3f, kAbsFloor = 1e-5f, kDirTol = 1e-4f;
// How far the conditioning check nudges directions (per component) and random numbers, and the
// share of a run's queries whose tolerance it may widen.
constexpr float kDirectionNudge = 1e-6f, kRandomNudge = 1e-5f, kIllConditionedShare = 0.01f;

struct Query {
  vec3 wi, wo;
  vec2 uv, u;
  float u_layer;
};

vec3 direction(double theta_deg, double phi_deg) {
  double t = theta_deg * kPi / 180.0, p = phi_deg * kPi / 180.0;
  return glm::normalize(vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t))));
}

// 64 x 64 grid pairs over thetas up to 89.5 degrees (grazing) and 8 azimuths, then 1024 random
// pairs; uv over [-0.6, 1.6] so that texture wrapping is exercised.
std::vector<Query> make_queries() {
  const double thetas[] = {0.0, 12.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.5};
  std::vector<vec3> dirs;
  for (double t : thetas)
    for (int k = 0; k < 8; ++k) dirs.push_back(direction(t, 45.0 * k + 7.0));
  std::mt19937 rng(20261122u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), wide(-0.6f, 1.6f);
  std::vector<Query> q;
  for (const vec3& wo : dirs)
    for (const vec3& wi : dirs)
      q.push_back({wi, wo, vec2(wide(rng), wide(rng)), vec2(unit(rng), unit(rng)), unit(rng)});
  for (int i = 0; i < 1024; ++i) {
    auto hemi = [&] {
      float z = 1.0f - unit(rng), phi = float(2.0 * kPi) * unit(rng);
      float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      return vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    vec3 wi = hemi(), wo = hemi();
    q.push_back({wi, wo, vec2(wide(rng), wide(rng)), vec2(unit(rng), unit(rng)), unit(rng)});
  }
  return q;
}

// A query's shading context: its uv, a world-space position that moves with it, so that textures
// over position (procedural noise, Voronoi cells, marble in 3D) vary across the queries as those
// over uv do, and a footprint from 0 (on the diagonal u = v) to 0.55 uv, so that the filtered
// textures (noise octaves, marble stripes, Voronoi cells fading to their means and the stacks that
// read them) are compared from point samples to full filtering. The harness computes the same
// context in GLSL (lamina_q_context).
ShadingContext query_context(vec2 uv) {
  ShadingContext ctx;
  ctx.uv = uv;
  ctx.position = vec3(3.25f * uv.x - 0.5f, 2.5f * uv.y + 0.25f, 0.75f * (uv.x - uv.y));
  ctx.footprint = 0.25f * std::abs(uv.x - uv.y);
  return ctx;
}

// WHERE is the shading point's argument of the three functions: `point`, resolved once (the
// default, as a renderer calls them), or `ctx`, the shading context, for the entry points that
// resolve at every call (each through the next: context, point; the uv entry points are the
// context ones at lamina_context(uv)).
const char* kHarness = R"(
// ---- parity harness: one query per fragment
uniform sampler2D lamina_q_wi;
uniform sampler2D lamina_q_wo;
uniform sampler2D lamina_q_u;
layout(location = 0) out vec4 o_eval;
layout(location = 1) out vec4 o_sample;
layout(location = 2) out vec4 o_sample_f;
LaminaContext lamina_q_context(vec2 uv) {
  LaminaContext ctx = lamina_context(uv);
  ctx.position = vec3(3.25f * uv.x - 0.5f, 2.5f * uv.y + 0.25f, 0.75f * (uv.x - uv.y));
  ctx.footprint = 0.25f * abs(uv.x - uv.y);
  return ctx;
}
void main() {
  ivec2 at = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(lamina_q_wi, at, 0);
  vec4 b = texelFetch(lamina_q_wo, at, 0);
  vec4 c = texelFetch(lamina_q_u, at, 0);
  LaminaContext ctx = lamina_q_context(c.xy);
  LaminaPoint point = NAME_point(ctx);
  o_eval = vec4(NAME_eval(a.xyz, b.xyz, WHERE), NAME_pdf(a.xyz, b.xyz, WHERE));
  vec3 wi;
  float pdf;
  vec3 f = NAME_sample(b.xyz, c.zw, a.w, WHERE, wi, pdf);
  o_sample = vec4(wi, pdf);
  o_sample_f = vec4(f, 0.0f);
}
)";

std::string harness(const std::string& prefix, bool per_call) {
  return glsl::replace_all(glsl::replace_all(kHarness, "WHERE", per_call ? "ctx" : "point"), "NAME", prefix);
}

// |gpu - cpu| / max(1e-3 |cpu|, 1e-5): the error as a fraction of the eval and pdf tolerance,
// widened to `spread` where the CPU is ill-conditioned. Infinite when either side is not finite.
float tolerance_fraction(float gpu, float cpu, float spread = 0.0f) {
  if (!std::isfinite(gpu) || !std::isfinite(cpu)) return INFINITY;
  return std::abs(gpu - cpu) / std::max({kRelTol * std::abs(cpu), kAbsFloor, spread});
}

// The fractions of eval's three channels and the pdf.
vec4 eval_fractions(const vec4& gpu, const cpu::EvalPdf& cpu, const vec4& spread = vec4(0.0f)) {
  vec4 f;
  for (int c = 0; c < 3; ++c) f[c] = tolerance_fraction(gpu[c], cpu.f[c], spread[c]);
  f.w = tolerance_fraction(gpu.w, cpu.pdf, spread.w);
  return f;
}

bool within(const vec4& fractions) {
  return fractions.x <= 1.0f && fractions.y <= 1.0f && fractions.z <= 1.0f && fractions.w <= 1.0f;
}

// How far the CPU's eval (per channel) and pdf move when one component of wi or of wo is nudged by
// kDirectionNudge: the error an implementation that rounds differently may make there.
vec4 eval_spread(const cpu::Evaluator& e, const ShadingContext& ctx, vec3 wi, vec3 wo) {
  const cpu::EvalPdf at = e.eval_pdf(ctx, wi, wo);
  const vec4 base(at.f, at.pdf);
  vec4 spread(0.0f);
  for (int which = 0; which < 2; ++which)
    for (int c = 0; c < 3; ++c)
      for (float sign : {-1.0f, 1.0f}) {
        vec3 a = wi, b = wo;
        vec3& nudged = which == 0 ? a : b;
        nudged[c] += sign * kDirectionNudge;
        nudged = glm::normalize(nudged);
        const cpu::EvalPdf n = e.eval_pdf(ctx, a, b);
        const vec4 change = glm::abs(vec4(n.f, n.pdf) - base);
        if (std::isfinite(change.x + change.y + change.z + change.w)) spread = glm::max(spread, change);
      }
  return spread;
}

// How far the CPU's sampled direction moves (largest component) when one of u and u_layer is
// nudged by kRandomNudge; infinite where a nudge changes whether anything is drawn.
float direction_spread(const cpu::Evaluator& e, const ShadingContext& ctx, const Query& q, const cpu::Sample& drawn) {
  float spread = 0.0f;
  for (int k = 0; k < 3; ++k)
    for (float sign : {-1.0f, 1.0f}) {
      vec2 u = q.u;
      float u_layer = q.u_layer;
      float& nudged = k < 2 ? u[k] : u_layer;
      nudged = std::clamp(nudged + sign * kRandomNudge, 0.0f, std::nextafter(1.0f, 0.0f));
      const cpu::Sample n = e.sample(ctx, q.wo, u, u_layer);
      if ((n.pdf > 0.0f) != (drawn.pdf > 0.0f)) return INFINITY;
      const vec3 change = glm::abs(n.wi - drawn.wi);
      spread = std::max({spread, change.x, change.y, change.z});
    }
  return spread;
}

// The worst of one check's errors, each a fraction of its tolerance; NaN counts as infinite.
struct Worst {
  float fraction = 0.0f;
  size_t query = 0;
  int failures = 0;
  void add(float f, size_t q) {
    if (std::isnan(f)) f = INFINITY;
    if (!(f <= 1.0f)) ++failures;
    if (f > fraction) {
      fraction = f;
      query = q;
    }
  }
};

struct Run {
  glsl::Target target;
  bool uniforms;
  bool per_call;  // the entry points that resolve the point at every call (--entries uv)
};

// The checks of one run.
struct Checks {
  Worst eval, pdf, direction, sample_f, sample_pdf;
  int ill_conditioned = 0;  // queries that pass only on the CPU's own spread
  bool too_many_ill_conditioned = false;
  int failures() const {
    return eval.failures + pdf.failures + direction.failures + sample_f.failures + sample_pdf.failures +
           int(too_many_ill_conditioned);
  }
};

enum class Perturbation { None, EvalScale, EvalNan, KernelConstant, SampleDirection };

// A deliberately wrong module; false when the text to change is missing (then the perturbation
// proves nothing).
bool perturb(std::string& source, const std::string& prefix, int model, Perturbation kind) {
  // The composition's call that ends the point's eval (and sample), as the generator writes it.
  const std::string call = std::string(glsl::composition_function(model)) + "(" + prefix + "_count, " + prefix +
                           "_entries, point.params, wi, wo);\n}\n\n//";
  auto change = [&](const std::string& from, const std::string& to) {
    std::string changed = glsl::replace_all(source, from, to);
    bool found = changed != source;
    source = changed;
    return found;
  };
  switch (kind) {
    case Perturbation::None: return true;
    case Perturbation::EvalScale: return change("  return " + call, "  return 1.01f * " + call);
    case Perturbation::EvalNan:  // a quiet NaN that depends on the query, so that no compiler folds it
      return change("  return " + call, "  return uintBitsToFloat(0x7fc00000u + uint(wi.z < 0.5f)) * " + call);
    case Perturbation::KernelConstant:
      return change("const float LAMINA_INV_PI = 0.318309886183791f;", "const float LAMINA_INV_PI = 0.32f;");
    case Perturbation::SampleDirection:
      return change("  wi = d;\n", "  wi = normalize(d + vec3(1.0e-3f, 0.0f, 0.0f));\n");
  }
  return false;
}

// Runs one material in one target and mode; nothing when the module did not run at all.
std::optional<Checks> run_material(gltest::Runner& runner, const Program& program, const Run& run,
                                   Perturbation perturbation, const std::vector<Query>& queries,
                                   const cpu::Evaluator& cpu_eval, const std::vector<cpu::EvalPdf>& ref_eval,
                                   const std::vector<cpu::Sample>& ref_sample) {
  const char* target = glsl::target_name(run.target);
  const char* mode = run.uniforms ? "uniforms" : "inline";
  glsl::Options options;
  options.target = run.target;
  options.uniforms = run.uniforms;
  glsl::Module module = glsl::generate(std::span<const Program>(&program, 1), options);
  const glsl::MaterialInterface& mi = module.materials.front();
  if (!perturb(module.source, mi.prefix, program.model, perturbation)) {
    std::printf("  FAIL %s %s: the perturbation found nothing to change\n", target, mode);
    return std::nullopt;
  }

  const int width = 64, height = int((queries.size() + 63) / 64);
  gltest::Pass pass;
  pass.fragment_source = module.source + harness(mi.prefix, run.per_call);
  pass.width = width;
  pass.height = height;
  pass.outputs = 3;
  gltest::Texture twi{"lamina_q_wi", width, height, {}, {}}, two{"lamina_q_wo", width, height, {}, {}},
      tu{"lamina_q_u", width, height, {}, {}};
  for (size_t i = 0; i < size_t(width * height); ++i) {
    const Query& q = queries[std::min(i, queries.size() - 1)];
    twi.texels.push_back(vec4(q.wi, q.u_layer));
    two.texels.push_back(vec4(q.wo, 0.0f));
    tu.texels.push_back(vec4(q.uv, q.u));
  }
  pass.textures = {twi, two, tu};
  test::bind_material(pass, program, module, mi, run.uniforms);
  std::vector<std::vector<vec4>> out;
  std::string error;
  if (!runner.run(pass, &out, &error)) {
    std::printf("  FAIL %s %s: %s\n", target, mode, error.c_str());
    return std::nullopt;
  }

  Checks checks;
  for (size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    const ShadingContext ctx = query_context(q.uv);
    bool widened = false;
    // The plain tolerance first; the CPU's spread only where that fails (see the top of the file).
    vec4 e = eval_fractions(out[0][i], ref_eval[i]);
    if (!within(e)) {
      vec4 wide = eval_fractions(out[0][i], ref_eval[i], eval_spread(cpu_eval, ctx, q.wi, q.wo));
      widened = within(wide);
      e = wide;
    }
    for (int c = 0; c < 3; ++c) checks.eval.add(e[c], i);
    checks.pdf.add(e.w, i);

    const vec4 s = out[1][i], sf = out[2][i];
    const cpu::Sample& r = ref_sample[i];
    // The CPU gives wi = 0 and pdf = 0 when it draws nothing; the GPU must do the same.
    const bool gpu_drew = !(s.w == 0.0f);  // NaN counts as drawn, and fails below
    const vec3 diff = glm::abs(vec3(s) - r.wi);
    float d = std::isfinite(diff.x + diff.y + diff.z) ? std::max({diff.x, diff.y, diff.z}) : INFINITY;
    if ((r.pdf > 0.0f) != gpu_drew) d = INFINITY;
    float direction = d / kDirTol;
    // A GPU value that is not finite fails whatever the CPU's conditioning; where a nudge changes
    // whether the CPU draws at all, whether the GPU drew is no error (an infinite spread).
    const bool gpu_finite = std::isfinite(s.x + s.y + s.z + s.w);
    if (!(direction <= 1.0f) && gpu_finite) {
      const float spread = direction_spread(cpu_eval, ctx, q, r);
      direction = std::isinf(spread) ? 0.0f : d / std::max(kDirTol, spread);
      widened = widened || direction <= 1.0f;
    }
    checks.direction.add(direction, i);
    // The sample's f and pdf must be eval and pdf at the direction the GPU drew: compare with the
    // CPU at that direction (the direction itself is checked above, against the CPU's draw).
    if (r.pdf > 0.0f || gpu_drew) {
      const vec3 at_wi = vec3(s);
      cpu::EvalPdf at = s.w > 0.0f ? cpu_eval.eval_pdf(ctx, at_wi, q.wo) : cpu::EvalPdf{};
      vec4 f = eval_fractions(vec4(vec3(sf), s.w), at);
      if (!within(f) && s.w > 0.0f) {
        vec4 wide = eval_fractions(vec4(vec3(sf), s.w), at, eval_spread(cpu_eval, ctx, at_wi, q.wo));
        widened = widened || within(wide);
        f = wide;
      }
      for (int c = 0; c < 3; ++c) checks.sample_f.add(f[c], i);
      checks.sample_pdf.add(f.w, i);
    }
    checks.ill_conditioned += widened ? 1 : 0;
  }
  checks.too_many_ill_conditioned = float(checks.ill_conditioned) > kIllConditionedShare * float(queries.size());
  std::printf(
      "  %-5s %-8s eval %8.2e  pdf %8.2e  sample dir %8.2e  sample f %8.2e  sample pdf %8.2e  (%d "
      "ill-conditioned%s)%s\n",
      target, mode, double(checks.eval.fraction), double(checks.pdf.fraction), double(checks.direction.fraction),
      double(checks.sample_f.fraction), double(checks.sample_pdf.fraction), checks.ill_conditioned,
      checks.too_many_ill_conditioned ? ", more than 1%" : "", checks.failures() ? "  FAIL" : "");
  auto describe = [&](const char* what, size_t q) {
    const Query& x = queries[q];
    std::printf(
        "    worst %s at wi (%.9g, %.9g, %.9g) wo (%.9g, %.9g, %.9g) uv (%.9g, %.9g) u (%.9g, %.9g) u_layer %.9g\n",
        what, double(x.wi.x), double(x.wi.y), double(x.wi.z), double(x.wo.x), double(x.wo.y), double(x.wo.z),
        double(x.uv.x), double(x.uv.y), double(x.u.x), double(x.u.y), double(x.u_layer));
  };
  if (checks.failures() && perturbation == Perturbation::None) {
    std::printf("    failures: eval %d, pdf %d, sample direction %d, sample f %d, sample pdf %d\n",
                checks.eval.failures, checks.pdf.failures, checks.direction.failures, checks.sample_f.failures,
                checks.sample_pdf.failures);
    if (checks.eval.failures) describe("eval", checks.eval.query);
    if (checks.pdf.failures) describe("pdf", checks.pdf.query);
    if (checks.direction.failures) describe("sample direction", checks.direction.query);
    if (checks.sample_pdf.failures) {
      size_t q = checks.sample_pdf.query;
      describe("sample pdf", q);
      const vec4 g = out[1][q];
      const ShadingContext ctx = query_context(queries[q].uv);
      std::printf("    GPU drew wi (%.9g, %.9g, %.9g) with pdf %.7g, CPU pdf there %.7g\n", double(g.x), double(g.y),
                  double(g.z), double(g.w), double(cpu_eval.eval_pdf(ctx, vec3(g), queries[q].wo).pdf));
    }
    if (checks.sample_f.failures) {
      size_t q = checks.sample_f.query;
      describe("sample f", q);
      const vec4 g = out[1][q], gf = out[2][q];
      const ShadingContext ctx = query_context(queries[q].uv);
      cpu::EvalPdf at = cpu_eval.eval_pdf(ctx, vec3(g), queries[q].wo);
      std::printf("    GPU drew wi (%.9g, %.9g, %.9g) with f (%.7g, %.7g, %.7g), CPU f there (%.7g, %.7g, %.7g)\n",
                  double(g.x), double(g.y), double(g.z), double(gf.x), double(gf.y), double(gf.z), double(at.f.x),
                  double(at.f.y), double(at.f.z));
    }
  }
  return checks;
}

// The failures of the check `kind` must break.
int broken_check_failures(const Checks& c, Perturbation kind) {
  switch (kind) {
    case Perturbation::None: return c.failures();
    case Perturbation::EvalScale:
    case Perturbation::EvalNan:
    case Perturbation::KernelConstant: return c.eval.failures;
    case Perturbation::SampleDirection: return c.direction.failures;
  }
  return 0;
}

int run_parity(int argc, char** argv) {
  std::vector<Run> runs;
  std::vector<std::string> files;
  std::string targets = "330,450,es300", modes = "inline,uniforms", entries = "point";
  Perturbation perturbation = Perturbation::None;
  bool usage_error = false;
  int random_count = 0;
  uint32_t random_seed = 1;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    bool has_value = i + 1 < argc;
    if (a == "--targets" && has_value) {
      targets = argv[++i];
    } else if (a == "--modes" && has_value) {
      modes = argv[++i];
    } else if (a == "--entries" && has_value) {
      entries = argv[++i];
      usage_error = usage_error || (entries != "point" && entries != "uv");
    } else if (a == "--perturb" && has_value) {
      std::string kind = argv[++i];
      perturbation = kind == "eval_scale"         ? Perturbation::EvalScale
                     : kind == "eval_nan"         ? Perturbation::EvalNan
                     : kind == "kernel_constant"  ? Perturbation::KernelConstant
                     : kind == "sample_direction" ? Perturbation::SampleDirection
                                                  : Perturbation::None;
      usage_error = usage_error || perturbation == Perturbation::None;
    } else if (a == "--random" && has_value) {
      random_count = std::atoi(argv[++i]);
      usage_error = usage_error || random_count <= 0;
    } else if (a == "--seed" && has_value) {
      random_seed = uint32_t(std::strtoul(argv[++i], nullptr, 10));
    } else if (a.rfind("--", 0) == 0) {
      usage_error = true;
    } else {
      files.push_back(a);
    }
  }
  std::stringstream ts(targets);
  for (std::string t; std::getline(ts, t, ',');) {
    glsl::Target target;
    if (!glsl::parse_target(t, target)) {
      std::fprintf(stderr, "unknown target %s\n", t.c_str());
      return 2;
    }
    std::stringstream ms(modes);
    for (std::string m; std::getline(ms, m, ',');) {
      usage_error = usage_error || (m != "inline" && m != "uniforms");
      runs.push_back({target, m == "uniforms", entries == "uv"});
    }
  }
  if (usage_error || (files.empty() && random_count == 0)) {
    std::fprintf(stderr,
                 "usage: lamina_glsl_parity [--targets 330,450,es300] [--modes inline,uniforms] [--entries point|uv] "
                 "[--perturb eval_scale|eval_nan|kernel_constant|sample_direction] [--random N [--seed S]] "
                 "[FILE...]\n");
    return 2;
  }

  std::string error;
  auto desktop = gltest::Runner::create(gltest::Api::Desktop, &error);
  if (!desktop) {
    std::fprintf(stderr, "no desktop GL context: %s\n", error.c_str());
    return 1;
  }
  auto es = gltest::Runner::create(gltest::Api::Es, &error);
  if (!es) {
    std::fprintf(stderr, "no GL ES context: %s\n", error.c_str());
    return 1;
  }
  std::printf("GL: %s\n", desktop->renderer().c_str());

  const std::vector<Query> queries = make_queries();
  std::printf("%zu queries per material (64 x 64 grid pairs with theta up to 89.5 deg, 1024 random)\n", queries.size());
  std::printf(
      "Worst errors as fractions of their tolerance (a check passes at <= 1): eval, pdf and the sample's f and pdf "
      "|gpu - cpu| / max(1e-3 |cpu|, 1e-5), the sample's at the GPU's direction; sample dir max |gpu - cpu| per "
      "component / 1e-4. NaN or inf is inf.\n");
  if (perturbation != Perturbation::None) std::printf("Perturbed modules: every run must FAIL.\n");

  std::vector<Program> programs;
  bool ok = true;
  for (const std::string& file : files) {
    CheckedFile checked = check_file(file);
    if (!checked.ok()) {
      std::printf("FAIL %s: invalid material file\n", file.c_str());
      ok = false;
      continue;
    }
    for (size_t m = 0; m < checked.graphs.size(); ++m) programs.push_back(compile(*checked.graphs[m], file));
  }
  if (random_count > 0) {
    const std::string name = "random stacks (seed " + std::to_string(random_seed) + ")";
    const std::string text = test::RandomStacks(random_seed).file(random_count);
    CheckedFile checked = check_text(text, name);
    for (const Diagnostic& d : checked.diagnostics.errors()) std::printf("generator bug: %s\n", format(d).c_str());
    if (checked.ok()) {
      for (size_t m = 0; m < checked.graphs.size(); ++m) programs.push_back(compile(*checked.graphs[m], name));
    } else {
      std::printf("FAIL %s: the checker refused a generated file:\n%s\n", name.c_str(), text.c_str());
      ok = false;
    }
  }

  int passed = 0, total = 0;
  for (const Program& program : programs) {
    cpu::Evaluator cpu_eval(program);
    std::vector<cpu::EvalPdf> ref_eval;
    std::vector<cpu::Sample> ref_sample;
    for (const Query& q : queries) {
      const ShadingContext ctx = query_context(q.uv);
      ref_eval.push_back(cpu_eval.eval_pdf(ctx, q.wi, q.wo));
      ref_sample.push_back(cpu_eval.sample(ctx, q.wo, q.u, q.u_layer));
    }
    std::printf("%s (%s, %zu lobes)\n", program.name.c_str(), program.source_file.c_str(), cpu_eval.lobe_count());
    for (const Run& run : runs) {
      gltest::Runner& runner = run.target == glsl::Target::Es300 ? *es : *desktop;
      std::optional<Checks> checks =
          run_material(runner, program, run, perturbation, queries, cpu_eval, ref_eval, ref_sample);
      ++total;
      bool good = checks && (perturbation == Perturbation::None ? checks->failures() == 0
                                                                : broken_check_failures(*checks, perturbation) > 0);
      if (perturbation != Perturbation::None && checks)
        std::printf("    perturbed: %d failing queries in the check it must break%s\n",
                    broken_check_failures(*checks, perturbation), good ? "" : "  (the comparator missed it)");
      passed += good ? 1 : 0;
      ok = ok && good;
    }
  }
  std::printf("%s: %d of %d runs (%zu materials x %zu runs) %s\n", ok ? "PASS" : "FAIL", passed, total, programs.size(),
              runs.size(), perturbation == Perturbation::None ? "passed" : "failed as they must");
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const int status = run_parity(argc, argv);
  gltest::check_leaks_now();
  return status;
}
