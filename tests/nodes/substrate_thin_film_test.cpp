// substrate/thin_film: the film's reflectance (nodes/kernels/film.glsl) against values computed
// independently: Airy's sum against the characteristic matrix of a stratified medium (Born and
// Wolf, Principles of Optics, sec. 1.6.2), the spectral fold against a brute-force integral of
// that reflectance over the channels' responses, the limits a film must reach, and the glTF
// KHR_materials_iridescence extension's published formula on the same parameters.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>

#include "graph/gltf/pbr_fit.h"
#include "nodes/kernels/kernels.h"

namespace k = lamina::kernels;
namespace gltf = lamina::gltf;
using glm::vec3;

namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// One film between the medium above (index 1) and a base of complex index `base`, by the
// characteristic matrix of the film (Born and Wolf, sec. 1.6.2, eqs. 24-25 and 35 with p = n cos
// for s light and q = cos / n for p light), averaged over the two polarisations.
double matrix_reflectance(double cos_i, double film, cd base, double thickness_nm, double lambda_nm) {
  const double sin2 = 1.0 - cos_i * cos_i;
  const cd cf = std::sqrt(cd(1.0 - sin2 / (film * film)));
  const cd cb = std::sqrt(cd(1.0) - sin2 / (base * base));
  const cd beta = 2.0 * kPi / lambda_nm * film * thickness_nm * cf;
  double sum = 0.0;
  for (int pol = 0; pol < 2; ++pol) {
    const cd p1 = cd(cos_i);  // the medium above has index 1: n cos = cos / n
    const cd pf = pol == 0 ? film * cf : cf / film;
    const cd pb = pol == 0 ? base * cb : cb / base;
    const cd m11 = std::cos(beta), m12 = -cd(0, 1) * std::sin(beta) / pf;
    const cd m21 = -cd(0, 1) * pf * std::sin(beta), m22 = std::cos(beta);
    const cd a = (m11 + m12 * pb) * p1, b = m21 + m22 * pb;
    sum += 0.5 * std::norm((a - b) / (a + b));
  }
  return sum;
}

// The incoherent sum of the film's reflections, which a thick film's colour fades to: per
// polarisation R12 + (1 - R12)^2 R23 / (1 - R12 R23), with the boundaries' reflectances from the
// Fresnel formulae (Born and Wolf, sec. 1.5.2).
double incoherent_reflectance(double cos_i, double film, cd base) {
  const double sin2 = 1.0 - cos_i * cos_i;
  const double cf = std::sqrt(1.0 - sin2 / (film * film));
  const cd cb = std::sqrt(cd(1.0) - sin2 / (base * base));
  const cd n = base / film;
  const double r12[2] = {std::norm((cos_i - film * cf) / (cos_i + film * cf)),
                         std::norm((film * cos_i - cf) / (film * cos_i + cf))};
  const double r23[2] = {std::norm((cf - n * (cb)) / (cf + n * cb)), std::norm((n * cf - cb) / (n * cf + cb))};
  double sum = 0.0;
  for (int pol = 0; pol < 2; ++pol)
    sum += 0.5 * (r12[pol] + (1.0 - r12[pol]) * (1.0 - r12[pol]) * r23[pol] / (1.0 - r12[pol] * r23[pol]));
  return sum;
}

// The channels' responses as film.glsl defines them (Belcour and Barla 2017's Gaussian fits of the
// CIE 1931 functions in wavenumber nu, per nm, then linear Rec. 709): lobes of integral A, centre mu
// and Fourier variance v, that is Gaussians of variance 2 v.
struct Lobe {
  double area, centre, variance;
  int xyz;
};
constexpr std::array<Lobe, 4> kLobes{{{0.846402, 1.6810e-3, 4.3278e-9, 0},
                                      {1.0, 1.7953e-3, 9.3046e-9, 1},
                                      {1.000900, 2.2084e-3, 6.6121e-9, 2},
                                      {0.153834, 2.2399e-3, 4.5282e-9, 0}}};
constexpr double kRgbOfXyz[3][3] = {
    {3.2404542, -1.5371385, -0.4985314}, {-0.9692660, 1.8760108, 0.0415560}, {0.0556434, -0.2040259, 1.0572252}};

double response(int channel, double nu) {
  double xyz[3] = {0.0, 0.0, 0.0};
  for (const Lobe& l : kLobes)
    xyz[l.xyz] +=
        l.area / std::sqrt(4.0 * kPi * l.variance) * std::exp(-(nu - l.centre) * (nu - l.centre) / (4.0 * l.variance));
  return kRgbOfXyz[channel][0] * xyz[0] + kRgbOfXyz[channel][1] * xyz[1] + kRgbOfXyz[channel][2] * xyz[2];
}

