// Helpers for the statistical tests of the CPU evaluator: loading the examples, directions in
// double precision, the chi-square machinery of pbrt's BSDF tests (pooling of small bins, p-value
// from the regularised incomplete gamma function) and adaptive quadrature of a density over a
// spherical (theta, phi) grid.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/load.h"
#include "graph/parallel.h"

namespace lamina::test {

// Under ASan + UBSan (3-5x slower) statistical tests divide their sample counts by this and skip
// some cross-checks.
#ifdef LAMINA_SANITIZED
inline constexpr bool kSanitized = true;
inline constexpr int kSanitizerDivisor = 8;
#else
inline constexpr bool kSanitized = false;
inline constexpr int kSanitizerDivisor = 1;
#endif

inline constexpr double kPi = std::numbers::pi;

// The unpolarised Fresnel reflectance of a smooth dielectric of relative index eta, in double, written
// apart from the kernels (Born and Wolf, Principles of Optics, sec. 1.5.2); 1 under total reflection.
inline double fresnel_reference(double cos_i, double eta) {
  double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  double cos_t = std::sqrt(1.0 - sin2_t);
  double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// The same for a boundary to a complex relative index eta (a metal; Born and Wolf sec. 14.2): cos_t
// from Snell's law in complex arithmetic, then the mean of |r_s|^2 and |r_p|^2. Real eta below 1 past
// the critical angle gives |r| = 1.
inline double fresnel_reference(double cos_i, std::complex<double> eta) {
  using C = std::complex<double>;
  double sin2_i = 1.0 - cos_i * cos_i;
  C cos_t = std::sqrt(C(1.0) - sin2_i / (eta * eta));
  C r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  C r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

inline double radians(double degrees) { return degrees * kPi / 180.0; }
inline double degrees(double radians) { return radians * 180.0 / kPi; }

inline Program load_program(const std::filesystem::path& file) {
  CheckedFile checked = check_file(file);
  REQUIRE_MESSAGE(checked.ok(), file.string());
  REQUIRE(checked.graphs.size() == 1);
  REQUIRE(checked.graphs[0].has_value());
  return compile(*checked.graphs[0], file.string());
}

inline cpu::Evaluator load_evaluator(const std::filesystem::path& file) { return cpu::Evaluator(load_program(file)); }

// As above, composing the stack in `model` (LAMINA_MODEL_*) whatever the file names, as the
// command line's --model does.
inline cpu::Evaluator load_evaluator(const std::filesystem::path& file, int model) {
  Program program = load_program(file);
  program.model = model;
  return cpu::Evaluator(std::move(program));
}

inline cpu::Evaluator evaluator_from_text(const std::string& text) {
  CheckedFile checked = check_text(text, "inline.json");
  REQUIRE(checked.ok());
  REQUIRE(checked.graphs[0].has_value());
  return cpu::Evaluator(compile(*checked.graphs[0], "inline.json"));
}

// --- random numbers that do not depend on the standard library's distributions ----------------

// Uniform in (0, 1) with 53 random bits; std::mt19937_64's output is fixed by the standard.
inline double uniform(std::mt19937_64& rng) { return (double(rng() >> 11) + 0.5) * 0x1.0p-53; }

// --- directions ------------------------------------------------------------------------------

inline glm::dvec3 spherical(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// A direction with the given cosine and azimuth.
inline glm::dvec3 from_cosine(double cos_theta, double phi) {
  double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

inline glm::vec3 to_float(const glm::dvec3& w) { return glm::vec3(float(w.x), float(w.y), float(w.z)); }
inline glm::dvec3 to_double(const glm::vec3& w) { return glm::dvec3(double(w.x), double(w.y), double(w.z)); }

// Ideal mirror direction about the macro normal (the peak of every microfacet lobe of a stack:
// Snell's law keeps the azimuth, so a mirror reflection below any layer leaves as the mirror above).
inline glm::dvec3 mirror(const glm::dvec3& w) { return {-w.x, -w.y, w.z}; }

inline double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  // atan2 of |a x b| and a.b is accurate for tiny angles, unlike acos.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// An orthonormal frame (t, b, n) around n.
struct Frame {
  glm::dvec3 t, b, n;
  explicit Frame(const glm::dvec3& normal) : n(glm::normalize(normal)) {
    glm::dvec3 helper = std::abs(n.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
    t = glm::normalize(glm::cross(helper, n));
    b = glm::cross(n, t);
  }
  Frame() : t(1.0, 0.0, 0.0), b(0.0, 1.0, 0.0), n(0.0, 0.0, 1.0) {}
  glm::dvec3 direction(double theta, double phi) const {
    glm::dvec3 s = spherical(theta, phi);
    return s.x * t + s.y * b + s.z * n;
  }
  // (theta, phi) of w in this frame, phi in [0, 2 pi).
  std::pair<double, double> angles(const glm::dvec3& w) const {
    double x = glm::dot(w, t), y = glm::dot(w, b), z = glm::dot(w, n);
    double phi = std::atan2(y, x);
    if (phi < 0.0) phi += 2.0 * kPi;
    if (phi >= 2.0 * kPi) phi = 0.0;
    return {std::atan2(std::sqrt(x * x + y * y), z), phi};
  }
};

// --- chi-square ------------------------------------------------------------------------------

// Regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a) (Numerical Recipes,
// 3rd ed., sec. 6.2: the series for P when x < a + 1, else the continued fraction for Q evaluated
// with the modified Lentz method).
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  const double eps = 1.0e-15;
  if (x < a + 1.0) {
    // P(a, x) = e^-x x^a / Gamma(a) * sum_n x^n / (a (a+1) ... (a+n)), NR eq. 6.2.5.
    double ap = a, term = 1.0 / a, sum = term;
    for (int n = 0; n < 1000000; ++n) {
      ap += 1.0;
      term *= x / ap;
      sum += term;
      if (std::abs(term) < std::abs(sum) * eps) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefactor));
  }
  // Q(a, x) = e^-x x^a / Gamma(a) * 1/(x+1-a- 1(1-a)/(x+3-a- 2(2-a)/(x+5-a- ...))), NR eq. 6.2.7.
  const double tiny = std::numeric_limits<double>::min() / eps;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000000; ++i) {
    double an = -double(i) * (double(i) - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < eps) break;
  }
  return std::exp(log_prefactor) * h;
}

// P(X >= chi2) for a chi-square variable with `dof` degrees of freedom.
inline double chi_square_p_value(double chi2, int dof) {
  if (dof <= 0) return 1.0;
  return gamma_q(0.5 * double(dof), 0.5 * chi2);
}

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  bool impossible_samples = false;  // samples in a bin of zero expected count
  std::string worst_bins;           // the bins contributing most, for failure messages
};

// pbrt's chi-square test (pbrt-v4 src/pbrt/bsdfs_test.cpp, Chi2Test): bins sorted by expected
// count, those below `min_expected` pooled until the pool reaches it; all parameters known, so the degrees
// of freedom are the bins used minus 1. `names` label the bins for the failure dump.
inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected,
                                  double sample_count, const std::function<std::string(size_t)>& names,
                                  double min_expected = 5.0) {
  ChiSquareResult r;
  std::vector<size_t> order(observed.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double pooled_observed = 0.0, pooled_expected = 0.0;
  std::vector<std::pair<double, size_t>> contributions;
  for (size_t index : order) {
    if (expected[index] <= 0.0) {
      if (observed[index] > sample_count * 1.0e-5) {
        r.impossible_samples = true;
        contributions.push_back({std::numeric_limits<double>::infinity(), index});
      }
    } else if (expected[index] < min_expected || (pooled_expected > 0.0 && pooled_expected < min_expected)) {
      pooled_observed += observed[index];
      pooled_expected += expected[index];
    } else {
      double diff = observed[index] - expected[index];
      double term = diff * diff / expected[index];
      r.statistic += term;
      contributions.push_back({term, index});
      ++r.dof;
    }
  }
  if (pooled_expected > 0.0 || pooled_observed > 0.0) {
    double diff = pooled_observed - pooled_expected;
    r.statistic += diff * diff / std::max(pooled_expected, 1.0e-300);
    ++r.dof;
  }
  r.dof -= 1;
  // pbrt rejects, too, when too few bins remain to test anything.
  r.p_value = (r.impossible_samples || r.dof <= 0) ? 0.0 : chi_square_p_value(r.statistic, r.dof);
  std::sort(contributions.begin(), contributions.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = 0; i < std::min<size_t>(contributions.size(), 12); ++i) {
    size_t index = contributions[i].second;
    r.worst_bins += "  " + names(index) + ": observed " + std::to_string(observed[index]) + ", expected " +
                    std::to_string(expected[index]) + ", (o-e)^2/e " + std::to_string(contributions[i].first) + "\n";
  }
  r.worst_bins += "  pooled small bins: observed " + std::to_string(pooled_observed) + ", expected " +
                  std::to_string(pooled_expected) + "\n";
  return r;
}

// Per-test significance for `tests` independent tests at overall significance `alpha` (Sidak).
inline double sidak(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / double(tests)); }

// --- adaptive quadrature over spherical cells ------------------------------------------------

// Integrates a density over cells [theta0, theta1] x [phi0, phi1] ("bins") of a Frame's
// spherical coordinates, by globally adaptive quadrature. A cell is estimated by the midpoint rule
// on 3 x 3 sub-cells, each weighted by its exact solid angle (cos theta0 - cos theta1) dphi; its
// error estimate is the difference between that and the sum of its pieces' estimates (a split
// is in theta, in phi or in both, whichever keeps the pieces roughly square, so that cells at the
// pole do not multiply in phi). The cell with the largest error estimate is split until the sum of
// the error estimates is below the bin's tolerance, first splitting every cell that lies next to a
// seed direction (a known narrow peak, which midpoints could miss entirely) and is larger than
// `seed_resolution`. Cells below `min_size` are not split: the pdf of a microfacet lobe folded at
// the horizon has an integrable 1/distance spike at the mirror direction (microfacets seen edge-on
// reflect wo to -wo, which folds onto the mirror direction), where a float pdf is noise and the
// probability within 1e-5 rad is far below one sample; there, too, the error estimates shrink only
// like the cells, so a bin stops after `max_splits` splits (its error is then a few counts, against
// a Poisson noise of about 100). A bin's tolerance is in expected counts of `sample_count` samples: 0.05, 5%
// of their Poisson noise, or 1e-3 of them (in the narrowest lobes a float pdf is a staircase, as
// cos_h near 1 has few float values, which no refinement resolves); even if every bin were off by
// 5% of its noise, the chi-square statistic would grow by only 0.25% of its degrees of freedom.
class SphericalQuadrature {
 public:
  using Density = std::function<double(const glm::dvec3&)>;

