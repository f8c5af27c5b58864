// The procedural texture kernels (nodes/kernels/procedural.glsl) against values computed
// independently and the properties their sources state, and the nodes that use them (texture/noise,
// texture/marble, texture/voronoi, texture/patina, math/mix) through checker, compiler and evaluator.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu_test_support.h"
#include "graph/load.h"
#include "nodes/kernels/kernels.h"
#include "test_support.h"

using namespace lamina;
namespace k = lamina::kernels;

namespace {

// How far a footprint-filtered texture value may lie from the box mean of its point samples, in
// units of the value (which spans [0, 1]); measured worst cases are printed by the tests.
constexpr double kFootprintTolerance = 0.1;

// F1 and F2 by brute force over the 5x5 (x5) cells around p, the kernel's feature points.
glm::vec2 voronoi_brute_force(glm::vec3 p, bool three_d, float jitter, unsigned seed) {
  const glm::ivec3 home = glm::ivec3(glm::floor(p));
  float f1 = 1e30f, f2 = 1e30f;
  const int reach_z = three_d ? 2 : 0;
  for (int dz = -reach_z; dz <= reach_z; ++dz)
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const glm::ivec3 c = home + glm::ivec3(dx, dy, dz);
        const glm::uvec3 h = k::lamina_hash_cell(c, seed);
        const glm::vec3 u(k::lamina_hash_unit(h.x), k::lamina_hash_unit(h.y), k::lamina_hash_unit(h.z));
        glm::vec3 point = glm::vec3(c) + glm::vec3(0.5f) + jitter * (u - glm::vec3(0.5f));
        if (!three_d) point.z = 0.0f;
        const float d2 = glm::dot(point - p, point - p);
        if (d2 < f1) {
          f2 = f1;
          f1 = d2;
        } else {
          f2 = std::min(f2, d2);
        }
      }
  return glm::vec2(std::sqrt(f1), std::sqrt(f2));
}

cpu::Evaluator compile_text(const std::string& text, const char* file) {
  CheckedFile checked = check_text(text, file);
  REQUIRE(checked.ok());
  return cpu::Evaluator(compile(*checked.graphs[0], file));
}

}  // namespace

TEST_CASE("the hash is Jarzynski and Olano's pcg3d, as an independent implementation computes it") {
  // Values from a Python transcription of the paper's pcg3d in arbitrary-precision integers reduced
  // mod 2^32 (not from this kernel).
  const glm::uvec3 h = k::lamina_hash3(glm::uvec3(1u, 2u, 3u));
  CHECK(h == glm::uvec3(4204755366u, 1223881804u, 1500469937u));
  // A lattice point under seed 7: the point moved by 7 (2654435769, 2246822507, 3266489909) mod 2^32.
  const glm::uvec3 s = k::lamina_hash_cell(glm::ivec3(-1, 5, 0), 7u);
  CHECK(s == glm::uvec3(2700396214u, 1558107525u, 7787611u));
  // The unit number is exact: the top 24 bits over 2^24.
  CHECK(k::lamina_hash_unit(0xFFFFFFFFu) == float(16777215.0 / 16777216.0));
  CHECK(k::lamina_hash_unit(0x000000FFu) == 0.0f);
}

TEST_CASE("gradient noise vanishes at lattice points, is continuous across cells and stays within [-1, 1]") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> coordinate(-40.0f, 40.0f);
  for (int i = -3; i <= 3; ++i) CHECK(k::lamina_perlin(glm::vec3(float(i), float(2 * i), float(-i)), 4u) == 0.0f);
  double sum = 0.0, lo = 0.0, hi = 0.0;
  const int n = 200000 / test::kSanitizerDivisor;
  for (int i = 0; i < n; ++i) {
    const float x = coordinate(rng);
    const float y = coordinate(rng);
    const float z = coordinate(rng);
    const double v = k::lamina_perlin(glm::vec3(x, y, z), 0u);
    sum += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  CAPTURE(lo);
  CAPTURE(hi);
  CHECK(lo >= -1.0);
  CHECK(hi <= 1.0);
  CHECK(hi - lo > 1.2);  // it does come near its bounds
  CHECK(std::abs(sum / n) < 0.01);
  // Across a cell face the two cells' corners blend to the same value (the fade's zero slope).
  for (int i = 0; i < 100; ++i) {
    const float y = coordinate(rng);
    const float z = coordinate(rng);
    const float below = k::lamina_perlin(glm::vec3(std::nextafter(3.0f, 0.0f), y, z), 1u);
    const float above = k::lamina_perlin(glm::vec3(3.0f, y, z), 1u);
    CHECK(std::abs(below - above) < 1e-5f);
  }
  // Seeds give different patterns.
  CHECK(k::lamina_perlin(glm::vec3(0.3f, 0.6f, 0.2f), 1u) != k::lamina_perlin(glm::vec3(0.3f, 0.6f, 0.2f), 2u));
}

