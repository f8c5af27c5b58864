// The dielectric albedo table (nodes/kernels/energy.glsl): that it is the kernels' own quadrature,
// that its interpolation stays close to the albedo between nodes, and that the quadrature agrees
// with an independent integration over the hemisphere.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "graph/cpu/energy_table.h"
#include "graph/cpu/microsurface.h"
#include "graph/cpu/pcg32.h"
#include "graph/cpu_test_support.h"
#include "nodes/kernels/kernels.h"

namespace k = lamina::kernels;
namespace test = lamina::test;
using glm::vec3;

namespace {

const char* const kIncPath = LAMINA_SOURCE_DIR "/nodes/kernels/dielectric_albedo.inc";

// Measured with the table of nodes/kernels/dielectric_albedo.inc, with some room.
constexpr double kSmoothTolerance = 0.015;
// The table's E is raised to bound E between the nodes (graph/cpu/energy_table.h); where eta is at
// least kNearOne it falls below the quadrature by little and rises above it by more.
constexpr float kNearOne = 1.1f;
constexpr double kBelowTolerance = 0.01;
constexpr double kAboveTolerance = 0.08;
// Within kNearOne of 1 a grazing view's E climbs from 0 to nearly 1 over a step of eta far finer than
// the grid's (the Fresnel reflectance at grazing incidence), and under an index below 1 it climbs to
// 1 at the edge of the cone, which moves with eta between the nodes: the table is coarse there.
constexpr double kBelowToleranceNearOne = 0.1;
constexpr double kAboveToleranceNearOne = 0.4;
// How much more than the table's E + M a boundary's raised lobe may reflect between the nodes
// (measured, with some room): the boost's interpolation across eta and the slope, where M changes
// fast (rough boundaries), and, under an index below 1, across the moving edge of the cone.
constexpr double kRaisedOverTolerance = 0.005;
constexpr double kRaisedOverToleranceNearOne = 0.08;
constexpr double kRaisedOffTolerance = 0.01;
constexpr double kRaisedOffToleranceNearOne = 0.08;

// The integral of f(l) cos_l over the directions l above the cosine `cone` (0: the hemisphere) by the
// midpoint rule in (cos_l, phi) on a fine grid: independent of the normal sampling the table uses.
template <typename F>
double plain_integral(F f, double cone = 0.0) {
  const int n = 600;
  double sum = 0.0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < 2 * n; ++b) {
      double cos_l = (a + 0.5) / n, phi = M_PI * (b + 0.5) / n;
      if (cos_l <= cone) continue;
      double sin_l = std::sqrt(1.0 - cos_l * cos_l);
      sum += f(vec3(float(sin_l * std::cos(phi)), float(sin_l * std::sin(phi)), float(cos_l))) * cos_l;
    }
  }
  return sum * (1.0 / n) * (M_PI / n);
}

// A point of the table's domain, drawn at random: any view and slope, or (grazing) a view within 26
// degrees of the horizon and a slope m = y^3, crowding toward smooth boundaries as the grid does,
// where E curves most; where eta < 1 the view folded into the cone, where the composition reads
// the table.
// `range` is 0 where eta >= kNearOne, 1 between 1 and kNearOne, 2 below 1.
struct TablePoint {
  int distribution;
  int fresnel;
  float mu;
  float m;
  float eta;
  int range;
};
TablePoint draw_table_point(std::mt19937& rng, bool grazing) {
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  TablePoint p;
  p.distribution = int(rng() % 3u);
  p.fresnel = int(rng() % 2u);
  p.mu = 0.02f + 0.98f * uniform(rng);
  p.m = uniform(rng);
  if (grazing) {
    const float a = uniform(rng), y = uniform(rng);
    p.mu = 0.001f + 0.2f * a * a;
    p.m = y * y * y;
  }
  p.eta = std::exp2(2.0f * (2.0f * uniform(rng) - 1.0f));
  if (p.eta < 1.0f && (1.0f - p.mu * p.mu) >= p.eta * p.eta)
    p.mu = std::sqrt(1.0f - p.eta * p.eta * (1.0f - p.mu * p.mu));
  p.range = p.eta >= kNearOne ? 0 : p.eta >= 1.0f ? 1 : 2;
  return p;
}

}  // namespace

