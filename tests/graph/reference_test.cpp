// The reference solver (graph/cpu/reference.h) and the rough boundary it walks through
// (nodes/kernels/boundary.glsl), each checked on its own: the boundary against a double-precision
// transcription of Walter et al. 2007 and against its own sampler, the walks against closed forms,
// against each other and against the laws every BRDF obeys.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "graph/cpu/microsurface.h"
#include "graph/cpu/reference.h"
#include "graph/cpu_test_support.h"
#include "random_stacks.h"
#include "test_support.h"

namespace lamina {
namespace {

namespace k = kernels;
using glm::dvec3;
using glm::vec3;

// --- the boundary ---------------------------------------------------------------------------------

// A random direction on the whole sphere.
vec3 random_direction(std::mt19937_64& rng) {
  const double z = 1.0 - 2.0 * test::uniform(rng);
  return test::to_float(test::from_cosine(z, 2.0 * test::kPi * test::uniform(rng)));
}

struct BoundaryCase {
  int distribution;
  int fresnel;
  float m;
  float eta;
};

BoundaryCase random_boundary(std::mt19937_64& rng) {
  BoundaryCase c;
  c.distribution = int(test::uniform(rng) * 3.0);
  c.fresnel = int(test::uniform(rng) * 3.0);
  c.m = float(0.05 + 0.6 * test::uniform(rng));
  c.eta = float(test::uniform(rng) < 0.5 ? 1.1 + 1.4 * test::uniform(rng) : 1.0 / (1.1 + 1.4 * test::uniform(rng)));
  return c;
}

// Walter, Marschner, Li and Torrance 2007 in double precision, in the paper's own variables: i the
// incident direction, o the scattered one, eta_i and eta_o their media; exact Fresnel.
double walter_fresnel(double c, double eta_t_over_i) {
  const double g2 = eta_t_over_i * eta_t_over_i - 1.0 + c * c;  // eq. 22
  if (g2 < 0.0) return 1.0;
  const double g = std::sqrt(g2);
  const double a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

double walter_d(int distribution, double cos_m, double m) {
  if (cos_m <= 0.0) return 0.0;
  const double c2 = cos_m * cos_m, tan2 = (1.0 - c2) / c2;
  if (distribution == 0) return std::exp(-tan2 / (m * m)) / (test::kPi * m * m * c2 * c2);  // eq. 25
  if (distribution == 1) {
    const double e = 2.0 / (m * m) - 2.0;                       // lamina's Blinn exponent for slope m
    return (e + 2.0) / (2.0 * test::kPi) * std::pow(cos_m, e);  // eq. 30
  }
  const double a2 = m * m;
  return a2 / (test::kPi * c2 * c2 * (a2 + tan2) * (a2 + tan2));  // eq. 33
}

// Smith's G1: Beckmann's exact form under eq. 27 (with erf), GGX's eq. 34. (Blinn's has no closed
// form; its own test integrates it.)
double walter_g1(int distribution, double cos_v, double m) {
  const double tan_v = std::sqrt(1.0 - cos_v * cos_v) / cos_v;
  if (distribution == 2) return 2.0 / (1.0 + std::sqrt(1.0 + m * m * tan_v * tan_v));  // eq. 34
  const double a = 1.0 / (m * tan_v);
  return 2.0 / (1.0 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(test::kPi)));  // eq. 27
}

// G1 = cos / (the integral of max(0, w.n) D(n) over normals), by brute force: a midpoint grid in
// (theta_n, phi) in double precision.
double brute_force_g1(int distribution, double cos_v, double m) {
  const dvec3 w(std::sqrt(1.0 - cos_v * cos_v), 0.0, cos_v);
  const int cells_theta = 3000, cells_phi = 720;
  double integral = 0.0;
  for (int i = 0; i < cells_theta; ++i) {
    const double theta = (i + 0.5) * (test::kPi / 2.0) / cells_theta;
    const double d = walter_d(distribution, std::cos(theta), m) * std::sin(theta);
    if (d == 0.0) continue;
    for (int j = 0; j < cells_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * test::kPi / cells_phi;
      integral += std::max(glm::dot(w, test::spherical(theta, phi)), 0.0) * d;
    }
  }
  integral *= (test::kPi / 2.0 / cells_theta) * (2.0 * test::kPi / cells_phi);
  return cos_v / integral;
}

double walter_bsdf(dvec3 i, dvec3 o, const BoundaryCase& c) {
  const double eta_i = i.z > 0.0 ? 1.0 : c.eta, eta_o = o.z > 0.0 ? 1.0 : c.eta;
  const bool reflection = (i.z > 0.0) == (o.z > 0.0);
  dvec3 h = reflection ? glm::normalize(i + o) * (i.z > 0.0 ? 1.0 : -1.0)  // eq. 13, toward n
                       : -glm::normalize(eta_i * i + eta_o * o);           // eq. 16
  if (h.z < 0.0) h = -h;
  if (glm::dot(i, h) * i.z <= 0.0 || glm::dot(o, h) * o.z <= 0.0) return 0.0;
  const double f =
      walter_fresnel(std::abs(glm::dot(i, h)), eta_o == eta_i ? (i.z > 0.0 ? c.eta : 1.0 / c.eta) : eta_o / eta_i);
  const double d = walter_d(c.distribution, h.z, c.m);
  const double g = walter_g1(c.distribution, std::abs(i.z), c.m) * walter_g1(c.distribution, std::abs(o.z), c.m);
  if (reflection) return f * d * g / (4.0 * std::abs(i.z) * std::abs(o.z));  // eq. 20
  const double ih = glm::dot(i, h), oh = glm::dot(o, h);
  const double denom = eta_i * ih + eta_o * oh;
  return std::abs(ih) * std::abs(oh) / (std::abs(i.z) * std::abs(o.z)) * eta_o * eta_o * (1.0 - f) * d * g /
         (denom * denom);  // eq. 21
}

TEST_CASE("a rough boundary matches a double-precision transcription of Walter et al. 2007, eqs. 20 and 21") {
  std::mt19937_64 rng(11);
  int compared = 0;
  for (int n = 0; n < 20000; ++n) {
    BoundaryCase c = random_boundary(rng);
    c.fresnel = 0;  // the transcription's Fresnel term is the exact one (eq. 22)
    if (c.distribution == 1) c.distribution = 0;
    const vec3 l = random_direction(rng), e = random_direction(rng);
    if (std::abs(l.z) < 0.05f || std::abs(e.z) < 0.05f) continue;  // float V.H cancels at grazing
    const double expected = walter_bsdf(test::to_double(l), test::to_double(e), c);
    const double got = k::lamina_boundary_eval(l, e, c.eta, c.distribution, 0, c.m);
    if (expected < 1e-6 && got < 1e-6) continue;
    ++compared;
    INFO("distribution " << c.distribution << " m " << c.m << " eta " << c.eta << " l " << l.x << "," << l.y << ","
                         << l.z << " e " << e.x << "," << e.y << "," << e.z);
    // 2e-3 relative; below 1e-3 (float V.H and D lose digits there) 2e-6 absolute.
    CHECK(got == doctest::Approx(expected).epsilon(2e-3).scale(1e-3));
  }
  CHECK(compared > 2000);
}

TEST_CASE("Smith's masking of every distribution matches a brute-force integral of its projected area") {
  // Blinn's Lambda is a quadrature in the kernels; Beckmann's and GGX's are closed forms.
  for (int distribution : {0, 1, 2})
    for (double m : {0.1, 0.4, 1.0})
      for (double cos_v : {0.15, 0.5, 0.9}) {
        const double expected = brute_force_g1(distribution, cos_v, m);
        const double got = k::lamina_smith_g1(distribution, float(cos_v), float(m));
        INFO("distribution " << distribution << " m " << m << " cos " << cos_v);
        CHECK(got == doctest::Approx(expected).epsilon(3e-4).scale(0.0));
      }
}

TEST_CASE("a rough boundary obeys the radiance law of refraction: f(l, e) / n_e^2 = f(e, l) / n_l^2") {
  std::mt19937_64 rng(12);
  for (int n = 0; n < 20000; ++n) {
    const BoundaryCase c = random_boundary(rng);
    const vec3 l = random_direction(rng), e = random_direction(rng);
    const double n_l = l.z > 0.0f ? 1.0 : c.eta, n_e = e.z > 0.0f ? 1.0 : c.eta;
    const double forward = k::lamina_boundary_eval(l, e, c.eta, c.distribution, c.fresnel, c.m) / (n_e * n_e);
    const double backward = k::lamina_boundary_eval(e, l, c.eta, c.distribution, c.fresnel, c.m) / (n_l * n_l);
    // 2e-4 relative; below 0.02, where the float refraction's rounding moves a transmitted value by
    // up to 2% of itself, 4e-6 absolute.
    CHECK(forward == doctest::Approx(backward).epsilon(2e-4).scale(0.02));
    CHECK(forward >= 0.0);
  }
}

// For light arriving from x: the share the boundary scatters (the integral of f(x, y) |cos y|) and
// the integral of its sampling density, both by quadrature over the sphere; and by its sampler: the
// mean of f(x, y) |cos y| / pdf(y) and the share of draws that are kept.
TEST_CASE("a rough boundary's sampler draws its pdf, and no boundary scatters more light than it receives") {
  std::mt19937_64 rng(13);
  const int draws = 400000 / test::kSanitizerDivisor;
  for (int n = 0; n < 12; ++n) {
    BoundaryCase c = random_boundary(rng);
    c.m = float(0.2 + 0.4 * test::uniform(rng));  // quadrature needs lobes wider than its cells
    const vec3 x =
        test::to_float(test::from_cosine((test::uniform(rng) < 0.5 ? 1.0 : -1.0) * (0.15 + 0.85 * test::uniform(rng)),
                                         2.0 * test::kPi * test::uniform(rng)));
    // Midpoint quadrature in (cos theta, phi) over the sphere: d omega = d cos d phi.
    const int cells_z = 1600, cells_phi = 800;
    double scattered = 0.0, density = 0.0;
    for (int iz = 0; iz < cells_z; ++iz)
      for (int ip = 0; ip < cells_phi; ++ip) {
        const double z = -1.0 + (iz + 0.5) * 2.0 / cells_z, phi = (ip + 0.5) * 2.0 * test::kPi / cells_phi;
        const vec3 y = test::to_float(test::from_cosine(z, phi));
        const double cell = (2.0 / cells_z) * (2.0 * test::kPi / cells_phi);
        scattered += k::lamina_boundary_eval(x, y, c.eta, c.distribution, c.fresnel, c.m) * std::abs(y.z) * cell;
        density += k::lamina_boundary_pdf(y, x, c.eta, c.distribution, c.fresnel, c.m) * cell;
      }
    double sampled = 0.0, sampled_sq = 0.0;
    int kept = 0;
    for (int i = 0; i < draws; ++i) {
      const vec3 u(float(test::uniform(rng)), float(test::uniform(rng)), float(test::uniform(rng)));
      const vec3 y = k::lamina_boundary_sample(x, c.eta, c.distribution, c.fresnel, c.m, u);
      if (y == vec3(0.0f)) continue;
      const float p = k::lamina_boundary_pdf(y, x, c.eta, c.distribution, c.fresnel, c.m);
      REQUIRE(p > 0.0f);
      ++kept;
      const double w = k::lamina_boundary_eval(x, y, c.eta, c.distribution, c.fresnel, c.m) * std::abs(y.z) / p;
      sampled += w;
      sampled_sq += w * w;
    }
    const double mean = sampled / draws;
    const double error = std::sqrt(std::max(sampled_sq / draws - mean * mean, 0.0) / draws);
    INFO("distribution " << c.distribution << " fresnel " << c.fresnel << " m " << c.m << " eta " << c.eta << " x.z "
                         << x.z);
    CHECK(density == doctest::Approx(double(kept) / draws).epsilon(0.01).scale(0.0));
    CHECK(mean == doctest::Approx(scattered).epsilon(0.01 + 4.0 * error / scattered).scale(0.0));
    CHECK(scattered <= 1.0 + 0.005);
  }
}

// --- the microsurface ------------------------------------------------------------------------------

cpu::MicrosurfaceBoundary random_microsurface(std::mt19937_64& rng) {
  const BoundaryCase c = random_boundary(rng);
  return cpu::MicrosurfaceBoundary{c.eta, c.distribution, c.fresnel, c.m};
}

TEST_CASE("a microsurface boundary loses no light, from either side, whatever its roughness") {
  std::mt19937_64 rng(21);
  cpu::Pcg32 pcg(5, 6);
  const int draws = 100000 / test::kSanitizerDivisor;
  for (int n = 0; n < 24; ++n) {
    const cpu::MicrosurfaceBoundary b = random_microsurface(rng);
    const double z = (n % 2 == 0 ? 1.0 : -1.0) * (0.05 + 0.95 * test::uniform(rng));
    const vec3 x = test::to_float(test::from_cosine(z, 2.0 * test::kPi * test::uniform(rng)));
    double sum = 0.0, sum_sq = 0.0;
    for (int i = 0; i < draws; ++i) {
      const double w = cpu::microsurface_sample(b, x, pcg).weight;
      sum += w;
      sum_sq += w * w;
    }
    const double mean = sum / draws, error = std::sqrt(std::max(sum_sq / draws - mean * mean, 0.0) / draws);
    INFO("distribution " << b.distribution << " m " << b.m << " eta " << b.eta << " x.z " << x.z << ": " << mean
                         << " +- " << error);
    CHECK(std::abs(mean - 1.0) <= 4.0 * error + 1e-3);
  }
}

// Mean and standard error of a running sum.
struct Mean {
  double sum = 0.0, sum_sq = 0.0;
  int count = 0;
  void add(double x) {
    sum += x;
    sum_sq += x * x;
    ++count;
  }
  double value() const { return sum / count; }
  double error() const { return std::sqrt(std::max(sum_sq / count - value() * value(), 0.0) / count); }
};

bool agree(const Mean& a, const Mean& b, double scale_a = 1.0, double scale_b = 1.0) {
  const double error = std::hypot(a.error() * scale_a, b.error() * scale_b);
  return std::abs(a.value() * scale_a - b.value() * scale_b) <= 4.5 * error + 1e-6;
}

TEST_CASE("Beckmann's visible normals are drawn with their density max(0, w.n) D(n) / projected area") {
  // A chi-square test per case over (theta_n, phi_n) cells: 24 rings up to 5 slopes out and 16
  // sectors, the expected counts by a midpoint quadrature of lamina_visible_normal_density inside
  // each cell; w above the horizon and below it down to the cotangent (in the frame stretched to
  // slope 1) below which the walk stops drawing them.
  std::mt19937_64 rng(31);
  const int draws = 200000 / test::kSanitizerDivisor, rings = 24, sectors = 16, sub = 8;
  const std::vector<double> slopes{0.08, 0.45, 1.0};
  const std::vector<double> cotangents{40.0, 3.0, 0.5, 0.05, -0.7, -k::LAMINA_BECKMANN_LOWEST_COT};
  const double significance = test::sidak(0.01, int(slopes.size() * cotangents.size()));
  for (double m : slopes) {
    for (double c : cotangents) {
      const double phi_w = 2.0 * test::kPi * test::uniform(rng);
      const vec3 w = test::to_float(glm::normalize(dvec3(std::cos(phi_w), std::sin(phi_w), c * m)));
      const double theta_max = std::min(std::atan(5.0 * m), test::kPi / 2.0);
      std::vector<double> expected(size_t(rings * sectors), 0.0), observed(expected.size(), 0.0);
      for (int r = 0; r < rings; ++r)
        for (int s = 0; s < sectors; ++s)
          for (int a = 0; a < sub; ++a)
            for (int b = 0; b < sub; ++b) {
              const double theta = theta_max * (r + (a + 0.5) / sub) / rings;
              const double phi = 2.0 * test::kPi * (s + (b + 0.5) / sub) / sectors;
              const vec3 n = test::to_float(test::spherical(theta, phi));
              const double cell = std::sin(theta) * (theta_max / (rings * sub)) * (2.0 * test::kPi / (sectors * sub));
              expected[size_t(r * sectors + s)] += draws * cell * k::lamina_visible_normal_density(0, w, n, float(m));
            }
      for (int i = 0; i < draws; ++i) {
        const glm::vec2 u(float(test::uniform(rng)), float(test::uniform(rng)));
        const vec3 n = k::lamina_sample_beckmann_visible_normal(w, float(m), u);
        REQUIRE(std::abs(glm::length(n) - 1.0f) < 1e-5f);
        REQUIRE(glm::dot(w, n) > -1e-6f);
        const double theta = std::acos(std::clamp(double(n.z), -1.0, 1.0));
        double phi = std::atan2(double(n.y), double(n.x));
        if (phi < 0.0) phi += 2.0 * test::kPi;
        if (theta >= theta_max) continue;  // the tail beyond 5 slopes: under 1.4e-11 of the normals
        const int r = std::min(rings - 1, int(theta / theta_max * rings));
        const int s = std::min(sectors - 1, int(phi / (2.0 * test::kPi) * sectors));
        observed[size_t(r * sectors + s)] += 1.0;
      }
      const test::ChiSquareResult result = test::chi_square(observed, expected, draws, [&](size_t i) {
        return "ring " + std::to_string(i / sectors) + " sector " + std::to_string(i % sectors);
      });
      double total_expected = 0.0;
      for (double e : expected) total_expected += e;
      INFO("m " << m << " w.z " << w.z << " (expected counts sum to " << total_expected / draws
                << " of the draws): chi2 " << result.statistic << " dof " << result.dof << "\n"
                << result.worst_bins);
      CHECK(result.p_value >= significance);
    }
  }
}

TEST_CASE("a Beckmann microsurface seen from far below draws visible normals, weighed, and loses nothing") {
  // Below the lowest cotangent the phase function draws the normals seen from there and weighs
  // them by the ratio of the densities: every draw keeps the light on average (a facet wi cannot
  // see would lose it), whichever way the light is then reflected or refracted.
  std::mt19937_64 rng(37);
  const int draws = 200000 / test::kSanitizerDivisor;
  for (float m : {0.08f, 0.45f, 1.0f})
    for (double c : {-1.6, -2.0, -2.5})  // by -3.5 float cannot tell the area seen from there from 0
      for (float eta : {1.35f, 1.0f / 1.35f}) {
        const double phi_w = 2.0 * test::kPi * test::uniform(rng);
        const vec3 w = test::to_float(glm::normalize(dvec3(std::cos(phi_w), std::sin(phi_w), c * m)));
        REQUIRE(k::lamina_projected_area(0, w, m) > 0.0f);
        Mean kept;
        for (int i = 0; i < draws; ++i) {
          const vec3 u(float(test::uniform(rng)), float(test::uniform(rng)), float(test::uniform(rng)));
          float weight = 0.0f;
          bool refracted = false;
          k::lamina_phase_sample(w, eta, 0, 0, m, u, weight, refracted);
          kept.add(weight);
        }
        INFO("m " << m << " cot " << c << " eta " << eta << ": " << kept.value() << " +- " << kept.error());
        CHECK(std::abs(kept.value() - 1.0) <= 4.0 * kept.error() + 1e-4);
      }
}

TEST_CASE("light refracted at the microsurface's top height is masked going up as Lambda says, no more") {
  // A walk that meets the surface at the top height and refracts continues at the bottom of the
  // other side's heights. There C1(h) must stay above 0: light going up steeply under a smooth
  // boundary (Lambda near 0) escapes almost surely, and nothing divides 0 by 0 (a reference walk of
  // fabric returned NaN; at exactly -1, walks were trapped until the event limit lost them).
  const float bottom = -k::lamina_height_inverse_cdf(1.0f);
  CHECK(k::lamina_height_cdf(bottom) > 0.0f);
  for (int distribution : {0, 1, 2})
    for (float m : {0.05f, 0.36f, 1.0f})
      for (float z : {0.3f, 0.704f, 0.99f})
        for (float u : {0.0f, 0.25f, 0.5f, 0.999f}) {
          const vec3 w(std::sqrt(1.0f - z * z), 0.0f, z);
          const float h = k::lamina_next_height(distribution, w, bottom, m, u);
          CAPTURE(distribution);
          CAPTURE(m);
          CAPTURE(z);
          CAPTURE(u);
          CHECK(std::isfinite(h));
          // Lambda below 1e-4 (Beckmann and GGX at slope 0.05, 8 degrees from the normal): escapes
          // unless u falls in the last 0.2% (or is 0, which never escapes).
          if (distribution != 1 && m == 0.05f && z == 0.99f && u > 0.0f && u < 0.99f) CHECK(h == 2.0f);
        }
}

TEST_CASE("lamina_erf and lamina_erfinv agree with erf and with its inverse found in double") {
  for (int i = -400; i <= 400; ++i) {
    const double x = i / 100.0;
    CHECK(std::abs(double(k::lamina_erf(float(x))) - std::erf(x)) <= 3e-7);
  }
  // The inverse by Newton's method on std::erf, from y's whole range into its tails.
  auto inverse = [](double y) {
    double x = 0.0;
    for (int i = 0; i < 100; ++i) x -= (std::erf(x) - y) / (2.0 / std::sqrt(test::kPi) * std::exp(-x * x));
    return x;
  };
  std::vector<double> ys;
  for (int i = -999; i <= 999; ++i) ys.push_back(i / 1000.0);
  for (double y : {1e-7, 1e-3, 0.9999, 0.99999, 0.999999, 0.9999999}) {
    ys.push_back(y);
    ys.push_back(-y);
  }
  for (double y : ys) {
    CAPTURE(y);
    const double want = inverse(double(float(y)));
    CHECK(std::abs(double(k::lamina_erfinv(float(y))) - want) <= 3e-6 * std::abs(want));
  }
  CHECK(std::isfinite(k::lamina_erfinv(1.0f)));
  CHECK(std::isfinite(k::lamina_erfinv(-1.0f)));
}

TEST_CASE("a microsurface's estimate of f integrates to what its walks draw, and is reciprocal") {
  // The eval walk adds, at every event, the chance of leaving toward e; the sample walk leaves
  // where it leaves. Over the sphere, the first integrates to the second's distribution: checked
  // for the share reflected and the mean cosine of where light leaves, each side by Monte Carlo
  // with its own error (for the first, directions drawn half from the single-scattering boundary's
  // sampler and half uniformly over the sphere, weighed by the mixture's density).
  std::mt19937_64 rng(22);
  cpu::Pcg32 pcg(7, 8);
  const int count = 200000 / test::kSanitizerDivisor;
  for (int n = 0; n < 6; ++n) {
    const cpu::MicrosurfaceBoundary b = random_microsurface(rng);
    const vec3 x = test::to_float(test::from_cosine((n % 2 == 0 ? 1.0 : -1.0) * (0.1 + 0.9 * test::uniform(rng)),
                                                    2.0 * test::kPi * test::uniform(rng)));
    Mean reflected, mean_z, drawn_reflected, drawn_z;
    for (int i = 0; i < count; ++i) {
      const vec3 u(float(test::uniform(rng)), float(test::uniform(rng)), float(test::uniform(rng)));
      vec3 y = test::uniform(rng) < 0.5 ? k::lamina_boundary_sample(x, b.eta, b.distribution, b.fresnel, b.m, u)
                                        : random_direction(rng);
      // A lost draw counts 0: the sampler's own density integrates to less than 1 by its chance.
      const double mixture =
          0.5 * k::lamina_boundary_pdf(y, x, b.eta, b.distribution, b.fresnel, b.m) + 0.5 / (4.0 * test::kPi);
      const double density = y == vec3(0.0f) ? 0.0 : cpu::microsurface_eval(b, x, y, pcg) / mixture;
      reflected.add((y.z > 0.0f) == (x.z > 0.0f) ? density : 0.0);
      mean_z.add(density * y.z);
      const cpu::MicrosurfaceSample s = cpu::microsurface_sample(b, x, pcg);
      const bool same_side = s.direction != vec3(0.0f) && (s.direction.z > 0.0f) == (x.z > 0.0f);
      drawn_reflected.add(same_side ? s.weight : 0.0);
      drawn_z.add(s.weight * s.direction.z);
    }
    INFO("distribution " << b.distribution << " m " << b.m << " eta " << b.eta << " x.z " << x.z << ": reflected "
                         << reflected.value() << " +- " << reflected.error() << " drawn " << drawn_reflected.value()
                         << " +- " << drawn_reflected.error() << "; mean z " << mean_z.value() << " +- "
                         << mean_z.error() << " drawn " << drawn_z.value() << " +- " << drawn_z.error());
    CHECK(agree(reflected, drawn_reflected));
    CHECK(agree(mean_z, drawn_z));

    // Reciprocity of the estimate: f(l, e) / n_e^2 = f(e, l) / n_l^2.
    const vec3 l = x;
    const vec3 e = test::to_float(test::from_cosine((x.z > 0.0f ? -1.0 : 1.0) * 0.6, 1.0));
    Mean forward, backward;
    for (int i = 0; i < count / 4; ++i) {
      forward.add(cpu::microsurface_eval(b, l, e, pcg) / std::abs(e.z));
      backward.add(cpu::microsurface_eval(b, e, l, pcg) / std::abs(l.z));
    }
    const double n_l = l.z > 0.0f ? 1.0 : b.eta, n_e = e.z > 0.0f ? 1.0 : b.eta;
    INFO("f(l, e) " << forward.value() << " +- " << forward.error() << " f(e, l) " << backward.value() << " +- "
                    << backward.error());
    CHECK(agree(forward, backward, 1.0 / (n_e * n_e), 1.0 / (n_l * n_l)));
  }
}

// --- the walks ----------------------------------------------------------------------------------

std::string one_material(const std::string& nodes, const std::string& surface) {
  return R"({"format": 1, "materials": [{"name": "m", "surface": ")" + surface + R"(", "nodes": [)" + nodes + "]}]}";
}

std::string coat_over(const std::string& base_node, double roughness_deg, double ior = 1.5,
                      const std::string& medium = R"({"id": "clear", "type": "medium/clear"})") {
  return one_material(R"({"id": "coat", "type": "layer", "interface": "@iface", "medium": "@clear", "base": "@base"},
    {"id": "iface", "type": "interface/dielectric", "ior": )" +
                          std::to_string(ior) + R"(, "roughness_deg": )" + std::to_string(roughness_deg) + "}, " +
                          medium + ", " + base_node,
                      "@coat");
}

vec3 direction_at(double theta_deg, double phi_deg) {
  return test::to_float(test::spherical(test::radians(theta_deg), test::radians(phi_deg)));
}

bool within(dvec3 a, dvec3 b, dvec3 error, double sigmas, double slack = 0.0) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(a[c] - b[c]) > sigmas * error[c] + slack) return false;
  return true;
}