TEST_CASE("fractal sums are normalised by their amplitudes: one octave is the noise, turbulence its magnitude") {
  const glm::vec3 p(1.37f, -2.61f, 0.45f);
  CHECK(k::lamina_fbm(p, 1, 2.0f, 0.5f, 9u, false, 0.0f) == k::lamina_perlin(p, 9u));
  CHECK(k::lamina_fbm(p, 1, 2.0f, 0.5f, 9u, true, 0.0f) == std::abs(k::lamina_perlin(p, 9u)));
  // Two octaves: (n0 + gain n1) / (1 + gain), n1 at lacunarity p under the next seed.
  const float two = (k::lamina_perlin(p, 9u) + 0.6f * k::lamina_perlin(p * 2.5f, 10u)) / 1.6f;
  CHECK(k::lamina_fbm(p, 2, 2.5f, 0.6f, 9u, false, 0.0f) == doctest::Approx(two).epsilon(1e-6));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f);
  int outside = 0;
  for (int i = 0; i < 20000; ++i) {
    const float x = coordinate(rng);
    const float y = coordinate(rng);
    const glm::vec3 q(x, y, 0.0f);
    const float value = k::lamina_noise_value(q, 6, 2.0f, 0.5f, 3u, false, 0.0f);
    const float turbulence = k::lamina_noise_value(q, 6, 2.0f, 0.5f, 3u, true, 0.0f);
    outside += !(value >= 0.0f && value <= 1.0f) || !(turbulence >= 0.0f && turbulence <= 1.0f);
  }
  CHECK(outside == 0);
  // Coordinates beyond the lattice's range read as 0 instead of overflowing an int.
  CHECK(k::lamina_perlin(glm::vec3(1e30f, -1e30f, std::numeric_limits<float>::quiet_NaN()), 0u) == 0.0f);
}

TEST_CASE("marble is Perlin's sin of a stripe coordinate displaced by turbulence, in [0, 1]") {
  // Without turbulence: 0.5 + 0.5 sin(2 pi stripes x); at x = 0.0625 and 2 stripes, sin(pi / 4).
  const glm::vec3 p(0.0625f, 0.3f, 0.0f);
  const double expected = 0.5 + 0.5 * std::sin(std::numbers::pi / 4.0);
  CHECK(k::lamina_marble_value(p, 4.0f, glm::vec3(1.0f, 0.0f, 0.0f), 2.0f, 0.0f, 3, 2.0f, 0.5f, 1u, 0.0f) ==
        doctest::Approx(expected).epsilon(1e-5));
  // With it, the phase moves by strength times the turbulence at p scale.
  const float t = k::lamina_fbm(p * 4.0f, 3, 2.0f, 0.5f, 1u, true, 0.0f);
  const double moved = 0.5 + 0.5 * std::sin(2.0 * std::numbers::pi * (0.125 + 1.5 * double(t)));
  CHECK(k::lamina_marble_value(p, 4.0f, glm::vec3(1.0f, 0.0f, 0.0f), 2.0f, 1.5f, 3, 2.0f, 0.5f, 1u, 0.0f) ==
        doctest::Approx(moved).epsilon(1e-5));
}

TEST_CASE("Voronoi's 3x3 search finds the nearest and second nearest feature points up to jitter 0.75") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> coordinate(-100.0f, 100.0f);
  for (bool three_d : {false, true})
    for (float jitter : {0.0f, 0.5f, 0.75f}) {
      CAPTURE(three_d);
      CAPTURE(jitter);
      int wrong = 0;
      for (int i = 0; i < 20000 / test::kSanitizerDivisor; ++i) {
        const float x = coordinate(rng);
        const float y = coordinate(rng);
        const float z = three_d ? coordinate(rng) : 0.0f;
        glm::ivec3 cell;
        const glm::vec2 f = k::lamina_voronoi(glm::vec3(x, y, z), three_d, jitter, 8u, cell);
        const glm::vec2 brute = voronoi_brute_force(glm::vec3(x, y, z), three_d, jitter, 8u);
        // Compilers may fuse the two sides' arithmetic differently (clang contracts a * b + c):
        // equal to rounding.
        if (glm::any(glm::greaterThan(glm::abs(f - brute), glm::vec2(1e-5f))) || !(f.x <= f.y)) ++wrong;
      }
      CHECK(wrong == 0);
    }
  // Jitter 0 is the regular grid: F1 is the distance to the cell's centre.
  glm::ivec3 cell;
  const glm::vec2 f = k::lamina_voronoi(glm::vec3(2.25f, -0.5f, 7.0f), false, 0.0f, 1u, cell);
  CHECK(f.x == doctest::Approx(0.25).epsilon(1e-6));  // the centre (2.5, -0.5) of cell (2, -1)
  CHECK(cell == glm::ivec3(2, -1, 0));
}