TEST_CASE(
    "the dielectric albedo table is the kernels' quadrature of the boundary's reflection and the microsurface's "
    "surplus") {
  if (std::getenv("LAMINA_UPDATE_TABLES")) {
    std::ofstream(kIncPath) << lamina::cpu::dielectric_albedo_inc(lamina::cpu::dielectric_albedo_table());
    MESSAGE("rewrote " << kIncPath << "; rebuild, so that the kernels read it");
    return;
  }
  // Entries drawn at random; the quadrature may round differently under another compiler, by a
  // unit or two of the table's 1/65535, and a random walk may take another turn, which moves M by
  // its noise (six standard errors allowed).
  std::mt19937 rng(0x7ab1e);
  const int draws = test::kSanitized ? 3 : 16;
  for (int d = 0; d < draws; ++d) {
    int combo = int(rng() % unsigned(k::LAMINA_ALBEDO_COMBOS));
    int i = int(rng() % unsigned(k::LAMINA_ALBEDO_ETAS));
    int j = int(rng() % unsigned(k::LAMINA_ALBEDO_SLOPES));
    int c = int(rng() % unsigned(k::LAMINA_ALBEDO_COSINES));
    int row = k::LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[combo] + i;
    CAPTURE(combo);
    CAPTURE(i);
    CAPTURE(j);
    CAPTURE(c);
    INFO("nodes/kernels/dielectric_albedo.inc is out of date: rerun with LAMINA_UPDATE_TABLES=1");
    const int single = int(k::lamina_albedo_texel(j * k::LAMINA_ALBEDO_COSINES + c, row));
    CHECK(std::abs(single - lamina::cpu::dielectric_albedo_bounded_entry(combo, i, j, c)) <= 2);
    const int multiple =
        int(k::lamina_albedo_texel(k::LAMINA_ALBEDO_MULTIPLE_COLUMN + j * k::LAMINA_ALBEDO_COSINES + c, row));
    const int expected = std::min(lamina::cpu::dielectric_multiple_table_entry(
                                      combo, i, j, c, lamina::cpu::dielectric_albedo_table_entry(combo, i, j, c)),
                                  65535 - single);
    const double noise =
        65535.0 * std::sqrt(std::max(double(expected), 1.0) / 65535.0 / lamina::cpu::kMultipleScatteringWalks);
    CHECK(std::abs(multiple - expected) <= 2.0 + 6.0 * noise);
    CHECK(single + multiple <= 65535);
    const int cone = int(k::lamina_albedo_texel(k::LAMINA_ALBEDO_CONE_COLUMN + j * k::LAMINA_ALBEDO_COSINES + c, row));
    CHECK(std::abs(cone - lamina::cpu::conductor_cone_table_entry(combo, i, j, c)) <= 2);
    // The boost is solved from the run's M as the table holds it.
    std::vector<int> run_of_m(static_cast<size_t>(k::LAMINA_ALBEDO_COSINES));
    for (int q = 0; q < k::LAMINA_ALBEDO_COSINES; ++q)
      run_of_m[size_t(q)] =
          int(k::lamina_albedo_texel(k::LAMINA_ALBEDO_MULTIPLE_COLUMN + j * k::LAMINA_ALBEDO_COSINES + q, row));
    const int boost =
        int(k::lamina_albedo_texel(k::LAMINA_ALBEDO_BOOST_COLUMN + j * k::LAMINA_ALBEDO_COSINES + c, row));
    CHECK(std::abs(boost - lamina::cpu::boundary_boost_run(combo, i, j, run_of_m.data())[size_t(c)]) <= 2);
    // The path ratios come from the same walks: a turn taken otherwise moves them by 1% or so.
    for (bool at_depth : {false, true}) {
      const int column =
          (at_depth ? k::LAMINA_ALBEDO_DEPTH_COLUMN : k::LAMINA_ALBEDO_PATH_COLUMN) + j * k::LAMINA_ALBEDO_COSINES + c;
      const int path = int(k::lamina_albedo_texel(column, row));
      const int fresh = lamina::cpu::transmitted_path_table_entry(combo, i, j, c, at_depth);
      CAPTURE(at_depth);
      CHECK(std::abs(path - fresh) <= 2 + fresh / 50);
    }
  }
}

