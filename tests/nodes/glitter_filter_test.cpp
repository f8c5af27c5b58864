// Glitter without aliasing: a pixel that covers many Voronoi cells shows their mean. texture/voronoi
// fades its cells to their means (a filtered normal shorter than 1, a coverage), the stack widens a
// lobe whose normal is short (lamina_widened_slope) and a select shows every stack in proportion
// (lamina_select_weight). Checked here kernel by kernel against formulas worked out independently,
// then as a whole: the filtered evaluation against the mean of point evaluations over the footprint.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "graph/cpu/evaluator.h"
#include "graph/cpu_test_support.h"
#include "nodes/kernels/kernels.h"
#include "test_support.h"

using namespace lamina;
namespace k = lamina::kernels;
using glm::vec2;
using glm::vec3;

TEST_CASE("a normal of length 1 leaves the slope alone, and a shorter one adds Toksvig's variance to it") {
  for (float m : {0.0f, 0.02f, 0.3f, 1.0f}) {
    CAPTURE(m);
    CHECK(k::lamina_widened_slope(m, vec3(0.0f, 0.0f, 1.0f)) == m);
    CHECK(k::lamina_widened_slope(m, vec3(0.6f, 0.0f, 0.8f)) == m);
    CHECK(k::lamina_widened_slope(m, vec3(0.0f, 0.0f, 3.0f)) == m);  // longer: a direction
  }
  // Toksvig's sigma^2 = (1 - L) / L is 1 / s added to a Blinn-Phong exponent s; with s = 2 / m^2
  // the slope becomes sqrt(m^2 + 2 sigma^2). Mean normals of Voronoi cells tilted by m_t have
  // L = 2 / (2 + m_t^2), i.e. sigma^2 = m_t^2 / 2: the cells' slope variance adds to the lobe's.
  for (double tilt : {0.02, 0.1, 0.3}) {
    for (double m : {0.01, 0.1, 0.4}) {
      CAPTURE(tilt);
      CAPTURE(m);
      const double length = 2.0 / (2.0 + tilt * tilt);
      const double sigma2 = (1.0 - length) / length;
      const double expected = std::min(std::sqrt(m * m + 2.0 * sigma2), 1.0);
      CHECK(double(k::lamina_widened_slope(float(m), vec3(0.0f, 0.0f, float(length)))) ==
            doctest::Approx(expected).epsilon(1e-5));
      CHECK(expected == doctest::Approx(std::sqrt(m * m + tilt * tilt)).epsilon(1e-9));
    }
  }
  // The tilt of a short normal does not matter, only its length; at 2/3 and below the slope is 1.
  CHECK(k::lamina_widened_slope(0.1f, vec3(0.3f, 0.0f, 0.9f) * (0.95f / std::sqrt(0.9f))) ==
        doctest::Approx(k::lamina_widened_slope(0.1f, vec3(0.0f, 0.0f, 0.95f))).epsilon(1e-5));
  CHECK(k::lamina_widened_slope(0.1f, vec3(0.0f, 0.0f, 2.0f / 3.0f)) == doctest::Approx(1.0f).epsilon(1e-5));
  CHECK(k::lamina_widened_slope(0.1f, vec3(0.0f)) == 1.0f);
  CHECK(k::lamina_widened_slope(0.1f, vec3(std::nanf(""))) == 1.0f);
}