TEST_CASE("Voronoi cells draw uniform values and colours, and normals with the declared slope distribution") {
  const int n = 40000;
  double value = 0.0, colour = 0.0;
  for (int i = 0; i < n; ++i) {
    glm::vec4 r;
    k::lamina_cell_randoms(glm::ivec3(i % 200, i / 200, 0), 4u, r);
    value += r.x;
    colour += r.y + r.z + r.w;
  }
  CHECK(value / n == doctest::Approx(0.5).epsilon(0.01));
  CHECK(colour / (3.0 * n) == doctest::Approx(0.5).epsilon(0.01));
  // Beckmann: tan^2 theta = -m^2 ln(1 - u) is exponential with mean m^2. GGX: tan^2 = m^2 u / (1 - u),
  // whose median (u = 1/2) is m^2. Both at m = tan 5 degrees, over a stratified u.
  const float m = std::tan(5.0f * std::numbers::pi_v<float> / 180.0f);
  double mean_tan2 = 0.0;
  int ggx_below = 0, not_unit = 0;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 u((float(i) + 0.5f) / float(n), float((i * 7919) % n) / float(n));
    const glm::vec3 b = k::lamina_tilted_normal(u, m, 0);
    const glm::vec3 g = k::lamina_tilted_normal(u, m, 2);
    not_unit += std::abs(glm::length(b) - 1.0f) > 1e-5f || std::abs(glm::length(g) - 1.0f) > 1e-5f || !(g.z > 0.0f);
    mean_tan2 += double(b.x * b.x + b.y * b.y) / double(b.z * b.z);
    if ((g.x * g.x + g.y * g.y) / (g.z * g.z) < m * m) ++ggx_below;
  }
  CHECK(not_unit == 0);
  CHECK(mean_tan2 / n == doctest::Approx(double(m) * m).epsilon(0.01));
  CHECK(double(ggx_below) / n == doctest::Approx(0.5).epsilon(0.01));
}