TEST_CASE("over a black base a smooth coat reflects Fresnel's share of the light") {
  const cpu::Evaluator e =
      test::evaluator_from_text(coat_over(R"({"id": "base", "type": "substrate/lambert", "albedo": [0, 0, 0]})", 0.5));
  const cpu::ShadingPoint point = e.bind({});
  for (double theta : {0.0, 45.0, 80.0}) {
    const cpu::ReferenceEstimate r = cpu::reference_albedo(point, direction_at(theta, 0.0), {20000, 1000, 1});
    const double fresnel = walter_fresnel(std::cos(test::radians(theta)), 1.5);
    INFO("theta " << theta << " albedo " << r.value.r << " +- " << r.std_error.r << " Fresnel " << fresnel);
    CHECK(within(r.value, dvec3(fresnel), r.std_error, 4.0, 2e-3));
  }
}

TEST_CASE("a lossless coat over a white Lambert base reflects all the light it receives, smooth or rough") {
  // The coat's microsurface scatters light as often as it takes and loses none (the multiple
  // scattering of Heitz et al. 2016); a single-scattering coat would reflect 0.85 at 20 degrees.
  for (const char* coat :
       {R"("roughness_deg": 1)", R"("roughness_deg": 20)", R"("roughness_deg": 20, "distribution": "ggx")"}) {
    const std::string text = one_material(
        std::string(R"({"id": "coat", "type": "layer", "interface": "@iface", "medium": "@clear", "base": "@base"},
          {"id": "iface", "type": "interface/dielectric", "ior": 1.5, )") +
            coat + R"(}, {"id": "clear", "type": "medium/clear"},
          {"id": "base", "type": "substrate/lambert", "albedo": [1, 1, 1]})",
        "@coat");
    const cpu::Evaluator e = test::evaluator_from_text(text);
    const cpu::ShadingPoint point = e.bind({});
    const cpu::ReferenceOptions options{40000 / test::kSanitizerDivisor, 1000, 3};
    for (double theta : {0.0, 40.0, 75.0}) {
      const cpu::ReferenceEstimate r = cpu::reference_albedo(point, direction_at(theta, 0.0), options);
      INFO(coat << " theta " << theta << " albedo " << r.value.r << " +- " << r.std_error.r);
      CHECK(within(r.value, dvec3(1.0), r.std_error, 4.0, 1e-3));
      CHECK(r.truncated_walks == 0);
    }
  }
}

