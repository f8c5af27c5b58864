#include "graph/cpu/flake_slab.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nodes/kernels/kernels.h"

namespace lamina::cpu {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Gauss-Legendre nodes and weights of order n on [a, b], appended: Newton's iteration on the
// Legendre polynomial P_n from the usual cosine guesses; weights 2 / ((1 - z^2) P_n'(z)^2)
// (Abramowitz and Stegun 25.4.29), scaled to the interval.
void gauss_legendre(int n, double a, double b, std::vector<double>& x, std::vector<double>& w) {
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (double(i) + 0.75) / (double(n) + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p = 1.0, previous = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double older = previous;
        previous = p;
        p = ((2.0 * k - 1.0) * z * previous - (k - 1.0) * older) / k;
      }
      derivative = n * (z * p - previous) / (z * z - 1.0);
      const double step = p / derivative;
      z -= step;
      if (std::abs(step) < 1.0e-15) break;
    }
    x.push_back(0.5 * (a + b) + 0.5 * (b - a) * z);
    w.push_back((b - a) / ((1.0 - z * z) * derivative * derivative));
  }
}

// The boundary's reflectance at cosine c towards relative index eta (1 past the critical angle) and
// the flakes' orientation P(beta): the kernels' (nodes/kernels/fresnel.glsl, flakes.glsl).
double fresnel(double c, double eta) { return double(kernels::fresnel_dielectric(float(c), float(eta))); }
double orientation(const FlakeSlab& slab, double cos_beta) {
  return double(kernels::lamina_flake_orientation(slab.distribution, float(cos_beta), float(slab.flake_slope)));
}

// A flake's reflectance and straight transmittance for light at cosine c to its normal: the
// slab's constants, or a coated flake's film (Airy's sum at one wavelength, film.glsl, with the
// binder on both sides) and what it does not reflect.
double flake_reflectance(const FlakeSlab& slab, double c) {
  if (slab.film_ior <= 0.0) return slab.flake_reflectance;
  return double(kernels::lamina_film_channel(false, 0, float(c), float(slab.film_ior / slab.eta), glm::vec2(1.0f, 0.0f),
                                             float(slab.film_nm * slab.eta), float(slab.wavelength_nm)));
}
double flake_transmittance(const FlakeSlab& slab, double c) {
  return slab.film_ior <= 0.0 ? slab.flake_transmittance : 1.0 - flake_reflectance(slab, c);
}

// <|cos alpha| (1 - t_p(alpha))>(mu) of eq. 10: the flakes' mean projected area along a direction
// of cosine mu that does not pass light (Beckmann's orientations beyond tan beta = 6 m weigh under
// e^-36; the other laws' tails are integrated to the paint's plane).
double projected_area(double mu, const FlakeSlab& slab) {
  const double m = slab.flake_slope;
  std::vector<double> beta, weight;
  gauss_legendre(48, 0.0, slab.distribution == 0 ? std::min(0.5 * kPi, std::atan(6.0 * m)) : 0.5 * kPi, beta, weight);
  const int azimuths = 128;
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  double sum = 0.0, norm = 0.0;
  for (size_t b = 0; b < beta.size(); ++b) {
    const double p = orientation(slab, std::cos(beta[b])) * std::sin(beta[b]) * weight[b];
    double ring = 0.0;
    for (int a = 0; a < azimuths; ++a) {
      const double c =
          std::abs(std::cos(beta[b]) * mu + std::sin(beta[b]) * sin_theta * std::cos(2.0 * kPi * (a + 0.5) / azimuths));
      ring += c * (1.0 - flake_transmittance(slab, c));
    }
    sum += p * ring * (2.0 * kPi / azimuths);
    norm += p * 2.0 * kPi;
  }
  return sum / norm;
}

// (1 - e^-x) / x and (e^-a - e^-b) / (b - a): single scattering at a depth drawn through a
// sublayer, attenuated along both paths (reflected: x the two paths' depths; transmitted: a along
// the way in, b along the way out).
double reflected_depth(double x) { return x < 1.0e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x; }
double transmitted_depth(double a, double b) {
  if (std::abs(b - a) < 1.0e-9) return std::exp(-0.5 * (a + b));
  return (std::exp(-a) - std::exp(-b)) / (b - a);
}

// An operator of one cosine order: a delta part (the light that keeps its direction) and a
// kernel over the nodes, row = out, column = in. Applying it to radiance L is
// d_i L_i + sum_j k_ij w_j mu_j L_j.
struct Operator {
  std::vector<double> delta, kernel;
};