TEST_CASE("the patina weight is Elek's 1 - smoothstep(extent - transition, extent + transition, p)") {
  // p = 0.45, extent 0.5, transition 0.1: t = (0.45 - 0.4) / 0.2 = 0.25, smoothstep 0.15625.
  CHECK(k::lamina_patina_weight(0.45f, 0.5f, 0.1f) == doctest::Approx(0.84375).epsilon(1e-6));
  CHECK(k::lamina_patina_weight(0.5f, 0.5f, 0.1f) == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(k::lamina_patina_weight(0.2f, 0.5f, 0.1f) == 1.0f);
  CHECK(k::lamina_patina_weight(0.7f, 0.5f, 0.1f) == 0.0f);
  // Elek's extremes: extent -transition leaves no patina, 1 + transition covers the map.
  CHECK(k::lamina_patina_weight(0.0f, -0.1f, 0.1f) == 0.0f);
  CHECK(k::lamina_patina_weight(1.0f, 1.1f, 0.1f) == 1.0f);
  // Transition 0 is a hard edge at extent.
  CHECK(k::lamina_patina_weight(0.49f, 0.5f, 0.0f) == 1.0f);
  CHECK(k::lamina_patina_weight(0.51f, 0.5f, 0.0f) == 0.0f);
}

TEST_CASE("patina grows over a noise map as its extent rises, and a uv noise ignores the position") {
  // A white Lambert (bare) mixed with a black one (patina) by the patina weight of a noise:
  // f pi = 1 - k. The covered share of a grid of uv points grows with the extent.
  auto material = [](double extent, const char* space, double transition = 0.05) {
    return std::string(R"({"format": 1, "materials": [{"name": "growth", "surface": "@top", "nodes": [
      {"id": "map", "type": "texture/noise", "space": ")") +
           space + R"(", "scale": 5, "octaves": 3, "seed": 2},
      {"id": "k", "type": "texture/patina", "map": "@map", "extent": )" +
           std::to_string(extent) + R"(, "transition": )" + std::to_string(transition) + R"(},
      {"id": "top", "type": "mix", "weight": "@k", "a": "@white", "b": "@black"},
      {"id": "white", "type": "substrate/lambert", "albedo": [1, 1, 1]},
      {"id": "black", "type": "substrate/lambert", "albedo": [0, 0, 0]}]}]})";
  };
  const glm::vec3 up(0.0f, 0.0f, 1.0f);
  double previous = -1.0;
  for (double extent : {0.3, 0.45, 0.5, 0.55, 0.7}) {
    const cpu::Evaluator e = compile_text(material(extent, "uv"), "growth.json");
    double covered = 0.0;
    for (int i = 0; i < 32; ++i)
      for (int j = 0; j < 32; ++j) {
        ShadingContext ctx;
        ctx.uv = glm::vec2((float(i) + 0.5f) / 32.0f, (float(j) + 0.5f) / 32.0f);
        covered += 1.0 - double(e.eval(ctx, up, up).x) * std::numbers::pi;
      }
    CAPTURE(extent);
    CHECK(covered > previous);
    previous = covered;
  }
  // A transition of 1 keeps the weight off its bounds, so that any change of the map shows.
  const cpu::Evaluator uv = compile_text(material(0.5, "uv", 1.0), "growth.json");
  const cpu::Evaluator position = compile_text(material(0.5, "position", 1.0), "growth.json");
  ShadingContext a, b;
  a.uv = b.uv = glm::vec2(0.3f, 0.7f);
  a.position = glm::vec3(0.1f, 0.2f, 0.3f);
  b.position = glm::vec3(0.4f, -0.3f, 0.15f);
  CHECK(uv.eval(a, up, up) == uv.eval(b, up, up));
  CHECK(position.eval(a, up, up) != position.eval(b, up, up));
}

TEST_CASE("math/mix blends two colours by its factor, here a Lambert albedo") {
  const cpu::Evaluator e = compile_text(R"({"format": 1, "materials": [{"name": "tint", "surface": "@base", "nodes": [
      {"id": "tiles", "type": "texture/checker", "color_a": [0, 0, 0], "color_b": [1, 1, 1]},
      {"id": "tint", "type": "math/mix", "a": [0.8, 0.4, 0.2], "b": [0.2, 0.6, 1.0], "factor": "@tiles.value"},
      {"id": "flat", "type": "math/mix", "a": [0.8, 0.4, 0.2], "b": [0.2, 0.6, 1.0], "factor": 0.25},
      {"id": "top", "type": "mix", "weight": 0.5, "a": "@base", "b": "@flat_base"},
      {"id": "flat_base", "type": "substrate/lambert", "albedo": "@flat"},
      {"id": "base", "type": "substrate/lambert", "albedo": "@tint"}]}]})",
                                        "tint.json");
  const glm::vec3 up(0.0f, 0.0f, 1.0f);
  ShadingContext even, odd;
  even.uv = glm::vec2(0.1f, 0.1f);
  odd.uv = glm::vec2(0.2f, 0.1f);
  const glm::vec3 a = e.eval(even, up, up) * std::numbers::pi_v<float>;
  const glm::vec3 b = e.eval(odd, up, up) * std::numbers::pi_v<float>;
  CHECK(a.x == doctest::Approx(0.8).epsilon(1e-6));
  CHECK(a.z == doctest::Approx(0.2).epsilon(1e-6));
  CHECK(b.x == doctest::Approx(0.2).epsilon(1e-6));
  CHECK(b.z == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE("procedural nodes refuse counts that are not whole, beyond their maximum, and scales that are not positive") {
  struct Case {
    const char* node;
    const char* pointer;
  };
  const Case cases[] = {
      {R"({"id": "n", "type": "texture/noise", "octaves": 13})", "/octaves"},
      {R"({"id": "n", "type": "texture/noise", "octaves": 2.5})", "/octaves"},
      {R"({"id": "n", "type": "texture/noise", "octaves": "@other"})", "/octaves"},
      {R"({"id": "n", "type": "texture/marble", "scale": -1})", "/scale"},
      {R"({"id": "n", "type": "texture/voronoi", "seed": -1})", "/seed"},
      {R"({"id": "n", "type": "texture/voronoi", "jitter": 1.5})", "/jitter"},
      {R"({"id": "n", "type": "texture/voronoi", "tilt_distribution": "blinn"})", "/tilt_distribution"},
      {R"({"id": "n", "type": "texture/noise", "space": "world"})", "/space"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.node);
    const std::string text = std::string(R"({"format": 1, "materials": [{"name": "bad", "surface": "@base", "nodes": [
      {"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
      {"id": "other", "type": "texture/checker"},
      )") + c.node + "]}]}";
    CheckedFile checked = check_text(text, "bad.json");
    REQUIRE_FALSE(checked.ok());
    CHECK(checked.diagnostics.errors().front().pointer == std::string("/materials/0/nodes/2") + c.pointer);
  }
}

