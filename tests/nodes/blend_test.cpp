// A stack evaluated by parts (nodes/kernels/stack.glsl, "a blend of parts"), as the GLSL back end
// evaluates a stack longer than GLSL compilers unroll, is the same material as the whole stack the
// CPU evaluator composes: the same f, the same pdf, the same samples, at textured shading points.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/kernel_stack.h"
#include "graph/load.h"
#include "nodes/kernels/kernels.h"
#include "random_stacks.h"
#include "test_support.h"

using namespace lamina;
using glm::vec2;
using glm::vec3;
namespace k = lamina::kernels;

namespace {

// A material's blend resolved at one point by the kernels' blend functions, in the C++ layout
// (LAMINA_STACK = kMaxStackEntries entries per part).
struct Parts {
  int count = 0;
  std::vector<int> counts = std::vector<int>(size_t(kMaxLobes), 0);
  std::vector<k::LaminaEntry> entries;
  std::unique_ptr<k::LaminaPoint> point = std::make_unique<k::LaminaPoint>();
};

Parts resolve_parts(const Program& program, std::span<const float> registers) {
  const StackBlend blend = split_blend(program, true);
  const size_t stride = size_t(kMaxStackEntries);
  auto inputs_of = [&](int i) {
    const StackEntry& e = program.stack[size_t(i)];
    return kernel_inputs(e, kernel_constants(e, true), registers.data());
  };
  std::vector<k::LaminaInputs> blend_inputs(stride);
  for (size_t b = 0; b < blend.entries.size(); ++b) blend_inputs[b] = inputs_of(blend.whole[b]);
  std::vector<float> shares(stride, 0.0f);
  k::lamina_blend_shares(int(blend.entries.size()), blend.entries.data(), blend_inputs.data(), shares.data());
  Parts parts;
  parts.count = int(blend.parts.size());
  parts.entries.resize(size_t(kMaxLobes) * stride);
  std::vector<k::LaminaInputs> inputs(parts.entries.size());
  std::vector<float> share(size_t(kMaxLobes), 0.0f);
  for (size_t p = 0; p < blend.parts.size(); ++p) {
    const std::vector<k::LaminaEntry> part = blend.part_entries(program, p, true);
    parts.counts[p] = int(part.size());
    share[p] = shares[size_t(blend.parts[p].blend)];
    for (size_t j = 0; j < part.size(); ++j) {
      parts.entries[p * stride + j] = part[j];
      inputs[p * stride + j] = inputs_of(blend.parts[p].first + int(j));
    }
  }
  k::lamina_blend_resolve(parts.count, parts.counts.data(), parts.entries.data(), inputs.data(), share.data(),
                          program.clamp_lower_roughness, program.model, *parts.point);
  return parts;
}

// Every example and random stacks whose blend has more than one part.
std::vector<Program> blended_programs() {
  std::vector<Program> programs;
  auto add = [&](const CheckedFile& checked, const std::string& file) {
    REQUIRE_MESSAGE(checked.ok(), file);
    for (const auto& graph : checked.graphs) {
      Program p = compile(*graph, file, test::repository_policy());
      if (split_blend(p, true).parts.size() > 1) programs.push_back(std::move(p));
    }
  };
  for (const auto& file : test::example_files()) add(check_file(file, test::repository_policy()), file.string());
  add(check_text(test::RandomStacks(20261129).file(24), "random.json"), "random.json");
  return programs;
}

bool close(vec3 a, vec3 b) {
  const vec3 d = glm::abs(a - b);
  const vec3 scale = glm::max(glm::abs(a), glm::abs(b));
  return d.x <= 1.0e-4f * scale.x + 1.0e-7f && d.y <= 1.0e-4f * scale.y + 1.0e-7f && d.z <= 1.0e-4f * scale.z + 1.0e-7f;
}

}  // namespace

TEST_CASE("a stack evaluated by parts gives the whole stack's f, pdf and samples") {
  const std::vector<Program> programs = blended_programs();
  REQUIRE(!programs.empty());
  std::vector<vec3> directions;
  for (float theta : {0.05f, 0.6f, 1.1f, 1.45f})
    for (float phi : {0.3f, 2.2f, 4.4f})
      directions.push_back(vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
  size_t samples_compared = 0;
  for (const Program& program : programs) {
    CAPTURE(program.name);
    const cpu::Evaluator evaluator(program);
    for (vec2 uv : {vec2(0.13f, 0.71f), vec2(0.52f, 0.38f), vec2(0.91f, 0.07f)}) {
      for (float footprint : {0.0f, 0.05f}) {
        ShadingContext ctx;
        ctx.uv = uv;
        ctx.position = vec3(uv, 0.25f);
        ctx.footprint = footprint;
        const cpu::ShadingPoint point = evaluator.bind(ctx);
        const Parts parts = resolve_parts(program, point.registers());
        auto selection = std::make_unique<k::LaminaPartsSelection>();
        for (vec3 wo : directions) {
          k::lamina_blend_select(parts.count, parts.counts.data(), parts.entries.data(), *parts.point, wo, *selection);
          for (vec3 wi : directions) {
            const vec3 f = k::lamina_blend_eval(parts.count, parts.counts.data(), parts.entries.data(), *parts.point,
                                                program.model, wi, wo);
            CHECK(close(f, point.eval(wi, wo)));
            const float pdf = k::lamina_blend_pdf(parts.count, parts.counts.data(), parts.entries.data(), *parts.point,
                                                  *selection, wi, wo);
            CHECK(close(vec3(pdf), vec3(point.pdf(wi, wo))));
          }
          for (float u_lobe : {0.07f, 0.33f, 0.61f, 0.94f}) {
            const vec2 u(0.37f, 0.82f);
            const int chosen = k::lamina_blend_choose(parts.count, parts.counts.data(), *selection, u_lobe);
            const vec3 wi =
                k::lamina_blend_sample(parts.counts.data(), parts.entries.data(), *parts.point, *selection, chosen, u);
            const cpu::Sample whole = point.sample(wo, u, u_lobe);
            CHECK(close(wi, whole.wi));
            ++samples_compared;
          }
        }
      }
    }
  }
  MESSAGE(programs.size() << " materials with a blend of several parts, " << samples_compared << " samples compared");
}
