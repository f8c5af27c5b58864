// The flake paint's full model (graph/cpu/flake_slab.h, doubling and adding) against what is known
// of it independently, and the fast model (nodes/kernels/flakes.glsl) against it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "graph/cpu/flake_slab.h"
#include "graph/cpu_test_support.h"
#include "nodes/kernels/kernels.h"

namespace lamina::flake_slab_test {
namespace {

using test::kPi;

// Fewer nodes and orders under the sanitisers, which look for memory errors, not precision.
cpu::FlakeSlabOptions options() {
  cpu::FlakeSlabOptions o;
  if (test::kSanitized) o = cpu::FlakeSlabOptions::coarse();
  return o;
}

// The smooth boundary's reflectance (Born and Wolf sec. 1.5.2), written out again.
double fresnel(double c, double eta) {
  const double s2 = (1.0 - c * c) / (eta * eta);
  if (s2 >= 1.0) return 1.0;
  const double t = std::sqrt(1.0 - s2);
  const double rs = (c - eta * t) / (c + eta * t), rp = (eta * c - t) / (eta * c + t);
  return 0.5 * (rs * rs + rp * rp);
}

// The boundary's hemispherical reflectance from inside, int F(mu) 2 mu d mu, by a fine midpoint sum.
double inside_reflectance(double eta) {
  double sum = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    sum += fresnel(mu, 1.0 / eta) * 2.0 * mu / n;
  }
  return sum;
}

const std::vector<double> kViews{1.0, std::cos(30.0 * kPi / 180.0), std::cos(60.0 * kPi / 180.0),
                                 std::cos(80.0 * kPi / 180.0)};

}  // namespace

TEST_CASE("flake slab: without flakes it is a Lambertian substrate under a smooth boundary, in closed form") {
  // Every bounce between the substrate and the boundary: f = (1 - F_i)(1 - F_o) r_s / (pi eta^2 (1 - r_s F_in)),
  // albedo (1 - F_i) r_s (1 - F_in) / (1 - r_s F_in), F_in the boundary's diffuse reflectance from inside.
  cpu::FlakeSlab slab;
  slab.coverage = 0.0;
  slab.substrate_albedo = 0.7;
  slab.binder_absorption = 0.0;
  const cpu::FlakeSlabSolution solution(slab, kViews, options());
  const double f_in = inside_reflectance(slab.eta);
  for (size_t i = 0; i < kViews.size(); ++i) {
    CAPTURE(i);
    const double fi = fresnel(kViews[i], slab.eta);
    CHECK(solution.mirror(i) == doctest::Approx(fi).epsilon(1e-6));  // the kernels' float Fresnel
    CHECK(solution.albedo(i) == doctest::Approx((1.0 - fi) * 0.7 * (1.0 - f_in) / (1.0 - 0.7 * f_in)).epsilon(2e-4));
    for (size_t o = 0; o < kViews.size(); ++o) {
      const double fo = fresnel(kViews[o], slab.eta);
      const double want = (1.0 - fi) * (1.0 - fo) * 0.7 / (kPi * slab.eta * slab.eta * (1.0 - 0.7 * f_in));
      CHECK(solution.brdf(i, o, 0.7) == doctest::Approx(want).epsilon(2e-4));
    }
  }
}

TEST_CASE("flake slab: lossless flakes over a white substrate return all the light (white furnace)") {
  // Plain flakes passing 0 and 0.6 (also with GGX's orientations, -0.5), and flakes coated with a
  // lossless film (reflecting 0.05 to 0.5 of the light by its angle, -1).
  for (double transmittance : {0.0, 0.6, -0.5, -1.0}) {
    cpu::FlakeSlab slab;
    slab.coverage = 1.5;
    slab.flake_slope = 0.25;
    slab.flake_transmittance = std::max(transmittance, 0.0);
    slab.flake_reflectance = 1.0 - slab.flake_transmittance;
    if (transmittance == -0.5) slab.distribution = 2;
    if (transmittance == -1.0) {
      slab.film_ior = 2.65;
      slab.film_nm = 160.0;
    }
    slab.substrate_albedo = 1.0;
    const cpu::FlakeSlabSolution solution(slab, kViews, options());
    double worst = 0.0;
    for (size_t i = 0; i < kViews.size(); ++i) {
      CAPTURE(transmittance);
      CAPTURE(i);
      CHECK(std::abs(solution.mirror(i) + solution.albedo(i) - 1.0) <= (test::kSanitized ? 2e-2 : 5e-4));
      worst = std::max(worst, std::abs(solution.mirror(i) + solution.albedo(i) - 1.0));
    }
    MESSAGE((transmittance == -1.0   ? std::string("coated flakes")
             : transmittance == -0.5 ? std::string("GGX flakes")
                                     : "t_p " + std::to_string(transmittance))
            << ": the furnace's largest departure from 1 is " << worst);
  }
}