TEST_CASE("clear layers between equal indices only attenuate: f is the base's times their transmittance") {
  // An absorbing layer of index 1 over a Lambert base: light crosses it once on the way in and once
  // out, and nothing reflects at its boundary.
  const cpu::Evaluator e = test::evaluator_from_text(
      coat_over(R"({"id": "base", "type": "substrate/lambert", "albedo": [0.8, 0.5, 0.2]})", 10.0, 1.0,
                R"({"id": "clear", "type": "medium/absorbing", "absorption": [0.1, 0.2, 0.4], "thickness": 2.0})"));
  const cpu::ShadingPoint point = e.bind({});
  const vec3 wi = direction_at(30.0, 0.0), wo = direction_at(60.0, 90.0);
  const cpu::ReferenceEstimate r = cpu::reference_eval(point, wi, wo, {500, 1000, 0});
  const auto& p = point.stack().params[0];
  const vec3 t = k::lamina_crossing_transmittance(p.absorption, p.thickness, wi.z) *
                 k::lamina_crossing_transmittance(p.absorption, p.thickness, wo.z);
  const dvec3 expected = dvec3(t) * dvec3(0.8, 0.5, 0.2) / test::kPi;
  for (int c = 0; c < 3; ++c) CHECK(r.value[c] == doctest::Approx(expected[c]).epsilon(1e-5).scale(0.0));
}

