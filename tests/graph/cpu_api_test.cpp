// The library face of the CPU evaluator: the local frame from a world normal and tangent, the
// batch forms (bit for bit the single queries, span lengths checked), the partial queries a baker
// uses (registers, entry covers), use from many threads at once, the limits of a program, and what
// compile hands the evaluator (the fresnel parameter).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cpu_test_support.h"
#include "graph/cpu/frame.h"
#include "graph/limits.h"
#include "graph/lobes.h"
#include "nodes/kernels/kernels.h"
#include "test_support.h"

using namespace lamina;
using glm::vec2;
using glm::vec3;

namespace {

bool near(vec3 a, vec3 b, float tolerance) { return glm::all(glm::lessThanEqual(glm::abs(a - b), vec3(tolerance))); }

// Random unit vectors and uvs from a fixed seed (uv over [-0.5, 1.5], so textures wrap).
struct Draws {
  std::mt19937_64 rng{0x5eed00a1};
  float uniform() { return float(test::uniform(rng)); }
  vec3 direction(float z_min) {
    float z = z_min + (1.0f - z_min) * uniform();
    float phi = 6.2831853f * uniform();
    float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return vec3(s * std::cos(phi), s * std::sin(phi), z);
  }
  vec2 uv() { return vec2(2.0f * uniform() - 0.5f, 2.0f * uniform() - 0.5f); }
};

// A few materials that between them reach every path of the evaluator: a plain stack, a checker
// mix, an image through a remap, and every node type, distribution and Fresnel term.
std::vector<cpu::Evaluator> materials() {
  std::vector<cpu::Evaluator> list;
  for (const char* file : {"examples/materials/car_paint.json", "examples/materials/checker_tiles.json",
                           "examples/materials/patina_map_copper.json", "tests/data/glsl/every_node.json",
                           "tests/data/physics/three_interfaces.json"})
    list.push_back(test::load_evaluator(test::source_dir() / file));
  return list;
}

struct Queries {
  std::vector<vec3> wi, wo;
  std::vector<vec2> uv, u;
  std::vector<float> u_lobe;
  std::vector<ShadingContext> ctx;  // at_uv(uv[i])
};

ShadingContext at_uv(vec2 uv) {
  ShadingContext ctx;
  ctx.uv = uv;
  return ctx;
}

// Directions above and below the horizon; uvs in runs of equal values and changing every query,
// so that the batch forms' reuse of a resolved shading point is exercised both ways.
Queries make_queries(size_t count) {
  Draws d;
  Queries q;
  vec2 run_uv = d.uv();
  for (size_t i = 0; i < count; ++i) {
    q.wi.push_back(d.direction(-0.2f));
    q.wo.push_back(d.direction(-0.1f));
    if (i % 7 == 0) run_uv = d.uv();
    q.uv.push_back(i < count / 2 ? run_uv : d.uv());
    q.ctx.push_back(at_uv(q.uv.back()));
    q.u.push_back(vec2(d.uniform(), d.uniform()));
    q.u_lobe.push_back(d.uniform());
  }
  return q;
}

bool same(const cpu::Sample& a, const cpu::Sample& b) {
  return a.wi == b.wi && a.f == b.f && a.pdf == b.pdf && a.lobe == b.lobe;
}

}  // namespace

// --- Frame ---------------------------------------------------------------------------------------