class Algebra {
 public:
  explicit Algebra(std::vector<double> measure) : measure_(std::move(measure)), n_(measure_.size()) {}

  size_t size() const { return n_; }

  Operator zero() const { return {std::vector<double>(n_, 0.0), std::vector<double>(n_ * n_, 0.0)}; }

  // A B: B applied first.
  Operator compose(const Operator& a, const Operator& b) const {
    Operator c = zero();
    for (size_t i = 0; i < n_; ++i) {
      c.delta[i] = a.delta[i] * b.delta[i];
      double* row = &c.kernel[i * n_];
      for (size_t j = 0; j < n_; ++j) row[j] = a.delta[i] * b.kernel[i * n_ + j] + a.kernel[i * n_ + j] * b.delta[j];
      for (size_t k = 0; k < n_; ++k) {
        const double aik = a.kernel[i * n_ + k] * measure_[k];
        if (aik == 0.0) continue;
        const double* brow = &b.kernel[k * n_];
        for (size_t j = 0; j < n_; ++j) row[j] += aik * brow[j];
      }
    }
    return c;
  }

  Operator add(Operator a, const Operator& b) const {
    for (size_t i = 0; i < n_; ++i) a.delta[i] += b.delta[i];
    for (size_t i = 0; i < n_ * n_; ++i) a.kernel[i] += b.kernel[i];
    return a;
  }

  // (1 - A)^-1 = 1 + A + A^2 + ...: delta 1 / (1 - a); kernel K from (1 - diag(a) - A W) K = A diag(x),
  // solved by LU with partial pivoting.
  Operator inverse_one_minus(const Operator& a) const {
    Operator x = zero();
    std::vector<double> m(n_ * n_);
    for (size_t i = 0; i < n_; ++i) {
      if (a.delta[i] >= 1.0) throw std::runtime_error("flake slab: an operator keeps all the light it is given");
      x.delta[i] = 1.0 / (1.0 - a.delta[i]);
    }
    for (size_t i = 0; i < n_; ++i)
      for (size_t j = 0; j < n_; ++j) {
        m[i * n_ + j] = (i == j ? 1.0 - a.delta[i] : 0.0) - a.kernel[i * n_ + j] * measure_[j];
        x.kernel[i * n_ + j] = a.kernel[i * n_ + j] * x.delta[j];
      }
    for (size_t c = 0; c < n_; ++c) {
      size_t pivot = c;
      for (size_t r = c + 1; r < n_; ++r)
        if (std::abs(m[r * n_ + c]) > std::abs(m[pivot * n_ + c])) pivot = r;
      if (pivot != c)
        for (size_t j = 0; j < n_; ++j) {
          std::swap(m[c * n_ + j], m[pivot * n_ + j]);
          std::swap(x.kernel[c * n_ + j], x.kernel[pivot * n_ + j]);
        }
      const double diagonal = m[c * n_ + c];
      for (size_t r = c + 1; r < n_; ++r) {
        const double f = m[r * n_ + c] / diagonal;
        if (f == 0.0) continue;
        for (size_t j = c; j < n_; ++j) m[r * n_ + j] -= f * m[c * n_ + j];
        for (size_t j = 0; j < n_; ++j) x.kernel[r * n_ + j] -= f * x.kernel[c * n_ + j];
      }
    }
    for (size_t c = n_; c-- > 0;) {
      for (size_t r = c + 1; r < n_; ++r) {
        const double f = m[c * n_ + r];
        if (f == 0.0) continue;
        for (size_t j = 0; j < n_; ++j) x.kernel[c * n_ + j] -= f * x.kernel[r * n_ + j];
      }
      for (size_t j = 0; j < n_; ++j) x.kernel[c * n_ + j] /= m[c * n_ + c];
    }
    return x;
  }

 private:
  std::vector<double> measure_;  // w_j mu_j
  size_t n_;
};

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("flake slab: " + what);
}

}  // namespace