// Every example, and random valid stacks with nested layers and mixes.
struct Material {
  std::string name;
  cpu::Evaluator evaluator;
};

const std::vector<Material>& materials() {
  static const std::vector<Material> all = [] {
    std::vector<Material> list;
    for (const auto& file : test::example_files()) list.push_back({file.stem().string(), test::load_evaluator(file)});
    const nlohmann::json random = nlohmann::json::parse(test::RandomStacks(5).file(6));
    for (const auto& material : random.at("materials")) {
      const std::string text = nlohmann::json{{"format", random.at("format")}, {"materials", {material}}}.dump();
      list.push_back({material.at("name").get<std::string>(), test::evaluator_from_text(text)});
    }
    // The solver walks flat boundaries only: tilted stacks are refused (a test below), not compared.
    std::erase_if(list, [](const Material& m) { return cpu::tilted_entry(m.evaluator.bind({})) >= 0; });
    return list;
  }();
  return all;
}

TEST_CASE("the reference BRDF integrates to the reference albedo: two estimators, one answer") {
  // The albedo walk only follows light out; the BRDF estimator joins walks to wi through the top
  // boundary in two ways weighed against each other. Integrated over wi against the cosine, the
  // second must give the first, so a wrong weight or density shows here. wi is drawn half from the
  // layered model's sampler (whose lobes have the reference's shape, roughly) and half
  // cosine-weighted, weighed by the mixture's density. Materials with a smooth interface are left
  // out: their f is too narrow for a few hundred directions.
  std::mt19937_64 rng(14);
  const int directions = 512 / test::kSanitizerDivisor, walks = 256;
  int compared = 0;
  for (const Material& m : materials()) {
    const cpu::ShadingPoint point = m.evaluator.bind({});
    bool rough = true;
    for (int i = 0; i < point.stack().count; ++i)
      rough = rough && (point.stack().entries[i].kind != k::LAMINA_LAYER || point.stack().params[i].m >= 0.1f);
    if (!rough) continue;
    for (double theta : {20.0, 65.0}) {
      const vec3 wo = direction_at(theta, 0.0);
      dvec3 sum(0.0), sum_sq(0.0);
      for (int i = 0; i < directions; ++i) {
        const glm::vec2 u(float(test::uniform(rng)), float(test::uniform(rng)));
        const vec3 wi = test::uniform(rng) < 0.5
                            ? point.sample(wo, u, float(test::uniform(rng))).wi
                            : test::to_float(test::from_cosine(std::sqrt(1.0 - u.x), 2.0 * test::kPi * u.y));
        if (!(wi.z > 0.0f)) continue;  // a lost draw counts 0
        const double density = 0.5 * point.pdf(wi, wo) + 0.5 * wi.z / test::kPi;
        const dvec3 x = cpu::reference_eval(point, wi, wo, {walks, 1000, uint64_t(i)}).value * double(wi.z) / density;
        sum += x;
        sum_sq += x * x;
      }
      const dvec3 integral = sum / double(directions);
      const dvec3 error =
          glm::sqrt(glm::max(sum_sq / double(directions) - integral * integral, dvec3(0.0)) / double(directions));
      const cpu::ReferenceEstimate albedo = cpu::reference_albedo(point, wo, {100000, 1000, 0});
      INFO(m.name << " theta " << theta << " integral " << integral.r << " " << integral.g << " " << integral.b
                  << " +- " << error.r << " albedo " << albedo.value.r << " " << albedo.value.g << " " << albedo.value.b
                  << " +- " << albedo.std_error.r);
      CHECK(within(integral, albedo.value, glm::sqrt(error * error + albedo.std_error * albedo.std_error), 4.5, 1e-3));
      ++compared;
    }
  }
  CHECK(compared >= 8);
}