// A channel's reflectance under white light: the matrix reflectance integrated over the channel's
// response by the midpoint rule over nu in [0.4e-3, 3.6e-3] per nm (every lobe within 9 standard
// deviations), divided by the response's own integral, clamped to [0, 1] as the kernel clamps.
double integrated_reflectance(int channel, double cos_i, double film, cd base, double thickness_nm) {
  const int steps = 40000;
  const double lo = 0.4e-3, hi = 3.6e-3, step = (hi - lo) / steps;
  double num = 0.0, den = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double nu = lo + (i + 0.5) * step;
    const double w = response(channel, nu);
    num += w * matrix_reflectance(cos_i, film, base, thickness_nm, 1.0 / nu);
    den += w;
  }
  return std::clamp(num / den, 0.0, 1.0);
}

// The gold of the course's metal foil slide, one channel at a time.
const vec3 kGoldN(0.1f, 0.42f, 1.56f), kGoldK(3.8f, 2.5f, 1.9f);

vec3 film_rgb(int mode, float cos_i, vec3 film, vec3 n, vec3 kk, float thickness) {
  return k::lamina_fresnel_film(mode, cos_i, film, n, kk, thickness);
}

}  // namespace

TEST_CASE(
    "thin film: the RGB form is Airy's sum, equal to the film's characteristic matrix at each channel's wavelength") {
  const double lambdas[3] = {645.0, 525.0, 445.0};
  struct Base {
    vec3 n, k;
  };
  // Gold; a dielectric below the film's index; one above it (which turns the phase of the second
  // reflection); a film over a base of its own index (no second boundary).
  const Base bases[] = {
      {kGoldN, kGoldK}, {vec3(1.33f), vec3(0.0f)}, {vec3(2.4f), vec3(0.0f)}, {vec3(1.45f), vec3(0.0f)}};
  for (const Base& b : bases)
    for (float film : {1.45f, 2.2f})
      for (float thickness : {0.0f, 90.0f, 310.0f, 1200.0f})
        for (float cos_i : {1.0f, 0.8f, 0.45f, 0.1f}) {
          CAPTURE(film);
          CAPTURE(thickness);
          CAPTURE(cos_i);
          const vec3 got = film_rgb(k::LAMINA_FRESNEL_FILM_RGB, cos_i, vec3(film), b.n, b.k, thickness);
          for (int c = 0; c < 3; ++c) {
            const double want = matrix_reflectance(cos_i, film, cd(b.n[c], b.k[c]), thickness, lambdas[c]);
            CHECK(std::abs(double(got[c]) - want) < 2e-5);
          }
        }
}

TEST_CASE("thin film: the spectral form is the film's reflectance averaged over each channel's response") {
  // Against a brute-force integral of the characteristic matrix's reflectance over wavenumber. The
  // kernel averages four orders of the Fourier series and takes the rest at the channel's wavelength.
  struct Case {
    float film;
    vec3 n, k;
    float cos_i;
  };
  const Case cases[] = {{1.4f, kGoldN, kGoldK, 1.0f},
                        {1.4f, kGoldN, kGoldK, 0.3f},
                        {1.33f, vec3(1.0f), vec3(0.0f), 0.9f},
                        {2.5f, vec3(3.5f, 2.9f, 2.1f), vec3(4.3f, 4.2f, 3.9f), 0.7f},
                        {1.47f, vec3(1.33f), vec3(0.0f), 0.5f}};
  double worst = 0.0;
  for (const Case& s : cases)
    for (float thickness : {0.0f, 120.0f, 350.0f, 800.0f, 3000.0f}) {
      CAPTURE(s.film);
      CAPTURE(s.cos_i);
      CAPTURE(thickness);
      const vec3 got = film_rgb(k::LAMINA_FRESNEL_FILM_SPECTRAL, s.cos_i, vec3(s.film), s.n, s.k, thickness);
      for (int c = 0; c < 3; ++c) {
        const double want = integrated_reflectance(c, s.cos_i, s.film, cd(s.n[c], s.k[c]), thickness);
        CAPTURE(c);
        CHECK(std::abs(double(got[c]) - want) < 1e-3);
        worst = std::max(worst, std::abs(double(got[c]) - want));
      }
    }
  MESSAGE("largest difference from the integral: " << worst);
}

TEST_CASE("thin film: a film of no thickness or of the medium's own index is the bare base") {
  for (float cos_i : {1.0f, 0.7f, 0.3f, 0.05f}) {
    CAPTURE(cos_i);
    const vec3 bare = k::fresnel_conductor(cos_i, kGoldN, kGoldK);
    for (int mode : {k::LAMINA_FRESNEL_FILM_RGB, k::LAMINA_FRESNEL_FILM_SPECTRAL}) {
      CAPTURE(mode);
      // Both are the exact sum then; what is left is float rounding in the complex arithmetic.
      const float tol = 2e-5f;
      const vec3 thin = film_rgb(mode, cos_i, vec3(1.6f), kGoldN, kGoldK, 0.0f);
      const vec3 matched = film_rgb(mode, cos_i, vec3(1.0f), kGoldN, kGoldK, 400.0f);
      for (int c = 0; c < 3; ++c) {
        CHECK(std::abs(thin[c] - bare[c]) < tol);
        CHECK(std::abs(matched[c] - bare[c]) < tol);
      }
    }
  }
}