TEST_CASE("a boundary's lobe raised by its boost reflects what the table says the boundary reflects, E + M") {
  // At the nodes the boost is solved so that the raised lobe reflects the node's E + M exactly;
  // between them both are interpolated. Points anywhere, and at grazing views, as for E alone.
  std::mt19937 rng(0xb0057);
  const int draws = test::kSanitized ? 4 : 160;
  // Per range of eta as above: the largest amount by which the raised lobe reflects more than the
  // table's E + M, and by which what the boost adds to the lobe differs from the table's M.
  double over[3] = {0.0, 0.0, 0.0}, off[3] = {0.0, 0.0, 0.0};
  std::string where;
  for (int d = 0; d < draws; ++d) {
    const auto [distribution, fresnel, mu, m, eta, range] = draw_table_point(rng, d % 2 == 1);
    float multiple = 0.0f;
    const double table =
        double(k::lamina_boundary_energy(distribution, fresnel, k::lamina_albedo_grid_xy(m, eta), mu, eta, multiple));
    const double raised = lamina::cpu::raised_albedo_quadrature(distribution, fresnel, mu, m, eta, 128);
    const double single = lamina::cpu::dielectric_albedo_quadrature(distribution, fresnel, mu, m, eta, 128);
    if (range == 0 && raised - table > over[0]) {
      std::ostringstream s;
      s << "distribution " << distribution << " fresnel " << fresnel << " mu " << mu << " m " << m << " eta " << eta
        << ": raised " << raised << " table " << table;
      where = s.str();
    }
    over[range] = std::max(over[range], raised - table);
    off[range] = std::max(off[range], std::abs(raised - single - double(multiple)));
  }
  MESSAGE("eta >= " << kNearOne << ": at most " << over[0] << " over E + M (" << where << "), the boost's part "
                    << off[0] << " off M; 1 <= eta < " << kNearOne << ": " << over[1] << " over, " << off[1]
                    << " off; eta < 1: " << over[2] << " over, " << off[2] << " off");
  CHECK(over[0] <= kRaisedOverTolerance);
  CHECK(off[0] <= kRaisedOffTolerance);
  CHECK(std::max(over[1], over[2]) <= kRaisedOverToleranceNearOne);
  CHECK(std::max(off[1], off[2]) <= kRaisedOffToleranceNearOne);
}

TEST_CASE("a smooth dielectric's albedo in the table is its Fresnel reflectance, and 0 where indices match") {
  double worst = 0.0;
  for (int distribution = 0; distribution < 3; ++distribution) {
    for (double eta : {0.5, 0.8, 1.0, 1.2, 1.33, 1.5, 1.7, 2.0, 2.4, 3.0}) {
      for (double mu : {0.02, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0}) {
        if (eta < 1.0 && 1.0 - mu * mu >= eta * eta) continue;  // beyond the cone: not read
        double table = double(k::lamina_dielectric_albedo(distribution, 0, float(mu), 0.0f, float(eta)));
        double error = std::abs(table - test::fresnel_reference(mu, eta));
        worst = std::max(worst, error);
        CAPTURE(distribution);
        CAPTURE(eta);
        CAPTURE(mu);
        // Linear interpolation between eta nodes 4^(1/8) apart of a curve that bends.
        CHECK(error <= kSmoothTolerance);
        if (eta == 1.0) CHECK(table == 0.0);
      }
    }
  }
  MESSAGE("largest difference from the Fresnel reflectance: " << worst);
}