  SphericalQuadrature(Density density, Frame frame, std::vector<glm::dvec3> seeds, double sample_count)
      : density_(std::move(density)), frame_(frame), seeds_(std::move(seeds)), sample_count_(sample_count) {}

  double integrate(double theta0, double theta1, double phi0, double phi1) {
    std::vector<Node> cells;
    Cell root{theta0, theta1, phi0, phi1};
    cells.push_back(assess(root, rule(root)));
    for (int splits = 0; splits < max_splits; ++splits) {
      double total = 0.0, error = 0.0;
      size_t worst = 0;
      for (size_t i = 0; i < cells.size(); ++i) {
        total += cells[i].fine;
        error += cells[i].error;
        if (cells[i].error > cells[worst].error) worst = i;
      }
      double counts = sample_count_ * std::abs(total);
      double tolerance = std::max({0.05, 0.05 * std::sqrt(counts), 1.0e-3 * counts}) / sample_count_;
      if (error <= tolerance) break;
      Node node = cells[worst];
      cells[worst] = cells.back();
      cells.pop_back();
      for (int i = 0; i < node.count; ++i) cells.push_back(assess(node.pieces[i], node.estimates[i]));
    }
    double total = 0.0;
    for (const Node& n : cells) total += n.fine;
    return total;
  }

