// select: one of N stacks per shading point. Where the pixel sees one cell, the select is exactly the
// stack it names, and the stacks it does not show cost nothing: their entries are skipped by every
// walk (share 0) and their lobes are never sampled. Consecutive repeats of a stack compile once.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "graph/cpu/evaluator.h"
#include "graph/cpu_test_support.h"
#include "nodes/kernels/kernels.h"
#include "test_support.h"

using namespace lamina;
using glm::vec2;
using glm::vec3;

namespace {

// Four different stacks: a varnish over a Lambertian base, a tinted varnish over copper, a bare
// rough silver, two layers over a Lambertian base.
const char* kStackNodes = R"(
  {"id": "varnish", "type": "interface/dielectric", "ior": 1.56, "roughness_deg": 2.0},
  {"id": "rough", "type": "interface/dielectric", "ior": 1.4, "roughness_deg": 14.0},
  {"id": "clear", "type": "medium/clear"},
  {"id": "tint", "type": "medium/absorbing", "thickness": 0.5, "absorption": [0.1, 0.4, 0.8]},
  {"id": "white", "type": "substrate/lambert", "albedo": [0.8, 0.7, 0.6]},
  {"id": "copper", "type": "substrate/conductor", "metal": "copper", "roughness_deg": 3.0},
  {"id": "s0", "type": "layer", "interface": "@varnish", "medium": "@clear", "base": "@white"},
  {"id": "s1", "type": "layer", "interface": "@varnish", "medium": "@tint", "base": "@copper"},
  {"id": "s2", "type": "substrate/conductor", "metal": "silver", "roughness_deg": 9.0},
  {"id": "inner", "type": "layer", "interface": "@rough", "medium": "@tint", "base": "@white"},
  {"id": "s3", "type": "layer", "interface": "@varnish", "medium": "@clear", "base": "@inner"})";

std::string material(const std::string& surface, const std::string& extra_nodes, const char* model) {
  return std::string(R"({"format": 1, "materials": [{"name": "m", "model": ")") + model + R"(", "surface": ")" +
         surface + R"(", "nodes": [)" + kStackNodes + extra_nodes + "]}]}";
}

std::string select_node(const std::vector<std::string>& stacks, double index, double coverage) {
  std::string node = R"(, {"id": "sel", "type": "select", "index": )" + std::to_string(index) + R"(, "coverage": )" +
                     std::to_string(coverage);
  for (size_t k = 0; k < stacks.size(); ++k) node += R"(, "stack_)" + std::to_string(k) + R"(": "@)" + stacks[k] + "\"";
  return node + "}";
}

const char* const kModels[] = {"energy_conserving", "weidlich_wilkie"};

// Directions from the pole to grazing on both sides.
std::vector<std::pair<vec3, vec3>> direction_pairs() {
  std::vector<std::pair<vec3, vec3>> pairs;
  for (float ti : {0.0f, 0.4f, 0.9f, 1.3f})
    for (float to : {0.1f, 0.7f, 1.2f, 1.5f})
      pairs.push_back({vec3(std::sin(ti), 0.0f, std::cos(ti)),
                       glm::normalize(vec3(-std::sin(to), 0.3f * std::sin(to), std::cos(to)))});
  return pairs;
}

bool close(vec3 a, vec3 b, float tolerance) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(a[c] - b[c]) <= tolerance * std::max(std::abs(b[c]), 1e-6f))) return false;
  return true;
}

}  // namespace