TEST_CASE("Frame::from_normal_tangent builds the right-handed shading frame of a world normal and tangent") {
  // n = y, t = x: the bitangent is n x t = (0, 1, 0) x (1, 0, 0) = (0, 0, -1), and a direction
  // (0, 1, 1) / sqrt 2 has local coordinates (t.w, b.w, n.w) = (0, -1, 1) / sqrt 2.
  Frame f = Frame::from_normal_tangent({0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
  CHECK(f.tangent == vec3(1.0f, 0.0f, 0.0f));
  CHECK(f.bitangent == vec3(0.0f, 0.0f, -1.0f));
  CHECK(f.normal == vec3(0.0f, 1.0f, 0.0f));
  const float r = 1.0f / std::sqrt(2.0f);
  CHECK(near(f.to_local(vec3(0.0f, r, r)), vec3(0.0f, -r, r), 1e-7f));
  CHECK(near(f.to_local(f.normal), vec3(0.0f, 0.0f, 1.0f), 0.0f));

  // A tangent that is not perpendicular is made so (Gram-Schmidt), and neither vector need be unit.
  Frame g = Frame::from_normal_tangent({0.0f, 0.0f, 2.0f}, {3.0f, 0.0f, 3.0f});
  CHECK(near(g.tangent, vec3(1.0f, 0.0f, 0.0f), 1e-7f));
  CHECK(near(g.bitangent, vec3(0.0f, 1.0f, 0.0f), 1e-7f));
  CHECK(near(g.normal, vec3(0.0f, 0.0f, 1.0f), 1e-7f));

  // Random normals and tangents: orthonormal, right-handed, n kept, t in the plane of n and the
  // given tangent, and to_world undoes to_local.
  Draws d;
  for (int i = 0; i < 2000; ++i) {
    vec3 n = d.direction(-1.0f) * (0.5f + d.uniform());
    vec3 t = d.direction(-1.0f);
    Frame h = Frame::from_normal_tangent(n, t);
    CAPTURE(i);
    CHECK(std::abs(glm::length(h.tangent) - 1.0f) <= 1e-6f);
    CHECK(std::abs(glm::length(h.bitangent) - 1.0f) <= 1e-6f);
    CHECK(near(h.normal, glm::normalize(n), 1e-6f));
    CHECK(std::abs(glm::dot(h.tangent, h.normal)) <= 1e-6f);
    CHECK(std::abs(glm::dot(h.bitangent, h.normal)) <= 1e-6f);
    CHECK(std::abs(glm::dot(h.tangent, h.bitangent)) <= 1e-6f);
    CHECK(near(glm::cross(h.tangent, h.bitangent), h.normal, 1e-6f));
    // The tangent leans toward the one given: t_local = (|t_perp|, 0, t.n) / |t|.
    vec3 local_t = h.to_local(t);
    CHECK(local_t.x > 0.0f);
    CHECK(std::abs(local_t.y) <= 1e-6f);
    vec3 w = d.direction(-1.0f);
    CHECK(near(h.to_world(h.to_local(w)), w, 1e-6f));
    CHECK(std::abs(glm::dot(h.to_local(w), h.to_local(t)) - glm::dot(w, t)) <= 1e-6f);
  }
}

TEST_CASE("Frame::from_normal_tangent picks a tangent when the one given is missing or along the normal") {
  for (vec3 n : {vec3(0.0f, 0.0f, 1.0f), vec3(0.0f, 0.0f, -1.0f), glm::normalize(vec3(1.0f, -2.0f, 0.5f)),
                 glm::normalize(vec3(-0.3f, 0.1f, -2.0f))}) {
    for (vec3 t : {vec3(0.0f), n, -3.0f * n}) {
      CAPTURE(n);
      CAPTURE(t);
      Frame f = Frame::from_normal_tangent(n, t);
      CHECK(std::isfinite(f.tangent.x + f.tangent.y + f.tangent.z));
      CHECK(std::abs(glm::length(f.tangent) - 1.0f) <= 1e-6f);
      CHECK(std::abs(glm::dot(f.tangent, f.normal)) <= 1e-6f);
      CHECK(near(glm::cross(f.tangent, f.bitangent), f.normal, 1e-6f));
      CHECK(near(f.normal, n, 1e-6f));
    }
  }
}

TEST_CASE("a material evaluated through the frame of a rotated surface gives the value of the local frame") {
  cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples/materials/car_paint.json");
  Draws d;
  for (int i = 0; i < 200; ++i) {
    vec3 wi = d.direction(0.05f), wo = d.direction(0.05f);
    // A surface whose normal and tangent are a random rotation of z and x.
    vec3 n = d.direction(-1.0f);
    Frame f = Frame::from_normal_tangent(n, d.direction(-1.0f));
    vec3 world_i = f.to_world(wi), world_o = f.to_world(wo);
    vec3 direct = e.eval(ShadingContext{}, wi, wo);
    vec3 through = e.eval(ShadingContext{}, f.to_local(world_i), f.to_local(world_o));
    CAPTURE(i);
    CHECK(near(through, direct, 2e-4f * std::max({direct.x, direct.y, direct.z, 1e-3f})));
  }
}

// --- batches -------------------------------------------------------------------------------------

TEST_CASE("the batch forms give bit for bit the single-query results, textured materials included") {
  const Queries q = make_queries(3000);
  const size_t n = q.wi.size();
  for (const cpu::Evaluator& e : materials()) {
    CAPTURE(e.program().name);
    std::vector<vec3> f(n);
    std::vector<float> pdf(n);
    std::vector<cpu::EvalPdf> both(n);
    std::vector<cpu::Sample> samples(n);
    e.eval(q.ctx, q.wi, q.wo, f);
    e.pdf(q.ctx, q.wi, q.wo, pdf);
    e.eval_pdf(q.ctx, q.wi, q.wo, both);
    e.sample(q.ctx, q.wo, q.u, q.u_lobe, samples);
    long differs = 0;
    for (size_t i = 0; i < n; ++i) {
      ShadingContext ctx = at_uv(q.uv[i]);
      vec3 f1 = e.eval(ctx, q.wi[i], q.wo[i]);
      float p1 = e.pdf(ctx, q.wi[i], q.wo[i]);
      cpu::EvalPdf b1 = e.eval_pdf(ctx, q.wi[i], q.wo[i]);
      if (f[i] != f1 || pdf[i] != p1 || both[i].f != f1 || both[i].pdf != p1 || b1.f != f1 || b1.pdf != p1 ||
          !same(samples[i], e.sample(ctx, q.wo[i], q.u[i], q.u_lobe[i])))
        ++differs;
    }
    CHECK(differs == 0);
    // Without contexts every query is at the default context.
    std::vector<vec3> f0(n);
    e.eval({}, q.wi, q.wo, f0);
    long differs0 = 0;
    for (size_t i = 0; i < n; ++i) differs0 += f0[i] != e.eval(ShadingContext{}, q.wi[i], q.wo[i]) ? 1 : 0;
    CHECK(differs0 == 0);
  }
}

TEST_CASE("texture_registers and entry_covers give what a bound point holds, for every example") {
  Draws d;
  for (const auto& file : test::example_files()) {
    const cpu::Evaluator e = test::load_evaluator(file);
    CAPTURE(e.program().name);
    long differs = 0;
    for (int i = 0; i < 64; ++i) {
      ShadingContext ctx = at_uv(d.uv());
      ctx.footprint = i % 2 == 0 ? 0.0f : 1.0e-3f * d.uniform();  // filtered textures too
      const cpu::ShadingPoint point = e.bind(ctx);
      const std::span<const float> bound = point.registers();
      const std::vector<float> registers = e.texture_registers(ctx);
      differs += std::vector<float>(bound.begin(), bound.end()) == registers ? 0 : 1;
      const cpu::ShadingPoint::Stack stack = point.stack();
      const std::vector<cpu::Evaluator::EntryCover> covers = e.entry_covers(ctx);
      REQUIRE(int(covers.size()) == stack.count);
      for (int j = 0; j < stack.count; ++j)
        differs +=
            covers[size_t(j)].share == stack.params[j].share && covers[size_t(j)].normal == stack.params[j].normal ? 0
                                                                                                                   : 1;
    }
    CHECK(differs == 0);
  }
}

TEST_CASE("a point's queries skip the stacks no mix shows there and give bit for bit the whole stack's results") {
  namespace k = lamina::kernels;
  Draws d;
  long skipping = 0;  // points whose queries walk fewer entries than the stack has
  for (const auto& file : test::example_files()) {
    const cpu::Evaluator e = test::load_evaluator(file);
    CAPTURE(e.program().name);
    const std::vector<Lobe> lobes = collect_lobes(e.program());
    const int model = e.program().model;
    long differs = 0;
    for (int i = 0; i < 32; ++i) {
      ShadingContext ctx = at_uv(d.uv());
      ctx.footprint = i % 2 == 0 ? 0.0f : 1.0e-3f * d.uniform();
      const cpu::ShadingPoint point = e.bind(ctx);
      const cpu::ShadingPoint::Stack whole = point.stack();
      skipping += point.walked_entries() < whole.count ? 1 : 0;
      for (int j = 0; j < 16; ++j) {
        const vec3 wi = d.direction(-0.1f), wo = d.direction(-0.1f);
        const vec2 u(d.uniform(), d.uniform());
        const float u_lobe = d.uniform();
        const vec3 f = model == k::LAMINA_MODEL_ENERGY_CONSERVING
                           ? k::lamina_stack_eval_conserving(whole.count, whole.entries, whole.params, wi, wo)
                           : k::lamina_stack_eval(whole.count, whole.entries, whole.params, wi, wo);
        std::array<float, kMaxStackEntries> weight{};
        std::array<vec3, kMaxStackEntries> v{};
        std::array<bool, kMaxStackEntries> valid{};
        k::lamina_stack_select(whole.count, whole.entries, whole.params, wo, weight.data(), v.data(), valid.data());
        const float pdf = wi.z > 0.0f && wo.z > 0.0f
                              ? k::lamina_stack_pdf(whole.count, whole.entries, whole.params, weight.data(), v.data(),
                                                    valid.data(), wi, wo)
                              : 0.0f;
        differs += point.eval(wi, wo) == f && point.pdf(wi, wo) == pdf ? 0 : 1;
        if (wo.z <= 0.0f) continue;
        const std::vector<float> lobe_weights = point.lobe_weights(wo);
        for (size_t l = 0; l < lobes.size(); ++l) differs += lobe_weights[l] == weight[size_t(lobes[l].entry)] ? 0 : 1;
        const int chosen = k::lamina_stack_choose(whole.count, weight.data(), u_lobe);
        const vec3 drawn = k::lamina_stack_sample(whole.count, whole.entries, whole.params, v.data(), chosen, u);
        const cpu::Sample sample = point.sample(wo, u, u_lobe);
        if (drawn.z > 0.0f)
          differs += sample.wi == drawn && sample.lobe >= 0 && lobes[size_t(sample.lobe)].entry == chosen ? 0 : 1;
        else
          differs += sample.pdf == 0.0f ? 0 : 1;
      }
    }
    CHECK(differs == 0);
  }
  // The bundled examples include selects over cells (the aventurescent stones).
  CHECK(skipping > 0);
}

TEST_CASE("the batch forms reject spans of different lengths and accept empty contexts and empty batches") {
  cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples/materials/car_paint.json");
  std::vector<vec3> three(3, vec3(0.0f, 0.0f, 1.0f)), four(4, vec3(0.0f, 0.0f, 1.0f));
  std::vector<vec2> u2(2), u3(3);
  std::vector<ShadingContext> ctx2(2);
  std::vector<float> lobe3(3), pdf3(3);
  std::vector<cpu::EvalPdf> both3(3);
  std::vector<cpu::Sample> samples3(3);
  auto message = [](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("(no exception)");
  };
  std::string m = message([&] { e.eval({}, three, four, three); });
  CHECK(m.find("Evaluator::eval: spans of different lengths: f 3, wi 3, wo 4, ctx 0") != std::string::npos);
  m = message([&] { e.pdf(ctx2, three, three, pdf3); });
  CHECK(m.find("Evaluator::pdf: spans of different lengths: pdf 3, wi 3, wo 3, ctx 2") != std::string::npos);
  CHECK(m.find("ctx may also be empty") != std::string::npos);
  m = message([&] { e.eval_pdf({}, four, three, both3); });
  CHECK(m.find("Evaluator::eval_pdf: spans of different lengths: out 3, wi 4, wo 3") != std::string::npos);
  m = message([&] { e.sample({}, three, u2, lobe3, samples3); });
  CHECK(m.find("Evaluator::sample: spans of different lengths: out 3, wo 3, u 2, u_lobe 3") != std::string::npos);
  // Right lengths: no exception; nothing at all is fine too.
  CHECK_NOTHROW(e.eval({}, three, three, three));
  CHECK_NOTHROW(e.sample({}, three, u3, lobe3, samples3));
  CHECK_NOTHROW(e.eval_pdf({}, {}, {}, std::span<cpu::EvalPdf>()));
}

// --- threads -------------------------------------------------------------------------------------

TEST_CASE("many threads on one Evaluator at once give bit for bit the serial results") {
  const Queries q = make_queries(test::kSanitized ? 400 : 2000);
  const size_t n = q.wi.size();
  const int threads = 8;
  for (const cpu::Evaluator& e : materials()) {
    CAPTURE(e.program().name);
    // Serial reference.
    std::vector<vec3> f(n), albedo(n / 100);
    std::vector<float> pdf(n);
    std::vector<cpu::Sample> samples(n);
    for (size_t i = 0; i < n; ++i) {
      ShadingContext ctx = at_uv(q.uv[i]);
      f[i] = e.eval(ctx, q.wi[i], q.wo[i]);
      pdf[i] = e.pdf(ctx, q.wi[i], q.wo[i]);
      samples[i] = e.sample(ctx, q.wo[i], q.u[i], q.u_lobe[i]);
    }
    for (size_t i = 0; i < albedo.size(); ++i) albedo[i] = e.albedo(at_uv(q.uv[i]), glm::abs(q.wo[i]), 64);
    std::vector<vec3> batch_f(n);
    e.eval(q.ctx, q.wi, q.wo, batch_f);
    // Each thread runs every query, starting at a different offset, with scalar and batch forms
    // interleaved; it counts its own mismatches (no doctest assertions off the main thread).
    std::vector<long> mismatches(threads, 0);
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        long bad = 0;
        for (size_t k = 0; k < n; ++k) {
          size_t i = (k + size_t(t) * n / threads) % n;
          ShadingContext ctx = at_uv(q.uv[i]);
          if (e.eval(ctx, q.wi[i], q.wo[i]) != f[i]) ++bad;
          if (e.pdf(ctx, q.wi[i], q.wo[i]) != pdf[i]) ++bad;
          cpu::EvalPdf both = e.eval_pdf(ctx, q.wi[i], q.wo[i]);
          if (both.f != f[i] || both.pdf != pdf[i]) ++bad;
          if (!same(e.sample(ctx, q.wo[i], q.u[i], q.u_lobe[i]), samples[i])) ++bad;
          if (i < albedo.size() && e.albedo(at_uv(q.uv[i]), glm::abs(q.wo[i]), 64) != albedo[i]) ++bad;
        }
        std::vector<vec3> mine(n);
        e.eval(q.ctx, q.wi, q.wo, mine);
        for (size_t i = 0; i < n; ++i) bad += mine[i] != batch_f[i] ? 1 : 0;
        mismatches[size_t(t)] = bad;
      });
    for (std::thread& thread : pool) thread.join();
    for (int t = 0; t < threads; ++t) {
      CAPTURE(t);
      CHECK(mismatches[size_t(t)] == 0);
    }
  }
}