TEST_CASE(
    "the interpolated dielectric albedo bounds the quadrature from above between the nodes, and stays close to it") {
  // Half the points anywhere, half at grazing views (draw_table_point), where E curves most.
  std::mt19937 rng(0xa1be);
  const int draws = test::kSanitized ? 8 : 600;
  // Per range of eta (>= kNearOne, between 1 and kNearOne, below 1): the largest amounts by which
  // the table falls below and rises above the quadrature.
  double below[3] = {0.0, 0.0, 0.0}, above[3] = {0.0, 0.0, 0.0};
  std::string where;
  for (int d = 0; d < draws; ++d) {
    const auto [distribution, fresnel, mu, m, eta, range] = draw_table_point(rng, d % 2 == 1);
    double exact = lamina::cpu::dielectric_albedo_quadrature(distribution, fresnel, mu, m, eta, 128);
    double table = double(k::lamina_dielectric_albedo(distribution, fresnel, mu, m, eta));
    if (range == 0 && exact - table > below[0]) {
      std::ostringstream s;
      s << "distribution " << distribution << " fresnel " << fresnel << " mu " << mu << " m " << m << " eta " << eta
        << ": table " << table << " quadrature " << exact;
      where = s.str();
    }
    below[range] = std::max(below[range], exact - table);
    above[range] = std::max(above[range], table - exact);
  }
  MESSAGE("eta >= " << kNearOne << ": at most " << below[0] << " below (" << where << "), " << above[0]
                    << " above; 1 <= eta < " << kNearOne << ": " << below[1] << " below, " << above[1]
                    << " above; eta < 1: " << below[2] << " below, " << above[2] << " above");
  CHECK(below[0] <= kBelowTolerance);
  CHECK(above[0] <= kAboveTolerance);
  CHECK(std::max(below[1], below[2]) <= kBelowToleranceNearOne);
  CHECK(std::max(above[1], above[2]) <= kAboveToleranceNearOne);
}

TEST_CASE("the albedo quadrature agrees with a plain integration over the hemisphere") {
  for (int distribution = 0; distribution < 3; ++distribution) {
    for (auto [mu_, m_, eta_] :
         {std::tuple{0.8f, 0.4f, 1.5f}, std::tuple{0.3f, 0.7f, 1.33f}, std::tuple{0.6f, 0.5f, 0.7f}}) {
      const float mu = mu_, m = m_, eta = eta_;  // clang 14 cannot capture a structured binding
      const vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
      const double plain =
          plain_integral([&](vec3 l) { return double(k::lamina_boundary_reflection(l, v, eta, distribution, 0, m)); });
      CAPTURE(distribution);
      CAPTURE(mu);
      CAPTURE(m);
      CAPTURE(eta);
      CHECK(lamina::cpu::dielectric_albedo_quadrature(distribution, 0, mu, m, eta, 192) ==
            doctest::Approx(plain).epsilon(2.0e-3).scale(0.0));
    }
  }
}

namespace {

// The mean of exp(-tau x), x = 1 / |cos|, over the directions below into which the boundary's
// transmission (lamina_boundary_eval, Walter et al. 2007, eq. 21) sends light from v, weighted by
// f |cos|; at tau = 0, the mean of x. The midpoint rule in (sqrt(cos), phi), which resolves the
// paths near the horizon: independent of the refraction through sampled normals of the table's
// quadrature.
double plain_transmitted_mean(int distribution, vec3 v, float m, float eta, double tau) {
  const int n = 400;
  double energy = 0.0, sum = 0.0;
  for (int a = 0; a < n; ++a) {
    const double s = (a + 0.5) / n, c = s * s, weight = 2.0 * s;
    for (int b = 0; b < 2 * n; ++b) {
      const double phi = M_PI * (b + 0.5) / n, sin_x = std::sqrt(1.0 - c * c);
      const vec3 x(float(sin_x * std::cos(phi)), float(sin_x * std::sin(phi)), float(-c));
      const double f = double(k::lamina_boundary_eval(v, x, eta, distribution, 0, m)) * c * weight;
      energy += f;
      sum += f * (tau > 0.0 ? std::exp(-tau / c) : 1.0 / c);
    }
  }
  return sum / energy;
}

}  // namespace