TEST_CASE("the reference never creates energy and is reciprocal within its error, for every example") {
  // The estimates run on every core and are checked here (test::parallel_for's jobs return their
  // findings).
  constexpr double kThetas[] = {0.0, 50.0, 85.0};
  const std::pair<vec3, vec3> pairs[] = {{direction_at(20.0, 0.0), direction_at(50.0, 120.0)},
                                         {direction_at(70.0, 30.0), direction_at(35.0, 250.0)}};
  struct Estimates {
    std::vector<cpu::ReferenceEstimate> albedo, forward, backward;
  };
  std::vector<Estimates> found(materials().size());
  test::parallel_for(materials().size(), [&](size_t index) {
    const cpu::ShadingPoint point = materials()[index].evaluator.bind({});
    for (double theta : kThetas)
      found[index].albedo.push_back(cpu::reference_albedo(point, direction_at(theta, 0.0), {20000, 1000, 0}));
    for (const auto& [wi, wo] : pairs) {
      found[index].forward.push_back(cpu::reference_eval(point, wi, wo, {20000, 1000, 0}));
      found[index].backward.push_back(cpu::reference_eval(point, wo, wi, {20000, 1000, 0}));
    }
  });
  for (size_t index = 0; index < materials().size(); ++index) {
    const std::string& name = materials()[index].name;
    for (size_t t = 0; t < std::size(kThetas); ++t) {
      const cpu::ReferenceEstimate& a = found[index].albedo[t];
      INFO(name << " theta " << kThetas[t] << " albedo " << a.value.r << " " << a.value.g << " " << a.value.b);
      CHECK(within(glm::min(a.value, dvec3(1.0)), a.value, a.std_error, 4.0, 1e-3));
      CHECK(glm::all(glm::greaterThanEqual(a.value, dvec3(0.0))));
    }
    for (size_t p = 0; p < std::size(pairs); ++p) {
      const cpu::ReferenceEstimate& forward = found[index].forward[p];
      const cpu::ReferenceEstimate& backward = found[index].backward[p];
      const dvec3 error = glm::sqrt(forward.std_error * forward.std_error + backward.std_error * backward.std_error);
      INFO(name << " f(wi, wo) " << forward.value.r << " " << forward.value.g << " " << forward.value.b << " f(wo, wi) "
                << backward.value.r << " " << backward.value.g << " " << backward.value.b);
      CHECK(within(forward.value, backward.value, error, 4.5, 1e-4 * (1.0 + forward.value.g)));
    }
  }
}