FlakeSlabSolution::FlakeSlabSolution(const FlakeSlab& slab, std::vector<double> views, const FlakeSlabOptions& options)
    : eta_(slab.eta), views_(std::move(views)) {
  require(std::isfinite(slab.eta) && slab.eta >= 1.0 && slab.eta <= 4.0, "eta must lie in [1, 4]");
  require(std::isfinite(slab.coverage) && slab.coverage >= 0.0 && slab.coverage <= 20.0,
          "coverage must lie in [0, 20]");
  require(std::isfinite(slab.flake_slope) && slab.flake_slope >= 0.01 && slab.flake_slope <= 1.0,
          "flake_slope must lie in [0.01, 1]");
  require(slab.distribution >= 0 && slab.distribution <= 2, "distribution must be 0 (Beckmann), 1 (Blinn) or 2 (GGX)");
  require(slab.film_ior == 0.0 || (std::isfinite(slab.film_ior) && slab.film_ior >= 1.0 && slab.film_ior <= 4.0 &&
                                   std::isfinite(slab.film_nm) && slab.film_nm >= 0.0 && slab.wavelength_nm > 0.0),
          "a coated flake's film_ior must lie in [1, 4], its film_nm be >= 0 and its wavelength > 0");
  require(slab.flake_reflectance >= 0.0 && slab.flake_transmittance >= 0.0 &&
              slab.flake_reflectance + slab.flake_transmittance <= 1.0,
          "a flake's reflectance and transmittance must be >= 0 with a sum <= 1");
  require(std::isfinite(slab.binder_absorption) && slab.binder_absorption >= 0.0, "binder_absorption must be >= 0");
  require(slab.substrate_albedo >= 0.0 && slab.substrate_albedo <= 1.0, "substrate_albedo must lie in [0, 1]");
  require(options.nodes >= 2 && options.nodes <= 256 && options.modes >= 1 && options.modes <= 1024 &&
              options.azimuths >= 2 * options.modes && options.doublings >= 1 && options.doublings <= 40,
          "options out of range");
  for (double v : views_) require(v > 0.0 && v <= 1.0, "every view's cosine must lie in (0, 1]");

  // Nodes of cos theta in the binder, split at the critical angle, then the views' own.
  const double critical = std::sqrt(1.0 - 1.0 / (slab.eta * slab.eta));
  if (critical > 1.0e-6) gauss_legendre(options.nodes, 0.0, critical, mu_, weight_);
  gauss_legendre(options.nodes, critical, 1.0, mu_, weight_);
  for (double v : views_) {
    view_nodes_.push_back(mu_.size());
    mu_.push_back(std::sqrt(1.0 - (1.0 - v * v) / (slab.eta * slab.eta)));
    weight_.push_back(0.0);
  }
  const size_t n = mu_.size();
  std::vector<double> measure(n);
  for (size_t i = 0; i < n; ++i) measure[i] = weight_[i] * mu_[i];
  const Algebra algebra(measure);

  // The starting sublayer: its optical depth along each node (eq. 13's extinction: the binder's
  // absorption and the flakes' area that does not pass light, <1 - t_p> of eq. 10).
  const double part = std::ldexp(1.0, -options.doublings);
  const double coverage = slab.coverage * part, absorption = slab.binder_absorption * part;
  std::vector<double> depth(n);
  for (size_t i = 0; i < n; ++i) depth[i] = (absorption + coverage * projected_area(mu_[i], slab)) / mu_[i];

  // Each order's coefficient of P(beta) over the azimuth difference, for light reflected (out
  // going up) and transmitted (out going on down) by flakes: a flake reflects from direction in
  // to out when its normal is the half vector out - in, whose length is twice the cosine of the
  // angle of incidence on the flake (where a coated flake's reflectance is taken).
  const int modes = options.modes, azimuths = options.azimuths;
  std::vector<double> cosines(size_t(azimuths) * size_t(modes));
  for (int a = 0; a < azimuths; ++a)
    for (int m = 0; m < modes; ++m) cosines[size_t(a * modes + m)] = std::cos(m * 2.0 * kPi * a / azimuths);
  std::vector<std::vector<double>> reflected(size_t(modes), std::vector<double>(n * n, 0.0));
  std::vector<std::vector<double>> transmitted = reflected;
  const double dphi = 2.0 * kPi / azimuths;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) {
      const double sin_i = std::sqrt(std::max(0.0, 1.0 - mu_[i] * mu_[i]));
      const double sin_j = std::sqrt(std::max(0.0, 1.0 - mu_[j] * mu_[j]));
      for (int a = 0; a < azimuths; ++a) {
        const double phi = 2.0 * kPi * a / azimuths;
        // in = (sin_j, 0, -mu_j); out = (sin_i cos phi, sin_i sin phi, +-mu_i).
        const double hx = sin_i * std::cos(phi) - sin_j, hy = sin_i * std::sin(phi);
        for (int side = 0; side < 2; ++side) {
          const double hz = side == 0 ? mu_[i] + mu_[j] : mu_[j] - mu_[i];
          const double length = std::sqrt(hx * hx + hy * hy + hz * hz);
          if (length < 1.0e-12) continue;  // straight on: not a reflection
          const double p = orientation(slab, std::abs(hz) / length) * flake_reflectance(slab, 0.5 * length) * dphi;
          if (p == 0.0) continue;
          auto& target = side == 0 ? reflected : transmitted;
          for (int m = 0; m < modes; ++m) target[size_t(m)][i * n + j] += p * cosines[size_t(a * modes + m)];
        }
      }
    }

  // Fresnel reflection of the boundary from below, per node (1 past the critical angle).
  std::vector<double> inside(n);
  for (size_t i = 0; i < n; ++i) inside[i] = fresnel(mu_[i], 1.0 / slab.eta);

  x_.resize(size_t(modes));
  for (int m = 0; m < modes; ++m) {
    // Eq. 9 for the sublayer, each path's attenuation integrated over its depth.
    Operator r = algebra.zero(), t = algebra.zero();
    for (size_t i = 0; i < n; ++i) {
      t.delta[i] = std::exp(-depth[i]);
      for (size_t j = 0; j < n; ++j) {
        const double scale = coverage / (4.0 * mu_[i] * mu_[j]);
        r.kernel[i * n + j] = scale * reflected_depth(depth[i] + depth[j]) * reflected[size_t(m)][i * n + j];
        t.kernel[i * n + j] = scale * transmitted_depth(depth[j], depth[i]) * transmitted[size_t(m)][i * n + j];
      }
    }
    // Doubling (eq. 6): the slab is up-down symmetric, so one R and one T serve both sides.
    for (int d = 0; d < options.doublings; ++d) {
      const Operator bounce = algebra.inverse_one_minus(algebra.compose(r, r));
      const Operator bounce_t = algebra.compose(bounce, t);
      Operator r2 = algebra.add(r, algebra.compose(t, algebra.compose(r, bounce_t)));
      t = algebra.compose(t, bounce_t);
      r = std::move(r2);
    }
    // Adding the Lambertian substrate (eq. 16): its kernel r_s / pi is constant, order 0 only.
    Operator below = r;
    if (m == 0 && slab.substrate_albedo > 0.0) {
      Operator substrate = algebra.zero();
      std::fill(substrate.kernel.begin(), substrate.kernel.end(), 2.0 * slab.substrate_albedo);  // 2 pi r_s / pi
      const Operator bounce = algebra.inverse_one_minus(algebra.compose(r, substrate));
      below = algebra.add(r, algebra.compose(t, algebra.compose(substrate, algebra.compose(bounce, t))));
    }
    // The boundary's reflection from below sends light back down, again and again (eq. 17).
    Operator boundary = algebra.zero();
    boundary.delta = inside;
    const Operator x = algebra.compose(below, algebra.inverse_one_minus(algebra.compose(boundary, below)));
    x_[size_t(m)] = x.kernel;
  }
}

