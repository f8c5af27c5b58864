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

#include "graph/cpu/energy_table.h"
#include "graph/cpu_test_support.h"
#include "nodes/kernels/kernels.h"

namespace k = lamina::kernels;
namespace test = lamina::test;
using glm::vec3;

namespace {

const char* const kIncPath = LAMINA_SOURCE_DIR "/nodes/kernels/dielectric_albedo.inc";

// Measured with the table of nodes/kernels/dielectric_albedo.inc, with some room.
constexpr double kSmoothTolerance = 0.015;
constexpr double kInterpolationTolerance = 0.02;
// Under an index below 1 E climbs to 1 at the edge of the cone, and the cone's edge moves with eta
// between the nodes.
constexpr double kInterpolationToleranceBelowOne = 0.15;

}  // namespace

TEST_CASE("the dielectric albedo table is the kernels' quadrature of the boundary's reflection") {
  if (std::getenv("LAMINA_UPDATE_TABLES")) {
    std::ofstream(kIncPath) << lamina::cpu::dielectric_albedo_inc(lamina::cpu::dielectric_albedo_table());
    MESSAGE("rewrote " << kIncPath << "; rebuild, so that the kernels read it");
    return;
  }
  // Entries drawn at random; the quadrature may round differently under another compiler, by a
  // unit or two of the table's 1/65535.
  std::mt19937 rng(0x7ab1e);
  const int draws = test::kSanitized ? 4 : 24;
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
    CHECK(std::abs(int(k::lamina_albedo_texel(j * k::LAMINA_ALBEDO_COSINES + c, row)) -
                   lamina::cpu::dielectric_albedo_table_entry(combo, i, j, c)) <= 2);
  }
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

TEST_CASE("the interpolated dielectric albedo stays close to the quadrature between the nodes") {
  std::mt19937 rng(0xa1be);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const int draws = test::kSanitized ? 8 : 400;
  double worst = 0.0, worst_below_one = 0.0;
  std::string where;
  for (int d = 0; d < draws; ++d) {
    int distribution = int(rng() % 3u);
    int fresnel = int(rng() % 2u);
    float mu = 0.02f + 0.98f * uniform(rng);
    float m = uniform(rng);
    float eta = std::exp2(2.0f * (2.0f * uniform(rng) - 1.0f));
    // Where eta < 1 the composition reads E only inside the cone light can enter.
    if (eta < 1.0f && (1.0f - mu * mu) >= eta * eta) mu = std::sqrt(1.0f - eta * eta * (1.0f - mu * mu));
    double exact = lamina::cpu::dielectric_albedo_quadrature(distribution, fresnel, mu, m, eta, 128);
    double table = double(k::lamina_dielectric_albedo(distribution, fresnel, mu, m, eta));
    if (eta < 1.0f) {
      worst_below_one = std::max(worst_below_one, std::abs(table - exact));
      continue;
    }
    if (std::abs(table - exact) > worst) {
      worst = std::abs(table - exact);
      std::ostringstream s;
      s << "distribution " << distribution << " fresnel " << fresnel << " mu " << mu << " m " << m << " eta " << eta
        << ": table " << table << " quadrature " << exact;
      where = s.str();
    }
  }
  MESSAGE("largest interpolation error " << worst << " (" << where << "); where eta < 1: " << worst_below_one);
  CHECK(worst <= kInterpolationTolerance);
  CHECK(worst_below_one <= kInterpolationToleranceBelowOne);
}

TEST_CASE("the albedo quadrature agrees with a plain integration over the hemisphere") {
  // Midpoint rule in (cos_l, phi) on a fine grid: independent of the normal sampling the table uses.
  for (int distribution = 0; distribution < 3; ++distribution) {
    for (auto [mu_, m_, eta_] :
         {std::tuple{0.8f, 0.4f, 1.5f}, std::tuple{0.3f, 0.7f, 1.33f}, std::tuple{0.6f, 0.5f, 0.7f}}) {
      const float mu = mu_, m = m_, eta = eta_;  // clang 14 cannot capture a structured binding
      const vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
      const int n = 600;
      double sum = 0.0;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < 2 * n; ++b) {
          double cos_l = (a + 0.5) / n, phi = M_PI * (b + 0.5) / n;
          double sin_l = std::sqrt(1.0 - cos_l * cos_l);
          vec3 l(float(sin_l * std::cos(phi)), float(sin_l * std::sin(phi)), float(cos_l));
          sum += double(k::lamina_boundary_reflection(l, v, eta, distribution, 0, m)) * cos_l;
        }
      }
      double plain = sum * (1.0 / n) * (M_PI / n);
      CAPTURE(distribution);
      CAPTURE(mu);
      CAPTURE(m);
      CAPTURE(eta);
      CHECK(lamina::cpu::dielectric_albedo_quadrature(distribution, 0, mu, m, eta, 192) ==
            doctest::Approx(plain).epsilon(2.0e-3));
    }
  }
}