TEST_CASE("the bundled patina growth stages differ only in extent, and each covers more of the copper") {
  // Every file of examples/materials/patina_growth, ordered by its extent: the share of a uv grid
  // where the patina weight exceeds 1/2 grows from stage to stage.
  struct Stage {
    double extent;
    double covered;
    nlohmann::json nodes;
  };
  std::vector<Stage> stages;
  for (const auto& entry :
       std::filesystem::directory_iterator(test::source_dir() / "examples/materials/patina_growth")) {
    const std::string file = entry.path().string();
    CAPTURE(file);
    nlohmann::json doc = nlohmann::json::parse(test::read_file(entry.path()));
    nlohmann::json nodes = doc["materials"][0]["nodes"];
    double extent = -1.0;
    for (auto& node : nodes)
      if (node["type"] == "texture/patina") {
        extent = node["extent"].get<double>();
        node.erase("extent");
      }
    REQUIRE(extent >= 0.0);
    CheckedFile checked = check_text(test::read_file(entry.path()), file);
    REQUIRE(checked.ok());
    const Program program = compile(*checked.graphs[0], file);
    const cpu::Evaluator e(program);
    const auto weight = std::find_if(program.ops.begin(), program.ops.end(),
                                     [](const TextureOp& op) { return op.decl->type == "texture/patina"; });
    REQUIRE(weight != program.ops.end());
    double covered = 0.0;
    for (int i = 0; i < 64; ++i)
      for (int j = 0; j < 64; ++j) {
        ShadingContext ctx;
        ctx.uv = glm::vec2((float(i) + 0.5f) / 64.0f, (float(j) + 0.5f) / 64.0f);
        covered += e.texture_registers(ctx)[size_t(weight->outputs[0])] > 0.5f ? 1.0 / 4096.0 : 0.0;
      }
    stages.push_back({extent, covered, nodes});
  }
  REQUIRE(stages.size() >= 2);
  std::sort(stages.begin(), stages.end(), [](const Stage& a, const Stage& b) { return a.extent < b.extent; });
  for (size_t s = 1; s < stages.size(); ++s) {
    CAPTURE(stages[s].extent);
    CHECK(stages[s].nodes == stages[0].nodes);
    CHECK(stages[s].covered > stages[s - 1].covered + 0.05);
  }
  MESSAGE("patina coverage by extent: " << stages.front().extent << " -> " << stages.front().covered << ", "
                                        << stages.back().extent << " -> " << stages.back().covered);
}

namespace {

// The mean of `sample(uv)` over the square footprint of side `width` centred on uv, 48 x 48 points.
template <class F>
double box_mean(F sample, glm::vec2 uv, float width) {
  double sum = 0.0;
  for (int i = 0; i < 48; ++i)
    for (int j = 0; j < 48; ++j)
      sum += double(sample(uv + width * glm::vec2((float(i) + 0.5f) / 48.0f - 0.5f, (float(j) + 0.5f) / 48.0f - 0.5f)));
  return sum / (48.0 * 48.0);
}

}  // namespace

TEST_CASE("the turbulence means the filter fades octaves to are those of the noise") {
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> coordinate(-300.0f, 300.0f);
  double plane = 0.0, space = 0.0;
  const int n = 400000 / test::kSanitizerDivisor;
  for (int i = 0; i < n; ++i) {
    const float x = coordinate(rng);
    const float y = coordinate(rng);
    const float z = coordinate(rng);
    plane += std::abs(k::lamina_perlin(glm::vec3(x, y, 0.0f), 0u));
    space += std::abs(k::lamina_perlin(glm::vec3(x, y, z), 0u));
  }
  CHECK(plane / n == doctest::Approx(k::LAMINA_TURBULENCE_MEAN_2D).epsilon(0.01));
  CHECK(space / n == doctest::Approx(k::LAMINA_TURBULENCE_MEAN_3D).epsilon(0.01));
}