TEST_CASE(
    "thin film: a thick film's spectral colour fades to the incoherent sum of its reflections, where RGB samples "
    "alias") {
  double rgb_spread = 0.0;
  for (float cos_i : {1.0f, 0.6f}) {
    const vec3 got = film_rgb(k::LAMINA_FRESNEL_FILM_SPECTRAL, cos_i, vec3(1.5f), vec3(1.0f), vec3(0.0f), 9000.0f);
    const double want = incoherent_reflectance(cos_i, 1.5, cd(1.0));
    for (int c = 0; c < 3; ++c) CHECK(std::abs(double(got[c]) - want) < 2e-3);
    // The three point samples of the same film swing between the extremes of its fringes.
    for (float d : {9000.0f, 9040.0f, 9080.0f}) {
      const vec3 rgb = film_rgb(k::LAMINA_FRESNEL_FILM_RGB, cos_i, vec3(1.5f), vec3(1.0f), vec3(0.0f), d);
      for (int c = 0; c < 3; ++c) rgb_spread = std::max(rgb_spread, std::abs(double(rgb[c]) - want));
    }
  }
  CHECK(rgb_spread > 0.03);
}

TEST_CASE(
    "thin film: reflectance stays within [0, 1], is 1 at grazing and under total internal reflection, and is finite") {
  for (int mode : {k::LAMINA_FRESNEL_FILM_RGB, k::LAMINA_FRESNEL_FILM_SPECTRAL})
    for (float cos_i : {0.0f, 1e-6f, 0.2f, 0.9f, 1.0f})
      for (float film : {1.0f, 1.33f, 3.0f})
        for (float thickness : {0.0f, 1.0f, 500.0f, 10000.0f})
          for (const vec3& n : {vec3(1.0f), vec3(1e-3f), vec3(1000.0f), kGoldN}) {
            const vec3 kk = n.x == 1.0f ? vec3(0.0f) : kGoldK;
            const vec3 r = film_rgb(mode, cos_i, vec3(film), n, kk, thickness);
            for (int c = 0; c < 3; ++c) {
              CHECK(std::isfinite(r[c]));
              CHECK(r[c] >= 0.0f);
              CHECK(r[c] <= 1.0f);
            }
            // Grazing light is turned back whole by any base but one of the medium's own index, where
            // a film of no thickness or no index step is no boundary at all.
            if (cos_i == 0.0f && n != vec3(1.0f)) CHECK(r == vec3(1.0f));
          }
  // Under a coat of index 1.5, a film of index 1.2 turns back light beyond 53 degrees.
  const vec3 tir = film_rgb(k::LAMINA_FRESNEL_FILM_RGB, 0.5f, vec3(1.2f / 1.5f), kGoldN / 1.5f, kGoldK / 1.5f, 300.0f);
  CHECK(tir == vec3(1.0f));
}

TEST_CASE(
    "thin film: the base's Fresnel term is the conductor's for the conductor's modes, the film's for the film's") {
  for (int mode : {0, 1, 2})
    CHECK(k::lamina_fresnel_base(mode, 0.6f, kGoldN, kGoldK, vec3(1.5f), 300.0f) ==
          k::lamina_fresnel_conductor(mode, 0.6f, kGoldN, kGoldK));
  for (int mode : {k::LAMINA_FRESNEL_FILM_RGB, k::LAMINA_FRESNEL_FILM_SPECTRAL})
    CHECK(k::lamina_fresnel_base(mode, 0.6f, kGoldN, kGoldK, vec3(1.5f), 300.0f) ==
          k::lamina_fresnel_film(mode, 0.6f, vec3(1.5f), kGoldN, kGoldK, 300.0f));
}

TEST_CASE(
    "thin film: lamina's spectral film agrees with KHR_materials_iridescence's published formula at normal incidence") {
  // gltf::iridescence_fresnel is the extension's formula as published (graph/gltf/pbr_brdf.cpp). At
  // normal incidence Schlick's terms are exact and the polarisations agree, so the two differ by
  // the extension's two orders and its sensitivity, which maps a flat spectrum to (1.20, 0.95, 0.91)
  // rather than grey. Films of index 1.3 to 2 over glass (F0 0.04) and over a dense base.
  double worst = 0.0;
  for (double film : {1.3, 1.6, 2.0})
    for (double base_f0 : {0.04, 0.2})
      for (double thickness = 100.0; thickness <= 1200.0; thickness += 50.0) {
        const double base_ior = (1.0 + std::sqrt(base_f0 + 0.0001)) / (1.0 - std::sqrt(base_f0 + 0.0001));
        const vec3 ours = film_rgb(k::LAMINA_FRESNEL_FILM_SPECTRAL, 1.0f, vec3(float(film)), vec3(float(base_ior)),
                                   vec3(0.0f), float(thickness));
        const vec3 theirs = gltf::iridescence_fresnel(1.0f, float(film), 1.0f, float(thickness), vec3(float(base_f0)));
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(ours[c]) - double(theirs[c])));
      }
  MESSAGE("largest difference from KHR_materials_iridescence: " << worst);
  CHECK(worst < 0.04);
}