TEST_CASE("a select's chain shows (1 - c) on the indexed stack plus c / N on each, and exactly one at c = 0") {
  // The share of each stack from the chain's weights: step k passes weight w_k on to the stacks
  // after stack k and keeps 1 - w_k for stack k; the last step's remainder is stack N - 1.
  auto shares = [](int count, float index, float coverage) {
    std::vector<double> share(size_t(count), 0.0);
    double reaching = 1.0;
    for (int step = 0; step + 1 < count; ++step) {
      const double w = k::lamina_select_weight(index, float(step), float(step + 1), float(count), coverage);
      share[size_t(step)] = reaching * (1.0 - w);
      reaching *= w;
    }
    share[size_t(count - 1)] = reaching;
    return share;
  };
  for (int count : {2, 4, 9}) {
    for (float cell : {0.0f, 0.3f, 0.74f, 0.999f}) {
      const float index = cell * float(count);
      const int named = int(std::floor(index));
      CAPTURE(count);
      CAPTURE(index);
      // c = 0: the named stack alone, with weights exactly 0 and 1.
      std::vector<double> point = shares(count, index, 0.0f);
      for (int j = 0; j < count; ++j) CHECK(point[size_t(j)] == (j == named ? 1.0 : 0.0));
      for (float c : {0.25f, 0.5f, 0.9f, 1.0f}) {
        CAPTURE(c);
        // The index a Voronoi value faded to: count / 2 + (1 - c) (index - count / 2).
        const float faded = 0.5f * float(count) + (1.0f - c) * (index - 0.5f * float(count));
        std::vector<double> got = shares(count, faded, c);
        double total = 0.0;
        for (int j = 0; j < count; ++j) {
          const double expected = (j == named ? 1.0 - c : 0.0) + c / double(count);
          CHECK(got[size_t(j)] == doctest::Approx(expected).epsilon(1e-5));
          total += got[size_t(j)];
        }
        CHECK(total == doctest::Approx(1.0).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("Voronoi cells fade to their means between half a cell and two cells per pixel") {
  const float tilt_deg = 5.0f;
  const double m = std::tan(tilt_deg * test::kPi / 180.0);
  for (int i = 0; i < 50; ++i) {
    const vec3 p(0.37f * float(i) + 0.11f, 0.53f * float(i) + 0.29f, 0.0f);
    const k::LaminaVoronoi point = k::lamina_voronoi_cell(p, false, 0.9f, 3u, tilt_deg, 0, 0.0f);
    // Up to half a cell: the point sample itself.
    const k::LaminaVoronoi half = k::lamina_voronoi_cell(p, false, 0.9f, 3u, tilt_deg, 0, 0.5f);
    CHECK(half.coverage == 0.0f);
    CHECK(half.value == point.value);
    CHECK(half.normal == point.normal);
    CHECK(std::abs(glm::length(point.normal) - 1.0f) < 1e-6f);
    // From two cells on: the means, the normal (0, 0, 2 / (2 + m^2)).
    const k::LaminaVoronoi many = k::lamina_voronoi_cell(p, false, 0.9f, 3u, tilt_deg, 0, 2.0f);
    CHECK(many.coverage == 1.0f);
    CHECK(many.value == 0.5f);
    CHECK(many.colour == vec3(0.5f));
    CHECK(many.normal.x == 0.0f);
    CHECK(many.normal.y == 0.0f);
    CHECK(double(many.normal.z) == doctest::Approx(2.0 / (2.0 + m * m)).epsilon(1e-6));
    // In between, partly: a coverage of 1/3 at 1 cell per pixel.
    const k::LaminaVoronoi one = k::lamina_voronoi_cell(p, false, 0.9f, 3u, tilt_deg, 0, 1.0f);
    CHECK(one.coverage == doctest::Approx(1.0f / 3.0f));
    CHECK(glm::length(one.normal) < 1.0f);
  }
  // The mean normal's z is, to first order in m^2, the mean cos(theta) of the cells' normals.
  double mean_z = 0.0;
  const int side = 200;
  for (int i = 0; i < side * side; ++i)
    mean_z += k::lamina_voronoi_cell(vec3(float(i % side) + 0.5f, float(i / side) + 0.5f, 0.0f), false, 0.9f, 3u,
                                     tilt_deg, 0, 0.0f)
                  .normal.z;
  mean_z /= side * side;
  CHECK(mean_z == doctest::Approx(2.0 / (2.0 + m * m)).epsilon(2e-4));
}

namespace {

// The mean of point evaluations over the square footprint of side `footprint` around uv, on a
// regular grid of side x side points (every cell under it met about equally often).
vec3 mean_over_footprint(const cpu::Evaluator& e, vec2 uv, float footprint, int side, vec3 wi, vec3 wo) {
  glm::dvec3 sum(0.0);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      ShadingContext point;
      point.uv = uv + footprint * (vec2(float(i) + 0.5f, float(j) + 0.5f) / float(side) - vec2(0.5f));
      sum += glm::dvec3(e.eval(point, wi, wo));
    }
  return vec3(sum / double(side * side));
}

}  // namespace

TEST_CASE("a footprint over many glitter cells evaluates as the mean of point evaluations under it") {
  // Sunstone's 600 cells per uv unit: a footprint of 1/6 covers 100 x 100 cells, half of them copper
  // glitter. The filtered evaluation widens the copper's lobe by the cells' tilt and shows the stone
  // and the glitter in proportion; the mean of 160 x 160 point evaluations is what a pixel would
  // average. Measured (both models, these directions): within 5.5%; held to 8%.
  const std::filesystem::path file = test::source_dir() / "examples/materials/sunstone.json";
  const float footprint = 1.0f / 6.0f;
  const vec2 uv(0.4f, 0.6f);
  struct Pair {
    vec3 wi, wo;
  };
  const Pair pairs[] = {
      {{0.3f, 0.1f, 1.0f}, {-0.3f, -0.1f, 1.0f}},  // the highlight
      {{0.6f, 0.0f, 1.0f}, {-0.5f, 0.1f, 1.0f}},   // near it
      {{0.2f, 0.0f, 1.0f}, {-0.5f, 0.1f, 1.0f}},   // its flank
      {{1.0f, 0.3f, 0.5f}, {-1.0f, -0.3f, 0.5f}},  // at 63 degrees
      {{0.5f, 0.5f, 1.0f}, {0.2f, -0.3f, 1.0f}},   // far from it: the stone
  };
  for (int model : {k::LAMINA_MODEL_ENERGY_CONSERVING, k::LAMINA_MODEL_WEIDLICH_WILKIE}) {
    const cpu::Evaluator e = test::load_evaluator(file, model);
    for (const Pair& pair : pairs) {
      const vec3 wi = glm::normalize(pair.wi), wo = glm::normalize(pair.wo);
      CAPTURE(model);
      CAPTURE(wi);
      CAPTURE(wo);
      ShadingContext pixel;
      pixel.uv = uv;
      pixel.footprint = footprint;
      const vec3 filtered = e.eval(pixel, wi, wo);
      const vec3 mean = mean_over_footprint(e, uv, footprint, 160, wi, wo);
      for (int c = 0; c < 3; ++c) CHECK(std::abs(filtered[c] / mean[c] - 1.0f) <= 0.08f);
    }
  }
}

TEST_CASE("a footprint under half a cell keeps every sparkle: the evaluation is the point sample's") {
  const cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples/materials/sunstone.json");
  const vec3 wi = glm::normalize(vec3(0.3f, 0.1f, 1.0f)), wo = glm::normalize(vec3(-0.3f, -0.1f, 1.0f));
  std::vector<vec3> seen;
  for (int i = 0; i < 40; ++i) {
    ShadingContext point, pixel;
    point.uv = pixel.uv = vec2(0.1f + 0.0137f * float(i), 0.3f + 0.0071f * float(i));
    pixel.footprint = 0.5f / 600.0f;  // Sunstone's cells: 600 per uv unit
    const vec3 f = e.eval(point, wi, wo);
    CHECK(e.eval(pixel, wi, wo) == f);
    if (std::find(seen.begin(), seen.end(), f) == seen.end()) seen.push_back(f);
  }
  // The stone is one value; half the cells are glitter, each facet tilted its own way.
  CHECK(seen.size() >= 4);
}

TEST_CASE("glitter does not flicker: moving a pixel over many cells by part of its width hardly changes it") {
  // A row of pixels of 1/60 uv (10 of Sunstone's cells across) evaluated at their centres and again
  // shifted by 0.37 of a pixel, as when the surface moves a little between two frames: filtered,
  // each pixel shows the mean of its cells and keeps it; point-sampled, each pixel shows whichever
  // cell its centre hits, a stone or a copper facet tilted its own way, and changes.
  const cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples/materials/sunstone.json");
  const vec3 wi = glm::normalize(vec3(0.3f, 0.1f, 1.0f)), wo = glm::normalize(vec3(-0.3f, -0.1f, 1.0f));
  const float pixel = 1.0f / 60.0f;
  double filtered = 0.0, point = 0.0, level = 0.0;
  const int count = 64;
  for (int i = 0; i < count; ++i) {
    const vec2 uv(0.2f + pixel * float(i), 0.55f);
    const vec2 moved = uv + vec2(0.37f * pixel, 0.21f * pixel);
    ShadingContext a, b, p, q;
    a.uv = p.uv = uv;
    b.uv = q.uv = moved;
    a.footprint = b.footprint = pixel;
    const float fa = e.eval(a, wi, wo).x, fb = e.eval(b, wi, wo).x;
    filtered += std::abs(double(fb - fa));
    point += std::abs(double(e.eval(q, wi, wo).x - e.eval(p, wi, wo).x));
    level += double(fa);
  }
  filtered /= level;
  point /= level;
  MESSAGE("mean change over the mean value: filtered " << filtered << ", point-sampled " << point);
  CHECK(filtered <= 0.01);
  CHECK(point >= 0.3);
}