  long evaluations() const { return evaluations_; }
  double seed_resolution = 2.0e-5;  // radians
  double min_size = 1.0e-5;         // radians: smaller cells are not split
  int max_splits = 400;             // per bin

 private:
  static constexpr int kSub = 3;
  struct Cell {
    double theta0, theta1, phi0, phi1;
    double theta_extent() const { return theta1 - theta0; }
    double phi_extent() const { return std::sin(std::min(theta1, 0.5 * kPi)) * (phi1 - phi0); }
  };
  struct Node {
    Cell pieces[4];
    double estimates[4];
    int count = 0;
    double fine = 0.0;
    double error = 0.0;  // infinite for a cell next to a seed
  };

  double rule(const Cell& c) {
    double dtheta = (c.theta1 - c.theta0) / kSub, dphi = (c.phi1 - c.phi0) / kSub;
    double sum = 0.0;
    for (int i = 0; i < kSub; ++i) {
      double a = c.theta0 + dtheta * i, b = a + dtheta;
      double solid = (std::cos(a) - std::cos(b)) * dphi;
      double theta = 0.5 * (a + b);
      for (int j = 0; j < kSub; ++j) {
        double phi = c.phi0 + dphi * (j + 0.5);
        sum += density_(frame_.direction(theta, phi)) * solid;
        ++evaluations_;
      }
    }
    return sum;
  }

