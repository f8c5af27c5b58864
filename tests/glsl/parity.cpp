// GLSL/CPU parity: runs the generated GLSL of every material given on the command line on a
// real OpenGL implementation (Mesa llvmpipe through headless EGL) over a grid of (wi, wo, uv)
// with grazing directions, and compares eval, pdf and sample with the CPU evaluator.
//
//   lamina_glsl_parity [--targets 330,450,es300] [--modes inline,uniforms] FILE...
//
// Tolerances (issue 4): eval and pdf within 1e-3 relative with an absolute floor of 1e-5, i.e.
// |gpu - cpu| <= max(1e-3 |cpu|, 1e-5); sampled directions within 1e-4 per component for the same
// random numbers. Queries whose u_layer lies within 1e-5 of a boundary between two lobes'
// selection intervals are not compared for sampling (float rounding may pick either lobe; the
// count is printed). Prints the worst errors per material; exits 1 on any failure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "glsl/gl_runner.h"
#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu/image.h"
#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/load.h"

using glm::vec2;
using glm::vec3;
using glm::vec4;
using namespace lamina;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kRelTol = 1e-3f, kAbsFloor = 1e-5f, kDirTol = 1e-4f, kLobeMargin = 1e-5f;

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

const char* kHarness = R"(
// ---- parity harness: one query per fragment
uniform sampler2D lamina_q_wi;
uniform sampler2D lamina_q_wo;
uniform sampler2D lamina_q_u;
layout(location = 0) out vec4 o_eval;
layout(location = 1) out vec4 o_sample;
layout(location = 2) out vec4 o_sample_f;
void main() {
  ivec2 at = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(lamina_q_wi, at, 0);
  vec4 b = texelFetch(lamina_q_wo, at, 0);
  vec4 c = texelFetch(lamina_q_u, at, 0);
  o_eval = vec4(NAME_eval(a.xyz, b.xyz, c.xy), NAME_pdf(a.xyz, b.xyz, c.xy));
  vec3 wi;
  float pdf;
  vec3 f = NAME_sample(b.xyz, c.zw, a.w, c.xy, wi, pdf);
  o_sample = vec4(wi, pdf);
  o_sample_f = vec4(f, 0.0f);
}
)";

std::string harness(const std::string& prefix) { return glsl::replace_all(kHarness, "NAME", prefix); }

// |gpu - cpu| in units of the tolerance max(1e-3 |cpu|, 1e-5): <= 1 passes.
float scaled_error(float gpu, float cpu) {
  if (!std::isfinite(gpu)) return INFINITY;
  return std::abs(gpu - cpu) / std::max(kRelTol * std::abs(cpu), kAbsFloor);
}
// The relative error, with the floor, as reported: |gpu - cpu| / max(|cpu|, 1e-2).
float reported_error(float gpu, float cpu) {
  if (!std::isfinite(gpu)) return INFINITY;
  return std::abs(gpu - cpu) / std::max(std::abs(cpu), kAbsFloor / kRelTol);
}

struct Worst {
  float scaled = 0.0f, reported = 0.0f;
  size_t query = 0;
  int failures = 0;
  void add(float gpu, float cpu, size_t q, float tol_scale = 1.0f) {
    float s = scaled_error(gpu, cpu) / tol_scale;
    if (s > 1.0f) ++failures;
    if (s > scaled || !std::isfinite(s)) {
      scaled = s;
      reported = reported_error(gpu, cpu);
      query = q;
    }
  }
};

struct Run {
  glsl::Target target;
  bool uniforms;
};