TEST_CASE("flake slab: its BRDF is reciprocal") {
  cpu::FlakeSlab slab;
  slab.coverage = 0.8;
  slab.flake_reflectance = 0.6;
  slab.binder_absorption = 0.2;
  const cpu::FlakeSlabSolution solution(slab, kViews, options());
  for (size_t i = 0; i < kViews.size(); ++i)
    for (size_t o = 0; o < kViews.size(); ++o)
      for (double phi : {0.0, 1.0, kPi}) {
        CAPTURE(i);
        CAPTURE(o);
        CAPTURE(phi);
        CHECK(solution.brdf(i, o, phi) == doctest::Approx(solution.brdf(o, i, phi)).epsilon(1e-9));
      }
}

}  // namespace lamina::flake_slab_test

namespace lamina::flake_slab_test {
namespace {

namespace kn = kernels;

// A direction in the binder for light at cosine mu from air, at azimuth phi.
glm::vec3 refracted(double mu, double phi, double eta) {
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu)) / eta;
  return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(std::sqrt(1.0 - s * s)));
}

// The fast model seen from air (nodes/kernels/flakes.glsl behind the boundary's transmission),
// azimuths as FlakeSlabSolution::brdf's: light arrives from phi = pi.
// Coated flakes are folded into RGB at one wavelength a channel (645, 525, 445 nm): the slab's
// wavelength_nm must be the channel's.
double fast_brdf(const cpu::FlakeSlab& slab, double mu_i, double mu_o, double phi, int channel = 0) {
  const float coverage = float(slab.coverage), tp = float(slab.flake_transmittance);
  const float kappa = float(slab.binder_absorption), m = float(slab.flake_slope);
  const glm::vec3 rp(float(slab.flake_reflectance)), rs(float(slab.substrate_albedo));
  const glm::vec3 l = refracted(mu_i, kPi, slab.eta), v = refracted(mu_o, phi, slab.eta);
  kn::LaminaFlakes flakes = kn::lamina_flakes(coverage, rp, tp, 0, m);
  if (slab.film_ior > 0.0) {
    flakes.film = kn::LAMINA_FRESNEL_FILM_RGB;
    flakes.film_eta = glm::vec3(float(slab.film_ior / slab.eta));
    flakes.film_depth = float(slab.film_nm * slab.eta);
  }
  const glm::vec3 q =
      kn::lamina_flake_q_flakes(flakes, kappa) + kn::lamina_flake_q_boundary(flakes, kappa, float(slab.eta));
  const glm::vec3 inside =
      kn::lamina_flake_glitter(l, v, flakes, kappa) + kn::lamina_flake_shade(l, v, flakes, kappa, rs, q);
  return (1.0 - fresnel(mu_i, slab.eta)) * (1.0 - fresnel(mu_o, slab.eta)) / (slab.eta * slab.eta) *
         double(inside[channel]);
}

// Its albedo: a midpoint sum over the hemisphere, fine enough for a lobe of slope 0.15.
double fast_albedo(const cpu::FlakeSlab& slab, double mu_i, int channel = 0) {
  const int rows = 400, columns = 720;
  double sum = 0.0;
  for (int r = 0; r < rows; ++r) {
    const double mu = (r + 0.5) / rows;
    for (int c = 0; c < columns; ++c) sum += fast_brdf(slab, mu_i, mu, 2.0 * kPi * (c + 0.5) / columns, channel) * mu;
  }
  return sum * (1.0 / rows) * (2.0 * kPi / columns);
}

struct Paint {
  const char* name;
  cpu::FlakeSlab slab;
  // The fast model's largest relative errors against the full model (albedo, and the BRDF in the
  // mirror direction) over kViews, measured with a margin: where single scattering dominates
  // both within a few percent; dense flakes are darker by what multiple scattering adds.
  double albedo_error, peak_error;
};

cpu::FlakeSlab paint(double coverage, double slope, double rp, double tp, double kappa, double substrate) {
  cpu::FlakeSlab s;
  s.coverage = coverage;
  s.flake_slope = slope;
  s.flake_reflectance = rp;
  s.flake_transmittance = tp;
  s.binder_absorption = kappa;
  s.substrate_albedo = substrate;
  return s;
}

}  // namespace