  bool near_seed(const Cell& c) const {
    double radius = 0.5 * std::hypot(c.theta_extent(), c.phi_extent());
    if (radius < seed_resolution) return false;
    glm::dvec3 centre = frame_.direction(0.5 * (c.theta0 + c.theta1), 0.5 * (c.phi0 + c.phi1));
    for (const glm::dvec3& seed : seeds_)
      if (angle_between(centre, seed) < 2.0 * radius) return true;
    return false;
  }

  // Splits a cell whose own estimate is `coarse` and estimates the pieces.
  Node assess(const Cell& c, double coarse) {
    Node n;
    bool split_theta = c.phi_extent() < 2.0 * c.theta_extent();
    bool split_phi = c.theta_extent() < 2.0 * c.phi_extent();
    double tm = 0.5 * (c.theta0 + c.theta1), pm = 0.5 * (c.phi0 + c.phi1);
    if (split_theta && split_phi) {
      n.pieces[n.count++] = {c.theta0, tm, c.phi0, pm};
      n.pieces[n.count++] = {tm, c.theta1, c.phi0, pm};
      n.pieces[n.count++] = {c.theta0, tm, pm, c.phi1};
      n.pieces[n.count++] = {tm, c.theta1, pm, c.phi1};
    } else if (split_theta) {
      n.pieces[n.count++] = {c.theta0, tm, c.phi0, c.phi1};
      n.pieces[n.count++] = {tm, c.theta1, c.phi0, c.phi1};
    } else {
      n.pieces[n.count++] = {c.theta0, c.theta1, c.phi0, pm};
      n.pieces[n.count++] = {c.theta0, c.theta1, pm, c.phi1};
    }
    for (int i = 0; i < n.count; ++i) n.fine += n.estimates[i] = rule(n.pieces[i]);
    if (near_seed(c))
      n.error = std::numeric_limits<double>::infinity();
    else if (0.5 * std::hypot(c.theta_extent(), c.phi_extent()) > min_size)
      n.error = std::abs(n.fine - coarse);
    return n;
  }

  Density density_;
  Frame frame_;
  std::vector<glm::dvec3> seeds_;
  double sample_count_;
  long evaluations_ = 0;
};

// Runs job(i) for i in [0, count) on a few threads. Jobs must not use doctest assertions: they
// return their findings, which the calling thread checks.
using lamina::parallel_for;

}  // namespace lamina::test