double FlakeSlabSolution::brdf(size_t i, size_t o, double phi) const {
  const size_t n = mu_.size(), vi = view_nodes_.at(i), vo = view_nodes_.at(o);
  double sum = 0.0;
  for (size_t m = 0; m < x_.size(); ++m)
    sum += x_[m][vo * n + vi] * std::cos(double(m) * phi) * (m == 0 ? 1.0 : 2.0) / (2.0 * kPi);
  // Into the binder and out again: each crossing transmits 1 - F; radiance gains eta^2 going in
  // and gives it back going out, and the solid angle does the same, leaving 1 / eta^2 (eq. 28).
  return (1.0 - mirror(i)) * (1.0 - mirror(o)) / (eta_ * eta_) * sum;
}

double FlakeSlabSolution::albedo(size_t i) const {
  const size_t n = mu_.size(), vi = view_nodes_.at(i);
  double sum = 0.0;
  for (size_t j = 0; j < n; ++j) sum += (1.0 - fresnel(mu_[j], 1.0 / eta_)) * x_[0][j * n + vi] * weight_[j] * mu_[j];
  return (1.0 - mirror(i)) * sum;
}

double FlakeSlabSolution::mirror(size_t i) const { return fresnel(views_.at(i), eta_); }

}  // namespace lamina::cpu