TEST_CASE("flake slab: the fast model's glitter and shade against the full model, per paint") {
  // The sanitisers look for memory errors, which the tests above find in the full model; the
  // comparison needs its full precision.
  if (test::kSanitized) return;
  const Paint paints[] = {
      {"a few aluminium flakes over black", paint(0.02, 0.15, 0.9, 0.0, 0.0, 0.0), 0.02, 0.01},
      {"sparse aluminium flakes over black", paint(0.1, 0.15, 0.9, 0.0, 0.0, 0.05), 0.06, 0.04},
      {"metallic: dense aluminium flakes over grey", paint(0.8, 0.15, 0.9, 0.0, 0.05, 0.3), 0.32, 0.20},
      {"pearlescent white: translucent mica over white", paint(1.2, 0.15, 0.25, 0.7, 0.0, 0.85), 0.35, 0.18},
  };
  for (const Paint& p : paints) {
    CAPTURE(p.name);
    const cpu::FlakeSlabSolution full(p.slab, kViews, options());
    double worst_albedo = 0.0, worst_peak = 0.0;
    for (size_t i = 0; i < kViews.size(); ++i) {
      const double fast = fast_albedo(p.slab, kViews[i]);
      if (p.albedo_error > 0.1) CHECK(fast < full.albedo(i));  // what multiple scattering adds is missing
      worst_albedo = std::max(worst_albedo, std::abs(fast - full.albedo(i)) / full.albedo(i));
      // The mirror direction, where the glitter peaks.
      const double peak_full = full.brdf(i, i, 0.0), peak_fast = fast_brdf(p.slab, kViews[i], kViews[i], 0.0);
      worst_peak = std::max(worst_peak, std::abs(peak_fast - peak_full) / peak_full);
      std::printf("%s, view %.0f deg: albedo fast %.4f full %.4f; mirror direction fast %.4f full %.4f\n", p.name,
                  test::degrees(std::acos(kViews[i])), fast, full.albedo(i), peak_fast, peak_full);
    }
    MESSAGE(std::string(p.name) << ": the fast model's albedo within " << 100.0 * worst_albedo << "%, its peak within "
                                << 100.0 * worst_peak << "% of the full model's");
    CHECK(worst_albedo <= p.albedo_error);
    CHECK(worst_peak <= p.peak_error);
  }
}

TEST_CASE("flake slab: coated flakes, the fast model against the full model per channel (two_tone_pearl)") {
  if (test::kSanitized) return;  // as above: the comparison needs the full precision
  // examples/materials/two_tone_pearl.json's paint: 160 nm of titanium dioxide per flake, coverage
  // 1, 10 degrees (a Beckmann slope of tan 10 deg), over a grey base, each channel at its
  // wavelength (the node's "rgb" fold).
  const double wavelengths[3] = {645.0, 525.0, 445.0}, film_ior[3] = {2.55, 2.65, 2.78};
  double worst_albedo = 0.0, worst_peak = 0.0;
  for (int c = 0; c < 3; ++c) {
    cpu::FlakeSlab slab = paint(1.0, std::tan(10.0 * kPi / 180.0), 0.0, 0.0, 0.0, 0.5);
    slab.film_ior = film_ior[c];
    slab.film_nm = 160.0;
    slab.wavelength_nm = wavelengths[c];
    const cpu::FlakeSlabSolution full(slab, kViews, options());
    for (size_t i = 0; i < kViews.size(); ++i) {
      const double fast = fast_albedo(slab, kViews[i], c);
      CHECK(fast < full.albedo(i));  // what multiple scattering adds is missing
      worst_albedo = std::max(worst_albedo, std::abs(fast - full.albedo(i)) / full.albedo(i));
      const double peak_full = full.brdf(i, i, 0.0), peak_fast = fast_brdf(slab, kViews[i], kViews[i], 0.0, c);
      worst_peak = std::max(worst_peak, std::abs(peak_fast - peak_full) / peak_full);
      std::printf(
          "two_tone_pearl, %.0f nm, view %.0f deg: albedo fast %.4f full %.4f; mirror direction fast %.4f "
          "full %.4f\n",
          wavelengths[c], test::degrees(std::acos(kViews[i])), fast, full.albedo(i), peak_fast, peak_full);
    }
  }
  MESSAGE("two_tone_pearl: the fast model's albedo within " << 100.0 * worst_albedo << "%, its peak within "
                                                            << 100.0 * worst_peak << "% of the full model's");
  CHECK(worst_albedo <= 0.27);  // measured: 23.5%, darker, green at 80 degrees
  CHECK(worst_peak <= 0.15);    // measured: 12.6%
}

}  // namespace lamina::flake_slab_test