// --- limits and compile --------------------------------------------------------------------------

TEST_CASE("a stack whose mixes share stacks into more than 64 lobes is refused by the checker at once") {
  // mix_i takes mix_(i-1) on both sides: 2^40 paths through 41 nodes. Counting them must not
  // list them; the checker knows the evaluator's limit, so no command gets as far as building it.
  std::string nodes = R"({"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]})";
  std::string below = "base";
  for (int i = 0; i < 40; ++i) {
    std::string id = "mix" + std::to_string(i);
    nodes += R"(, {"id": ")" + id + R"(", "type": "mix", "weight": 0.5, "a": "@)" + below + R"(", "b": "@)" + below +
             R"("})";
    below = id;
  }
  std::string text =
      R"({"format": 1, "materials": [{"name": "wide", "surface": "@)" + below + R"(", "nodes": [)" + nodes + "]}]}";
  CheckedFile checked = check_text(text, "wide.json");
  REQUIRE(checked.diagnostics.errors().size() == 1);
  CHECK(checked.diagnostics.errors()[0].pointer == "/materials/0/surface");
  CHECK(checked.diagnostics.errors()[0].message.find("more than " + std::to_string(kMaxLobes) + " lobes") !=
        std::string::npos);
  // Six levels (64 lobes) are fine.
  cpu::Evaluator ok = test::evaluator_from_text(
      R"({"format": 1, "materials": [{"name": "six", "surface": "@m5", "nodes": [
        {"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
        {"id": "m0", "type": "mix", "weight": 0.5, "a": "@base", "b": "@base"},
        {"id": "m1", "type": "mix", "weight": 0.5, "a": "@m0", "b": "@m0"},
        {"id": "m2", "type": "mix", "weight": 0.5, "a": "@m1", "b": "@m1"},
        {"id": "m3", "type": "mix", "weight": 0.5, "a": "@m2", "b": "@m2"},
        {"id": "m4", "type": "mix", "weight": 0.5, "a": "@m3", "b": "@m3"},
        {"id": "m5", "type": "mix", "weight": 0.5, "a": "@m4", "b": "@m4"}]}]})");
  CHECK(ok.lobe_count() == 64);
  // Every path leads to the same Lambert base: f is its albedo / pi.
  vec3 f = ok.eval(ShadingContext{}, glm::normalize(vec3(0.2f, 0.1f, 1.0f)), vec3(0.0f, 0.0f, 1.0f));
  CHECK(near(f, vec3(0.5f / float(test::kPi)), 1e-6f));
}