TEST_CASE("a select over one cell is exactly the stack it names: eval, pdf, samples and albedo, in both models") {
  const std::vector<std::string> stacks = {"s0", "s1", "s2", "s3"};
  for (const char* model : kModels) {
    for (size_t k = 0; k < stacks.size(); ++k) {
      CAPTURE(model);
      CAPTURE(k);
      const cpu::Evaluator selected =
          test::evaluator_from_text(material("@sel", select_node(stacks, double(k) + 0.5, 0.0), model));
      const cpu::Evaluator alone = test::evaluator_from_text(material("@" + stacks[k], "", model));
      const cpu::ShadingPoint a = selected.bind(ShadingContext{}), b = alone.bind(ShadingContext{});
      for (const auto& pair : direction_pairs()) {
        const vec3 wi = pair.first, wo = pair.second;  // clang 14 cannot capture a structured binding
        CAPTURE(wi);
        CAPTURE(wo);
        CHECK(close(a.eval(wi, wo), b.eval(wi, wo), 1e-6f));
        CHECK(a.pdf(wi, wo) == doctest::Approx(b.pdf(wi, wo)).epsilon(1e-6));
        for (float u : {0.1f, 0.5f, 0.93f}) {
          const cpu::Sample sa = a.sample(wo, vec2(u, 1.0f - u), u), sb = b.sample(wo, vec2(u, 1.0f - u), u);
          CHECK(close(sa.wi, sb.wi, 1e-5f));
          CHECK(sa.pdf == doctest::Approx(sb.pdf).epsilon(1e-5));
        }
      }
      CHECK(close(a.albedo(vec3(0.3f, 0.0f, 0.95f), 64), b.albedo(vec3(0.3f, 0.0f, 0.95f), 64), 1e-5f));
    }
  }
}

TEST_CASE("the stacks a select does not show are skipped: their entries have share 0 and their lobes no weight") {
  const std::vector<std::string> stacks = {"s0", "s1", "s2", "s3"};
  for (const char* model : kModels) {
    CAPTURE(model);
    const cpu::Evaluator e = test::evaluator_from_text(material("@sel", select_node(stacks, 2.5, 0.0), model));
    const cpu::ShadingPoint p = e.bind(ShadingContext{});
    const cpu::ShadingPoint::Stack s = p.stack();
    // Which entries belong to the shown stack (s2, a bare conductor): those whose chain of parents
    // reaches the select through its stack s2 side.
    const Program& program = e.program();
    int shown = 0;
    for (int i = 0; i < s.count; ++i) {
      const StackEntry& entry = program.stack[size_t(i)];
      CAPTURE(i);
      CAPTURE(entry.node);
      if (entry.node == "sel") {
        CHECK(s.params[i].share > 0.0f);  // the chain down to the shown stack
      } else {
        const bool is_shown = entry.node == "s2";
        shown += is_shown ? 1 : 0;
        CHECK(s.params[i].share == (is_shown ? 1.0f : 0.0f));
      }
    }
    CHECK(shown == 1);
    // Only the shown stack's lobe is ever chosen: the others get no floor share.
    const std::vector<float> weights = p.lobe_weights(vec3(0.2f, 0.1f, 0.97f));
    int nonzero = 0;
    for (float w : weights) nonzero += w > 0.0f ? 1 : 0;
    CHECK(nonzero == 1);
  }
}

TEST_CASE("consecutive repeats of a stack in a select compile once and keep the share of every place they fill") {
  // A sparse glitter map: three places of s0 (the transparent cells) and one of s2 (the glitter).
  for (const char* model : kModels) {
    CAPTURE(model);
    const cpu::Evaluator alone0 = test::evaluator_from_text(material("@s0", "", model));
    const cpu::Evaluator alone2 = test::evaluator_from_text(material("@s2", "", model));
    for (double coverage : {0.0, 0.4, 1.0}) {
      for (double index : {0.5, 2.5, 3.5}) {
        CAPTURE(coverage);
        CAPTURE(index);
        const cpu::Evaluator repeated =
            test::evaluator_from_text(material("@sel", select_node({"s0", "s0", "s0", "s2"}, index, coverage), model));
        // One chain step and each stack once: s0 is a layer over a base (2 entries), s2 one.
        CHECK(repeated.program().stack.size() == alone0.program().stack.size() + alone2.program().stack.size() + 1);
        // The glitter's share: (1 - c) where the cell is glitter, plus c / 4.
        const double glitter = (index >= 3.0 ? 1.0 - coverage : 0.0) + coverage / 4.0;
        const cpu::ShadingPoint p = repeated.bind(ShadingContext{});
        const cpu::ShadingPoint p0 = alone0.bind(ShadingContext{}), p2 = alone2.bind(ShadingContext{});
        for (const auto& pair : direction_pairs()) {
          const vec3 wi = pair.first, wo = pair.second;  // clang 14 cannot capture a structured binding
          CAPTURE(wi);
          CAPTURE(wo);
          const vec3 expected = float(1.0 - glitter) * p0.eval(wi, wo) + float(glitter) * p2.eval(wi, wo);
          CHECK(close(p.eval(wi, wo), expected, 1e-5f));
        }
      }
    }
  }
}