namespace {

// The mean of exp(-tau x) (tau > 0) or of x (tau = 0), x = 1 / |cos|, over the directions below in
// which walks over the microsurface from v leave it, weighted by the walks' weights.
double walked_transmitted_mean(int distribution, vec3 v, float m, float eta, double tau, int walks) {
  const lamina::cpu::MicrosurfaceBoundary boundary{eta, distribution, 0, m};
  lamina::cpu::Pcg32 rng(0x7a7, 0x11);
  double energy = 0.0, sum = 0.0;
  for (int w = 0; w < walks; ++w) {
    const lamina::cpu::MicrosurfaceSample s = lamina::cpu::microsurface_sample(boundary, v, rng);
    if (s.direction.z >= 0.0f) continue;
    const double x = 1.0 / double(-s.direction.z);
    energy += double(s.weight);
    sum += double(s.weight) * (tau > 0.0 ? std::exp(-tau * x) : x);
  }
  return sum / energy;
}

}  // namespace

TEST_CASE("the walks' transmitted paths agree with a plain integration of the boundary's lobe where it scatters once") {
  // Where light passes a boundary after one scattering event (steep views, gentle slopes), the
  // walks' path ratios (microsurface_statistics) are those of the single-scattering transmission
  // lobe, integrated over the directions below.
  for (int distribution = 0; distribution < 3; ++distribution) {
    for (auto [mu_, m_, eta_] :
         {std::tuple{0.5f, 0.1f, 1.45f}, std::tuple{0.9f, 0.2f, 1.33f}, std::tuple{0.8f, 0.15f, 0.8f}}) {
      const float mu = mu_, m = m_, eta = eta_;
      const vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
      const double x_s = 1.0 / double(k::lamina_cosine_below(mu, eta));
      const double depth = double(k::LAMINA_ALBEDO_PATH_DEPTH);
      const double plain_mean = x_s / plain_transmitted_mean(distribution, v, m, eta, 0.0);
      const double plain_depth = x_s * depth / -std::log(plain_transmitted_mean(distribution, v, m, eta, depth));
      const lamina::cpu::MicrosurfaceStatistics stats =
          lamina::cpu::microsurface_statistics(distribution, 0, mu, m, eta, 1 << 16, 99);
      CAPTURE(distribution);
      CAPTURE(mu);
      CAPTURE(m);
      CAPTURE(eta);
      CHECK(stats.path_ratio == doctest::Approx(plain_mean).epsilon(0.01).scale(0.0));
      CHECK(stats.depth_ratio == doctest::Approx(plain_depth).epsilon(0.01).scale(0.0));
    }
  }
}

TEST_CASE("the table's path ratios are the walks' between the nodes too") {
  // Off the nodes, where the composition reads them, at grazing views where they move fastest.
  for (int distribution = 0; distribution < 3; ++distribution) {
    for (auto [mu_, m_, eta_] : {std::tuple{0.03f, 0.3f, 1.45f}, std::tuple{0.17f, 0.25f, 1.6f},
                                 std::tuple{0.5f, 0.5f, 1.5f}, std::tuple{0.7f, 0.4f, 0.8f}}) {
      const float mu = mu_, m = m_, eta = eta_;
      const lamina::cpu::MicrosurfaceStatistics stats =
          lamina::cpu::microsurface_statistics(distribution, 0, mu, m, eta, 1 << 16, 5);
      const glm::vec2 table =
          k::lamina_boundary_path_ratios(distribution, 0, k::lamina_albedo_grid_xy(m, eta), mu, eta);
      CAPTURE(distribution);
      CAPTURE(mu);
      CAPTURE(m);
      CAPTURE(eta);
      CHECK(double(table.x) == doctest::Approx(stats.path_ratio).epsilon(0.03).scale(0.0));
      CHECK(double(table.y) == doctest::Approx(stats.depth_ratio).epsilon(0.03).scale(0.0));
    }
  }
}