TEST_CASE("the reference gives the same digits for the same arguments, and its seed only changes the noise") {
  const cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples" / "materials" / "car_paint.json");
  const cpu::ShadingPoint point = e.bind({});
  const vec3 wi = direction_at(25.0, 10.0), wo = direction_at(40.0, 200.0);
  const cpu::ReferenceEstimate a = cpu::reference_eval(point, wi, wo, {5000, 1000, 7});
  const cpu::ReferenceEstimate b = cpu::reference_eval(point, wi, wo, {5000, 1000, 7});
  const cpu::ReferenceEstimate c = cpu::reference_eval(point, wi, wo, {5000, 1000, 8});
  CHECK(a.value == b.value);
  CHECK(a.std_error == b.std_error);
  CHECK(a.value != c.value);
  CHECK(within(a.value, c.value, glm::sqrt(2.0) * a.std_error, 4.5));
}

}  // namespace
}  // namespace lamina

TEST_CASE("the reference solver refuses a stack tilted by a normal input, and names the tilted entry") {
  auto material = [](const std::string& normal) {
    return test::evaluator_from_text(
        R"({"format": 1, "materials": [{"name": "m", "surface": "@coat", "nodes": [
             {"id": "coat", "type": "layer", "interface": "@top", "base": "@base"},
             {"id": "top", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 10},
             {"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5], "normal": )" +
        normal + "}]}]}");
  };
  const cpu::Evaluator flat = material("[0, 0, 1]");
  const cpu::Evaluator tilted = material("[0.3, 0, 0.95]");
  const vec3 wi = direction_at(30.0, 0.0), wo = direction_at(40.0, 180.0);
  CHECK(cpu::tilted_entry(flat.bind({})) == -1);
  CHECK_NOTHROW(cpu::reference_eval(flat.bind({}), wi, wo, {64, 1000, 0}));
  CHECK(cpu::tilted_entry(tilted.bind({})) == 1);
  CHECK_THROWS_AS(cpu::reference_eval(tilted.bind({}), wi, wo, {64, 1000, 0}), std::domain_error);
  CHECK_THROWS_AS(cpu::reference_albedo(tilted.bind({}), wo, {64, 1000, 0}), std::domain_error);
}