TEST_CASE("a noise filtered over a pixel's footprint is the mean of its point samples there") {
  // Footprints from a tenth of the first octave's cell to 4 cells: the filtered value against the
  // box mean of unfiltered samples, worst over random pixels. Clamping keeps what the pixel
  // resolves and replaces the rest by its mean, so the two differ by what the partly faded octave
  // and the box's own sampling of the resolved ones leave (README, Procedural textures).
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> coordinate(-10.0f, 10.0f);
  for (bool turbulence : {false, true})
    for (float footprint : {0.0f, 0.1f, 0.5f, 1.0f, 4.0f}) {
      CAPTURE(turbulence);
      CAPTURE(footprint);
      double worst = 0.0, squares = 0.0;
      const int pixels = 60 / test::kSanitizerDivisor;
      for (int i = 0; i < pixels; ++i) {
        const float x = coordinate(rng);
        const float y = coordinate(rng);
        const glm::vec2 uv(x, y);
        auto point = [&](glm::vec2 q) {
          return k::lamina_noise_value(glm::vec3(q, 0.0f), 6, 2.0f, 0.5f, 5u, turbulence, 0.0f);
        };
        const double filtered = k::lamina_noise_value(glm::vec3(uv, 0.0f), 6, 2.0f, 0.5f, 5u, turbulence, footprint);
        const double mean = footprint > 0.0f ? box_mean(point, uv, footprint) : double(point(uv));
        worst = std::max(worst, std::abs(filtered - mean));
        squares += (filtered - mean) * (filtered - mean);
      }
      MESSAGE("noise " << std::string(turbulence ? "turbulence" : "fbm") << ", footprint " << footprint
                       << " cells: worst " << worst << ", rms " << std::sqrt(squares / pixels));
      CHECK(worst <= kFootprintTolerance);
    }
}

TEST_CASE("marble's filtered stripes are the box mean of the unfiltered ones, and Voronoi cells average to 1/2") {
  // Undisplaced stripes (strength 0): the sinc factor is the exact box mean.
  const glm::vec3 direction(0.6f, 0.8f, 0.0f);
  for (float footprint : {0.05f, 0.2f, 0.7f, 3.0f}) {
    CAPTURE(footprint);
    const glm::vec2 uv(0.37f, -1.21f);
    auto point = [&](glm::vec2 q) {
      return k::lamina_marble_value(glm::vec3(q, 0.0f), 4.0f, direction, 2.0f, 0.0f, 3, 2.0f, 0.5f, 1u, 0.0f);
    };
    const double filtered =
        k::lamina_marble_value(glm::vec3(uv, 0.0f), 4.0f, direction, 2.0f, 0.0f, 3, 2.0f, 0.5f, 1u, footprint);
    // The square box is a box along u times one along v: the sine's mean is the product of their
    // sinc factors, sin(a) / a for a phase width a along each axis.
    const double a = std::numbers::pi * 2.0 * 0.6 * footprint, b = std::numbers::pi * 2.0 * 0.8 * footprint;
    const double exact_factor = (std::sin(a) / a) * (std::sin(b) / b);
    const double centre = std::sin(2.0 * std::numbers::pi * 2.0 * (0.6 * 0.37 + 0.8 * -1.21));
    CHECK(box_mean(point, uv, footprint) == doctest::Approx(0.5 + 0.5 * exact_factor * centre).epsilon(2e-3));
    CHECK(filtered == doctest::Approx(0.5 + 0.5 * exact_factor * centre).epsilon(2e-3));
  }
  // A pixel over many Voronoi cells sees their mean value 1/2, and so does the filter.
  const glm::vec2 uv(2.3f, 5.1f);
  auto cell_value = [](glm::vec2 q, float footprint) {
    return k::lamina_voronoi_cell(glm::vec3(q, 0.0f), false, 0.9f, 2u, 3.0f, 0, footprint).value;
  };
  const double mean = box_mean([&](glm::vec2 q) { return cell_value(q, 0.0f); }, uv, 8.0f);
  CHECK(cell_value(uv, 8.0f) == 0.5f);
  CHECK(std::abs(mean - 0.5) <= 0.1);
  // Below half a cell per pixel the cell shows as it is.
  CHECK(cell_value(uv, 0.5f) == cell_value(uv, 0.0f));
}