TEST_CASE("a medium under a rough boundary lets through at most what the boundary's paths through it do, and nearly") {
  // lamina_rough_transmittance against the mean of exp(-tau x) over the walks' transmitted paths, at
  // grazing views where the paths spread most. Within the bound, the chord of the exponent is closest
  // at the depths the table holds (0 and LAMINA_ALBEDO_PATH_DEPTH) and furthest between and beyond.
  for (int distribution : {0, 2}) {
    for (auto [mu_, m_] :
         {std::tuple{0.0175f, 0.25f}, std::tuple{0.087f, 0.5f}, std::tuple{0.17f, 0.25f}, std::tuple{0.5f, 0.5f}}) {
      const float mu = mu_, m = m_, eta = 1.45f;
      const vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
      const glm::vec2 ratios =
          k::lamina_boundary_path_ratios(distribution, 0, k::lamina_albedo_grid_xy(m, eta), mu, eta);
      for (double tau : {0.05, 0.3, 0.5, 0.6, 1.2}) {
        const double truth = walked_transmitted_mean(distribution, v, m, eta, tau, 1 << 17);
        const double model =
            double(k::lamina_rough_transmittance(vec3(float(tau)), 1.0f, k::lamina_cosine_below(mu, eta), ratios).x);
        CAPTURE(distribution);
        CAPTURE(mu);
        CAPTURE(m);
        CAPTURE(tau);
        CAPTURE(truth);
        // The table's interpolation and the walks' noise may move it by a little either way.
        CHECK(model <= truth * 1.02);
        if (tau <= 0.6) CHECK(model >= truth * 0.9);
        if (tau > 0.6) CHECK(model >= truth * 0.6);
      }
    }
  }
}

TEST_CASE("the conductor cone quadrature agrees with a plain integration over the cone and the hemisphere") {
  // The conductor lobe with a Fresnel term of 1, over the exit cone of a boundary of index eta and
  // over the whole hemisphere (eta 1).
  for (int distribution = 0; distribution < 3; ++distribution) {
    for (auto [mu_, m_, eta_] :
         {std::tuple{0.8f, 0.3f, 1.5f}, std::tuple{0.5f, 0.6f, 1.7f}, std::tuple{0.6f, 0.4f, 1.0f}}) {
      const float mu = mu_, m = m_, eta = eta_;
      const float cone = eta > 1.0f ? std::sqrt(1.0f - 1.0f / (eta * eta)) : 0.0f;
      const vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
      // Schlick's term from F0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) = 1 - 4e-8 (n 1, k 10^4) is 1 at
      // every angle, to float precision.
      const double plain = plain_integral(
          [&](vec3 l) {
            return double(
                k::lamina_conductor_eval(l, v, vec3(1.0f), vec3(1.0e4f), vec3(1.0f), 0.0f, distribution, 1, m).x);
          },
          cone);
      CAPTURE(distribution);
      CAPTURE(mu);
      CAPTURE(m);
      CAPTURE(eta);
      CHECK(lamina::cpu::conductor_cone_quadrature(distribution, mu, m, cone, 192) ==
            doctest::Approx(plain).epsilon(3.0e-3).scale(0.0));
      // And the table, read as the composition reads it, within its interpolation.
      float whole = 0.0f, unused = 0.0f;
      const glm::vec2 xy = k::lamina_albedo_grid_xy(m, std::max(eta, 1.0f));
      CHECK(double(k::lamina_conductor_cone_share(distribution, xy, k::lamina_cone_etas(xy), mu, whole)) ==
            doctest::Approx(plain).epsilon(0.03).scale(0.0));
      // The whole hemisphere's share is the row eta = 1's.
      const glm::vec2 xy_1 = k::lamina_albedo_grid_xy(m, 1.0f);
      CHECK(whole == k::lamina_conductor_cone_share(distribution, xy_1, k::lamina_cone_etas(xy_1), mu, unused));
    }
  }
}