TEST_CASE("compile reads each microfacet node's fresnel parameter into the program, exact by default") {
  CheckedFile checked = check_file(test::source_dir() / "tests/data/glsl/fresnel_modes.json");
  REQUIRE(checked.ok());
  Program p = compile(*checked.graphs[0], "fresnel_modes.json");
  // Fresnel codes of nodes/kernels/fresnel.glsl: 0 exact, 1 Schlick, 2 Lazanyi-Szirmay-Kalos.
  namespace k = kernels;
  auto conductor_of = [](const StackEntry& e) {
    return e.kind == k::LAMINA_SUBSTRATE && e.model == k::LAMINA_SUBSTRATE_CONDUCTOR;
  };
  std::vector<int> interfaces;
  int conductor = 0;
  for (const StackEntry& e : p.stack) {
    if (e.kind == k::LAMINA_LAYER) interfaces.push_back(e.fresnel);
    if (conductor_of(e)) conductor = e.fresnel;
  }
  // From the surface down: the Lazanyi coat, then the Schlick interface into index 1.4.
  CHECK(interfaces == std::vector<int>{2, 1});
  CHECK(conductor == 1);
  Program car = compile(*check_file(test::source_dir() / "examples/materials/car_paint.json").graphs[0], "car.json");
  for (const StackEntry& e : car.stack)
    if (e.kind == k::LAMINA_LAYER || conductor_of(e)) CHECK(e.fresnel == 0);
  // The modes change the BRDF: the same stack with exact terms everywhere differs.
  cpu::Evaluator approximate(std::move(p));
  std::string text = test::read_file(test::source_dir() / "tests/data/glsl/fresnel_modes.json");
  for (const char* mode : {"\"fresnel\": \"lazanyi\"", "\"fresnel\": \"schlick\""})
    for (size_t at = text.find(mode); at != std::string::npos; at = text.find(mode))
      text.replace(at, std::string(mode).size(), "\"fresnel\": \"exact\"");
  cpu::Evaluator exact = test::evaluator_from_text(text);
  vec3 wi = glm::normalize(vec3(0.6f, 0.1f, 0.3f)), wo = glm::normalize(vec3(-0.5f, 0.0f, 0.4f));
  CHECK(approximate.eval(ShadingContext{}, wi, wo) != exact.eval(ShadingContext{}, wi, wo));
}
