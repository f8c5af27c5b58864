// The fallback fit's direction set (graph/gltf/hemisphere_quadrature.h): the GGX reflection density
// against GGX's D worked by hand and against integrals computed here independently in double
// precision, and the balance-heuristic weights against a known integral.
#include "graph/gltf/hemisphere_quadrature.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

using namespace lamina;
using glm::dvec3;
using glm::vec3;

namespace {

constexpr double kPi = std::numbers::pi;

vec3 view(double degrees) {
  double t = degrees * kPi / 180.0;
  return vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

// The integral of ggx_reflection_pdf over the upper hemisphere by the midpoint rule in spherical
// coordinates about the mirror direction of wo, where the lobe peaks: theta cells of pi / 6000 rad
// resolve lobes down to alpha = 0.04 (about 0.08 rad wide) with a hundred cells.
double integrate_pdf(float alpha, vec3 wo) {
  const dvec3 r = glm::normalize(dvec3(-wo.x, -wo.y, wo.z));
  const dvec3 t = glm::normalize(glm::cross(std::abs(r.z) < 0.9 ? dvec3(0, 0, 1) : dvec3(1, 0, 0), r));
  const dvec3 b = glm::cross(r, t);
  const int thetas = 6000, phis = 720;
  const double d_theta = kPi / thetas, d_phi = 2.0 * kPi / phis;
  double sum = 0.0;
  for (int i = 0; i < thetas; ++i) {
    const double theta = (i + 0.5) * d_theta;
    double ring = 0.0;
    for (int j = 0; j < phis; ++j) {
      const double phi = (j + 0.5) * d_phi;
      const dvec3 w = std::sin(theta) * (std::cos(phi) * t + std::sin(phi) * b) + std::cos(theta) * r;
      ring += double(gltf::ggx_reflection_pdf(alpha, vec3(w), wo));
    }
    sum += ring * std::sin(theta);
  }
  return sum * d_theta * d_phi;
}

// The probability that wo reflected about a GGX normal drawn with density D(h) cos(theta_h) leaves
// above the horizon: Walter et al. 2007's inversion (eqs. 35 and 36: tan^2 = alpha^2 u / (1 - u),
// phi = 2 pi v) on a stratified grid of cell centres, in double precision.
double share_reflected_above(double alpha, vec3 wo_float) {
  const dvec3 wo(wo_float);
  const int n = 1500;
  int above = 0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    const double tan2 = alpha * alpha * u / (1.0 - u);
    const double cos_h = 1.0 / std::sqrt(1.0 + tan2), sin_h = std::sqrt(tan2) * cos_h;
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / n;
      const dvec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      if ((2.0 * glm::dot(wo, h) * h - wo).z > 0.0) ++above;
    }
  }
  return double(above) / (double(n) * n);
}

}  // namespace

TEST_CASE("ggx_reflection_pdf is GGX's D(h) cos(theta_h) / (4 wo.h), D worked by hand") {
  const vec3 n(0.0f, 0.0f, 1.0f);
  // wi = wo = n: h = n, D = 1 / (pi alpha^2), cos(theta_h) = wo.h = 1. alpha = 0.25: 1 / (4 pi / 16).
  CHECK(double(gltf::ggx_reflection_pdf(0.25f, n, n)) == doctest::Approx(4.0 / kPi).epsilon(1e-6).scale(0.0));
  // wo = n, wi 60 degrees off it: h is 30 degrees off, cos(theta_h) = wo.h, so the pdf is D / 4 with
  // D = alpha^2 / (pi (cos^2 (alpha^2 - 1) + 1)^2) (Walter et al. 2007, eq. 33). alpha = 0.5:
  // 0.25 / (pi (0.75 * -0.75 + 1)^2) = 0.25 / (pi * 0.4375^2).
  const vec3 wi60 = view(60.0);
  CHECK(double(gltf::ggx_reflection_pdf(0.5f, wi60, n)) ==
        doctest::Approx(0.25 / (kPi * 0.4375 * 0.4375) / 4.0).epsilon(1e-5).scale(0.0));
  // Below the horizon on either side: no density.
  CHECK(gltf::ggx_reflection_pdf(0.5f, vec3(wi60.x, 0.0f, -wi60.z), n) == 0.0f);
  CHECK(gltf::ggx_reflection_pdf(0.5f, n, vec3(wi60.x, 0.0f, -wi60.z)) == 0.0f);
}

TEST_CASE("ggx_reflection_pdf integrates over the hemisphere to the share of reflections that stay above it") {
  // At normal incidence a reflection stays above the horizon when theta_h < 45 degrees, i.e.
  // tan^2 < 1, i.e. u < 1 / (1 + alpha^2) in Walter et al.'s inversion: that share exactly.
  for (float alpha : {0.04f, 0.15f, 0.5f, 1.0f}) {
    CAPTURE(alpha);
    CHECK(integrate_pdf(alpha, vec3(0.0f, 0.0f, 1.0f)) ==
          doctest::Approx(1.0 / (1.0 + alpha * alpha)).epsilon(1e-3).scale(0.0));
  }
  // Off the normal, against the share counted over a fine grid of drawn normals.
  for (double degrees : {45.0, 72.0}) {
    for (float alpha : {0.04f, 0.15f, 0.5f}) {
      CAPTURE(degrees);
      CAPTURE(alpha);
      const vec3 wo = view(degrees);
      CHECK(integrate_pdf(alpha, wo) == doctest::Approx(share_reflected_above(alpha, wo)).epsilon(2e-3).scale(0.0));
    }
  }
}

TEST_CASE("hemisphere_quadrature's weights integrate the cosine over the hemisphere to pi") {
  // sum of weights = sum cos / (count * mixture pdf), an estimate of the integral of cos, pi, which
  // holds only when every strategy's density is the density its directions are drawn with.
  const std::array<float, 5> alphas{0.0015f, 0.008f, 0.04f, 0.15f, 0.5f};
  for (double degrees : {0.0, 25.0, 60.0, 80.0}) {
    CAPTURE(degrees);
    const std::vector<gltf::WeightedDirection> set = gltf::hemisphere_quadrature(view(degrees), alphas, 1024);
    CHECK(set.size() == (alphas.size() + 1) * 1024);
    double sum = 0.0;
    for (const gltf::WeightedDirection& d : set) {
      CHECK(d.weight >= 0.0f);
      CHECK((d.weight > 0.0f) == (d.wi.z > 0.0f));
      sum += double(d.weight);
    }
    CHECK(sum == doctest::Approx(kPi).epsilon(2e-3).scale(0.0));
  }
  CHECK(gltf::hemisphere_quadrature(vec3(0.0f, 0.6f, -0.8f), alphas, 16).empty());
}