bool run_material(gltest::Runner& runner, const Program& program, const Run& run, const std::vector<Query>& queries,
                  const cpu::Evaluator& cpu_eval, const std::vector<cpu::EvalPdf>& ref_eval,
                  const std::vector<cpu::Sample>& ref_sample, const std::vector<bool>& skip_sample) {
  glsl::Options options;
  options.target = run.target;
  options.uniforms = run.uniforms;
  glsl::Module module = glsl::generate(std::span<const Program>(&program, 1), options);
  const glsl::MaterialInterface& mi = module.materials.front();

  const int width = 64, height = int((queries.size() + 63) / 64);
  gltest::Pass pass;
  pass.fragment_source = module.source + harness(mi.prefix);
  pass.width = width;
  pass.height = height;
  pass.outputs = 3;
  gltest::Texture twi{"lamina_q_wi", width, height, {}}, two{"lamina_q_wo", width, height, {}},
      tu{"lamina_q_u", width, height, {}};
  for (size_t i = 0; i < size_t(width * height); ++i) {
    const Query& q = queries[std::min(i, queries.size() - 1)];
    twi.texels.push_back(vec4(q.wi, q.u_layer));
    two.texels.push_back(vec4(q.wo, 0.0f));
    tu.texels.push_back(vec4(q.uv, q.u));
  }
  pass.textures = {twi, two, tu};
  for (const glsl::SamplerBinding& b : mi.samplers)
    for (const TextureOp& op : program.ops)
      if (const auto* img = std::get_if<ImageOp>(&op); img && img->node == b.node)
        pass.textures.push_back({b.name, img->image->width, img->image->height, img->image->texels});
  if (run.uniforms) {
    pass.uniform_block_name = mi.block;
    pass.uniform_block_data = glsl::pack_uniforms(mi);
  }
  std::vector<std::vector<vec4>> out;
  std::string error;
  if (!runner.run(pass, &out, &error)) {
    std::printf("  FAIL %s %s: %s\n", glsl::target_name(run.target), run.uniforms ? "uniforms" : "inline",
                error.c_str());
    return false;
  }

  Worst eval, pdf, sample_pdf, sample_f;
  float worst_dir = 0.0f;
  size_t worst_dir_query = 0;
  int dir_failures = 0, skipped = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    const vec4 e = out[0][i], s = out[1][i], sf = out[2][i];
    for (int c = 0; c < 3; ++c) eval.add(e[c], ref_eval[i].f[c], i);
    pdf.add(e.w, ref_eval[i].pdf, i);
    if (skip_sample[i]) {
      ++skipped;
      continue;
    }
    const cpu::Sample& r = ref_sample[i];
    float d = std::max({std::abs(s.x - r.wi.x), std::abs(s.y - r.wi.y), std::abs(s.z - r.wi.z)});
    if (!(d <= kDirTol)) ++dir_failures;
    if (!(d <= worst_dir)) {
      worst_dir = std::isfinite(d) ? d : INFINITY;
      worst_dir_query = i;
    }
    // The sample's f and pdf must be eval and pdf at the direction the GPU drew: compare with the
    // CPU at that direction (the direction itself is checked above, against the CPU's draw).
    if (r.pdf > 0.0f || s.w > 0.0f) {
      ShadingContext ctx;
      ctx.uv = queries[i].uv;
      vec3 wi = vec3(s);
      cpu::EvalPdf at = s.w > 0.0f ? cpu_eval.eval_pdf(ctx, wi, queries[i].wo) : cpu::EvalPdf{};
      sample_pdf.add(s.w, at.pdf, i);
      for (int c = 0; c < 3; ++c) sample_f.add(sf[c], at.f[c], i);
    }
    // A sample the CPU could not draw must not be drawn on the GPU either, and vice versa.
    if ((r.pdf > 0.0f) != (s.w > 0.0f)) ++dir_failures;
  }
  int failures = eval.failures + pdf.failures + dir_failures + sample_pdf.failures + sample_f.failures;
  std::printf(
      "  %-5s %-8s eval %.2e  pdf %.2e  sample dir %.2e  sample f %.2e  sample pdf %.2e  (%d lobe-boundary "
      "skips)%s\n",
      glsl::target_name(run.target), run.uniforms ? "uniforms" : "inline", double(eval.reported), double(pdf.reported),
      double(worst_dir), double(sample_f.reported), double(sample_pdf.reported), skipped, failures ? "  FAIL" : "");
  auto describe = [&](const char* what, size_t q) {
    const Query& x = queries[q];
    std::printf(
        "    worst %s at wi (%.6g, %.6g, %.6g) wo (%.6g, %.6g, %.6g) uv (%.4g, %.4g) u (%.6g, %.6g) u_layer %.6g\n",
        what, double(x.wi.x), double(x.wi.y), double(x.wi.z), double(x.wo.x), double(x.wo.y), double(x.wo.z),
        double(x.uv.x), double(x.uv.y), double(x.u.x), double(x.u.y), double(x.u_layer));
  };
  if (failures) {
    std::printf("    failures: eval %d, pdf %d, sample direction %d, sample f %d, sample pdf %d\n", eval.failures,
                pdf.failures, dir_failures, sample_f.failures, sample_pdf.failures);
    if (eval.failures) describe("eval", eval.query);
    if (pdf.failures) describe("pdf", pdf.query);
    if (dir_failures) describe("sample direction", worst_dir_query);
    if (sample_f.failures) {
      describe("sample f", sample_f.query);
      const vec4 g = out[1][sample_f.query], gf = out[2][sample_f.query];
      ShadingContext ctx;
      ctx.uv = queries[sample_f.query].uv;
      cpu::EvalPdf at = cpu_eval.eval_pdf(ctx, vec3(g), queries[sample_f.query].wo);
      std::printf("    GPU drew wi (%.9g, %.9g, %.9g) with f (%.7g, %.7g, %.7g), CPU f there (%.7g, %.7g, %.7g)\n",
                  double(g.x), double(g.y), double(g.z), double(gf.x), double(gf.y), double(gf.z), double(at.f.x),
                  double(at.f.y), double(at.f.z));
    }
  }
  return failures == 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Run> runs;
  std::vector<std::string> files;
  std::string targets = "330,450,es300", modes = "inline,uniforms";
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--targets" && i + 1 < argc)
      targets = argv[++i];
    else if (a == "--modes" && i + 1 < argc)
      modes = argv[++i];
    else
      files.push_back(a);
  }
  std::stringstream ts(targets);
  for (std::string t; std::getline(ts, t, ',');) {
    glsl::Target target;
    if (!glsl::parse_target(t, target)) {
      std::fprintf(stderr, "unknown target %s\n", t.c_str());
      return 2;
    }
    std::stringstream ms(modes);
    for (std::string m; std::getline(ms, m, ',');) runs.push_back({target, m == "uniforms"});
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: lamina_glsl_parity [--targets 330,450,es300] [--modes inline,uniforms] FILE...\n");
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
  bool ok = true;
  int materials = 0;
  for (const std::string& file : files) {
    CheckedFile checked = check_file(file);
    if (!checked.ok()) {
      std::printf("FAIL %s: invalid material file\n", file.c_str());
      ok = false;
      continue;
    }
    for (size_t m = 0; m < checked.graphs.size(); ++m) {
      Program program = compile(*checked.graphs[m], file);
      cpu::Evaluator cpu_eval(program);
      std::vector<cpu::EvalPdf> ref_eval;
      std::vector<cpu::Sample> ref_sample;
      std::vector<bool> skip;
      for (const Query& q : queries) {
        ShadingContext ctx;
        ctx.uv = q.uv;
        ref_eval.push_back(cpu_eval.eval_pdf(ctx, q.wi, q.wo));
        ref_sample.push_back(cpu_eval.sample(ctx, q.wo, q.u, q.u_layer));
        std::vector<float> w = cpu_eval.lobe_weights(ctx, q.wo);
        float cumulative = 0.0f;
        bool near = false;
        for (float x : w) {
          cumulative += x;
          near = near || std::abs(q.u_layer - cumulative) < kLobeMargin;
        }
        skip.push_back(near);
      }
      std::printf("%s (%s, %zu lobes): worst relative errors (floor 1e-5), direction max abs\n", program.name.c_str(),
                  file.c_str(), cpu_eval.lobe_count());
      ++materials;
      for (const Run& run : runs) {
        gltest::Runner& runner = run.target == glsl::Target::Es300 ? *es : *desktop;
        ok = run_material(runner, program, run, queries, cpu_eval, ref_eval, ref_sample, skip) && ok;
      }
    }
  }
  std::printf("%s: %d materials x %zu runs\n", ok ? "PASS" : "FAIL", materials, runs.size());
  return ok ? 0 : 1;
}
