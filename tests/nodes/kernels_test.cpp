// The BRDF leaf kernels (nodes/kernels/*.glsl compiled as C++): values against numbers computed
// independently from the papers' formulas (the python3 lines in the comments, double precision),
// and the physical and numerical properties every kernel promises.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "graph/limits.h"
#include "nodes/kernels/kernels.h"

namespace k = lamina::kernels;
using glm::vec2;
using glm::vec3;

namespace {

constexpr double kPi = std::numbers::pi;

// Relative tolerance for values against the double-precision references.
doctest::Approx rel(double expected, double eps = 1e-5) { return doctest::Approx(expected).epsilon(eps).scale(0.0); }

// Checks a vec3 against three expected components, each to rel().
#define CHECK_VEC3(got, want_x, want_y, want_z) \
  do {                                          \
    const vec3 got_ = (got);                    \
    CHECK(double(got_.x) == rel(want_x));       \
    CHECK(double(got_.y) == rel(want_y));       \
    CHECK(double(got_.z) == rel(want_z));       \
  } while (false)

// Checks a vec3 against another, each component to an absolute tolerance.
#define CHECK_VEC3_NEAR(got, want, tol)         \
  do {                                          \
    const vec3 got_ = (got);                    \
    const vec3 want_ = (want);                  \
    CHECK(std::abs(got_.x - want_.x) <= (tol)); \
    CHECK(std::abs(got_.y - want_.y) <= (tol)); \
    CHECK(std::abs(got_.z - want_.z) <= (tol)); \
  } while (false)

bool is_finite(float x) { return std::isfinite(x); }
bool is_finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Uniform floats in [0, 1) from a fixed-seed generator: 24 random bits, so 1 is never reached.
class Uniform {
 public:
  explicit Uniform(std::uint32_t seed) : rng_(seed) {}
  float next() { return float(rng_() >> 8) * 0x1p-24f; }
  vec2 next2() {
    float a = next();
    return vec2(a, next());
  }
  // A direction uniformly distributed over the upper hemisphere, never exactly on the horizon.
  vec3 hemisphere() {
    float z = 1.0f - next();
    float phi = 2.0f * float(kPi) * next();
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
  }

 private:
  std::mt19937 rng_;
};

vec3 direction(double theta_deg, double phi_deg) {
  double t = theta_deg * kPi / 180.0, p = phi_deg * kPi / 180.0;
  return vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t)));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// common.glsl

TEST_CASE("kernels: the common helpers square, weigh luminance and clamp the square root") {
  CHECK(k::lamina_sqr(-3.0f) == 9.0f);
  // 0.2126*0.5 + 0.7152*0.25 + 0.0722*1 = 0.1063 + 0.1788 + 0.0722 = 0.3573
  CHECK(double(k::lamina_luminance(vec3(0.5f, 0.25f, 1.0f))) == rel(0.3573));
  CHECK(double(k::lamina_luminance(vec3(1.0f))) == rel(1.0));
  CHECK(k::lamina_safe_sqrt(-1.0f) == 0.0f);
  CHECK(double(k::lamina_safe_sqrt(2.0f)) == rel(1.4142135623730951));
  CHECK(double(k::LAMINA_PI) == rel(kPi, 1e-7));
  CHECK(double(k::LAMINA_INV_PI) == rel(1.0 / kPi, 1e-7));
}

TEST_CASE("kernels: lamina_one_minus_exp is 1 - exp(-y) to float precision, also for tiny y") {
  double worst = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    const float y = std::ldexp(1.0f, -40) * std::pow(2.0f, float(i) / 100.0f);  // 2^-40 .. 2^0
    worst = std::max(worst, std::abs(double(k::lamina_one_minus_exp(y)) / -std::expm1(-double(y)) - 1.0));
  }
  CHECK(worst < 5e-7);
  CHECK(k::lamina_one_minus_exp(0.0f) == 0.0f);
  CHECK(double(k::lamina_one_minus_exp(20.0f)) == rel(-std::expm1(-20.0), 1e-7));
}

TEST_CASE("kernels: lamina_acos is arccos within Abramowitz-Stegun's 2e-8 plus float rounding, over [-1, 1]") {
  // Against the double-precision std::acos: 4.4.46's error bound is 2e-8; evaluating its eight
  // terms in float adds a few ulp of pi.
  double worst = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    const float x = -1.0f + 2.0f * float(i) / 20000.0f;
    worst = std::max(worst, std::abs(double(k::lamina_acos(x)) - std::acos(double(x))));
  }
  CHECK(worst < 1e-6);
  CHECK(k::lamina_acos(1.0f) == 0.0f);
  CHECK(double(k::lamina_acos(0.0f)) == rel(kPi / 2.0, 1e-7));
  CHECK(double(k::lamina_acos(-1.0f)) == rel(kPi, 1e-7));
  CHECK(double(k::lamina_acos(0.5f)) == rel(kPi / 3.0, 1e-6));
  // Arguments rounded just past 1 stay on the curve's end instead of giving NaN.
  CHECK(k::lamina_acos(1.0000001f) == 0.0f);
  CHECK(double(k::lamina_acos(-1.0000001f)) == rel(kPi, 1e-7));
}
// ---------------------------------------------------------------------------------------------
// fresnel.glsl

TEST_CASE("kernels: fresnel_dielectric agrees with the Cook-Torrance form of the Fresnel equations") {
  // Cook and Torrance 1982: g = sqrt(eta^2 - 1 + c^2),
  // F = 1/2 (g-c)^2/(g+c)^2 (1 + ((c(g+c)-1)/(c(g-c)+1))^2), a different arrangement of the same law.
  // python3 -c "import math
  // def F(c,e): g=math.sqrt(e*e-1+c*c); return 0.5*(g-c)**2/(g+c)**2*(1+((c*(g+c)-1)/(c*(g-c)+1))**2)
  // print(F(0.5,1.5), F(0.9,1/1.5), F(0.2,1.33))"
  // -> 0.08918671280221278 0.04633264795403766 0.2971299827153841
  CHECK(double(k::fresnel_dielectric(0.5f, 1.5f)) == rel(0.08918671280221278));
  CHECK(double(k::fresnel_dielectric(0.9f, 1.0f / 1.5f)) == rel(0.04633264795403766));
  CHECK(double(k::fresnel_dielectric(0.2f, 1.33f)) == rel(0.2971299827153841));
}

TEST_CASE("kernels: fresnel_dielectric is 0 without a boundary, ((eta-1)/(eta+1))^2 at normal incidence, 1 under TIR") {
  CHECK(k::fresnel_dielectric(1.0f, 1.0f) == 0.0f);
  for (float c : {0.0f, 1e-8f, 0.3f, 0.7f}) CHECK(k::fresnel_dielectric(c, 1.0f) == 0.0f);
  for (float eta : {1.0f / 1.5f, 1.2f, 1.33f, 1.5f, 1.7f, 2.4f}) {
    CAPTURE(eta);
    double r = (double(eta) - 1.0) / (double(eta) + 1.0);
    CHECK(double(k::fresnel_dielectric(1.0f, eta)) == rel(r * r));
  }
  // Inside glass (eta = 1/1.5) the critical angle has sin = 1/1.5, cos = sqrt(1 - 1/2.25) = 0.745.
  CHECK(k::fresnel_dielectric(0.5f, 1.0f / 1.5f) == 1.0f);
  CHECK(k::fresnel_dielectric(0.74f, 1.0f / 1.5f) == 1.0f);
  CHECK(k::fresnel_dielectric(0.75f, 1.0f / 1.5f) < 1.0f);
  CHECK(k::fresnel_dielectric(0.0f, 0.5f) == 1.0f);
  // Grazing incidence reflects everything from either side.
  CHECK(k::fresnel_dielectric(0.0f, 1.5f) == 1.0f);
  // cos_i is clamped to [0, 1].
  CHECK(k::fresnel_dielectric(1.5f, 1.5f) == k::fresnel_dielectric(1.0f, 1.5f));
  CHECK(k::fresnel_dielectric(-0.5f, 1.5f) == k::fresnel_dielectric(0.0f, 1.5f));
}

TEST_CASE("kernels: fresnel_conductor agrees with complex Snell's law and the Fresnel amplitudes") {
  // python3 -c "import cmath
  // def F(c,n,k):
  //   N=complex(n,k); ct=cmath.sqrt(1-(1-c*c)/(N*N))
  //   rs=(c-N*ct)/(c+N*ct); rp=(N*c-ct)/(N*c+ct); return 0.5*(abs(rs)**2+abs(rp)**2)
  // gold=list(zip((0.1,0.42,1.56),(3.8,2.5,1.9))); al=list(zip((1.94,1.0,0.6),(8.21,6.69,4.86)))
  // print([F(0.5,n,k) for n,k in gold], [F(1.0,n,k) for n,k in gold], [F(0.2,n,k) for n,k in al])"
  const vec3 gold_n(0.1f, 0.42f, 1.56f), gold_k(3.8f, 2.5f, 1.9f);
  const vec3 al_n(1.94f, 1.0f, 0.6f), al_k(8.21f, 6.69f, 4.86f);
  CHECK_VEC3(k::fresnel_conductor(0.5f, gold_n, gold_k), 0.9711765665341424, 0.7967686922198595, 0.41532722032591096);
  CHECK_VEC3(k::fresnel_conductor(1.0f, gold_n, gold_k), 0.97444089456869, 0.7967676376657314, 0.3860443150064937);
  CHECK_VEC3(k::fresnel_conductor(0.2f, al_n, al_k), 0.8193870554435135, 0.8652740888161148, 0.877909160846005);
  // Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2); gold red: (0.81 + 14.44) / (1.21 + 14.44) = 15.25 / 15.65.
  CHECK(double(k::fresnel_conductor(1.0f, gold_n, gold_k).x) == rel(15.25 / 15.65));
  // Grazing incidence reflects everything.
  CHECK_VEC3(k::fresnel_conductor(0.0f, gold_n, gold_k), 1.0, 1.0, 1.0);
}

TEST_CASE("kernels: fresnel_conductor with k = 0 equals fresnel_dielectric, total internal reflection included") {
  for (float eta : {0.5f, 1.0f / 1.5f, 0.9f, 1.0f, 1.2f, 1.5f, 2.4f}) {
    for (int i = 0; i <= 40; ++i) {
      float c = float(i) / 40.0f;
      CAPTURE(eta);
      CAPTURE(c);
      vec3 f = k::fresnel_conductor(c, vec3(eta), vec3(0.0f));
      float d = k::fresnel_dielectric(c, eta);
      CHECK(std::abs(f.x - d) <= 2e-6f);
      CHECK(f.x == f.y);
      CHECK(f.y == f.z);
    }
  }
}

TEST_CASE("kernels: fresnel_schlick and fresnel_lazanyi follow their approximations") {
  // Schlick 1994, eq. 24: 0.04 + 0.96 * 0.7**5 = 0.2013472
  CHECK(double(k::fresnel_schlick(0.3f, 0.04f)) == rel(0.2013472));
  CHECK(k::fresnel_schlick(1.0f, 0.04f) == 0.04f);
  CHECK(k::fresnel_schlick(0.0f, 0.04f) == 1.0f);
  // Elek 2010, App. B, gold at cos 0.5:
  // python3 -c "print([((n-1)**2+4*n*0.5**5+k*k)/((n+1)**2+k*k) for n,k in zip((0.1,0.42,1.56),(3.8,2.5,1.9))])"
  const vec3 gold_n(0.1f, 0.42f, 1.56f), gold_k(3.8f, 2.5f, 1.9f);
  CHECK_VEC3(k::fresnel_lazanyi(0.5f, gold_n, gold_k), 0.9752396166134185, 0.803118648988677, 0.4052304301625408);
  // At normal incidence the approximation is exact: 15.25 / 15.65 for gold's red channel.
  CHECK(double(k::fresnel_lazanyi(1.0f, gold_n, gold_k).x) == rel(15.25 / 15.65));
}

TEST_CASE("kernels: conductor_f0 is the exact conductor reflectance at normal incidence") {
  // Born and Wolf sec. 14.2 at cos 1: ((n-1)^2 + k^2) / ((n+1)^2 + k^2); gold's red channel is
  // (0.81 + 14.44) / (1.21 + 14.44) = 15.25 / 15.65, and k = 0 gives ((n-1)/(n+1))^2 = 0.04 for n = 1.5.
  const vec3 gold_n(0.1f, 0.42f, 1.56f), gold_k(3.8f, 2.5f, 1.9f);
  // python3 -c "print([((n-1)**2+k*k)/((n+1)**2+k*k) for n,k in zip((0.1,0.42,1.56),(3.8,2.5,1.9))])"
  CHECK_VEC3(k::conductor_f0(gold_n, gold_k), 0.9744408945686901, 0.7967676376657311, 0.3860443150064937);
  CHECK(double(k::conductor_f0(vec3(1.5f), vec3(0.0f)).x) == rel(0.04));
  CHECK_VEC3_NEAR(k::conductor_f0(gold_n, gold_k), k::fresnel_conductor(1.0f, gold_n, gold_k), 1e-6f);
  CHECK_VEC3_NEAR(k::fresnel_schlick_rgb(0.3f, vec3(0.04f, 0.5f, 1.0f)),
                  vec3(k::fresnel_schlick(0.3f, 0.04f), k::fresnel_schlick(0.3f, 0.5f), 1.0f), 0.0f);
}

TEST_CASE("kernels: the fresnel modes select the exact term, Schlick and Lazanyi-Szirmay-Kalos") {
  const vec3 gold_n(0.1f, 0.42f, 1.56f), gold_k(3.8f, 2.5f, 1.9f);
  Uniform u(31);
  for (int i = 0; i < 200; ++i) {
    float c = u.next();
    float eta = 0.5f + 2.0f * u.next();
    // Mode 0 (and unknown modes) is the exact term, bit for bit.
    CHECK(k::lamina_fresnel_dielectric(0, c, eta) == k::fresnel_dielectric(c, eta));
    CHECK(k::lamina_fresnel_dielectric(7, c, eta) == k::fresnel_dielectric(c, eta));
    CHECK(k::lamina_fresnel_conductor(0, c, gold_n, gold_k) == k::fresnel_conductor(c, gold_n, gold_k));
    // For k = 0, Lazanyi-Szirmay-Kalos is Schlick's polynomial: (eta + 1)^2 - (eta - 1)^2 = 4 eta.
    CHECK(std::abs(k::lamina_fresnel_dielectric(2, c, eta) - k::lamina_fresnel_dielectric(1, c, eta)) <= 3e-7f);
    // For metals, too, it is Schlick from the exact F0; the modes differ only in rounding.
    CHECK_VEC3_NEAR(k::lamina_fresnel_conductor(1, c, gold_n, gold_k),
                    k::lamina_fresnel_conductor(2, c, gold_n, gold_k), 3e-7f);
    CHECK(k::lamina_fresnel_conductor(2, c, gold_n, gold_k) == k::fresnel_lazanyi(c, gold_n, gold_k));
  }
  // Schlick at eta 1.5 (F0 0.04), cos 0.3: 0.04 + 0.96 * 0.7**5 = 0.2013472.
  CHECK(double(k::lamina_fresnel_dielectric(1, 0.3f, 1.5f)) == rel(0.2013472));
  // Metals: Elek App. B at cos 0.5 (the values of the fresnel_lazanyi test) for both modes.
  CHECK_VEC3(k::lamina_fresnel_conductor(1, 0.5f, gold_n, gold_k), 0.9752396166134185, 0.803118648988677,
             0.4052304301625408);
  // From the denser side (eta = 1/1.5) at 30 deg the polynomial takes the refracted cosine,
  // cos_t = sqrt(1 - (1.5 sin 30)^2) = 0.6614378: 0.04 + 0.96 (1 - cos_t)^5 = 0.044270349
  // python3 -c "import math; c=math.sqrt(1-(1.5*0.5)**2); print(c, 0.04+0.96*(1-c)**5)"
  const float cos30 = float(std::cos(kPi / 6.0));
  CHECK(double(k::lamina_rarer_side_cosine(cos30, 1.0f / 1.5f)) == rel(0.6614378277661477));
  CHECK(double(k::lamina_fresnel_dielectric(1, cos30, 1.0f / 1.5f)) == rel(0.04427034925264154));
  CHECK(double(k::lamina_fresnel_dielectric(2, cos30, 1.0f / 1.5f)) == rel(0.04427034925264154));
  // ... which is what the rarer side sees at the angle Snell's law connects (de Greve 2006).
  CHECK(k::lamina_fresnel_dielectric(1, 0.6614378f, 1.5f) ==
        doctest::Approx(0.04427034925264154).epsilon(1e-5).scale(0.0));
  // Past the critical angle (45 deg: 1.5 sin 45 > 1) total internal reflection gives 1, as the exact term.
  const float cos45 = float(std::cos(kPi / 4.0));
  CHECK(k::lamina_rarer_side_cosine(cos45, 1.0f / 1.5f) == -1.0f);
  for (int mode : {0, 1, 2}) {
    CAPTURE(mode);
    CHECK(k::lamina_fresnel_dielectric(mode, cos45, 1.0f / 1.5f) == 1.0f);
    // An index-matched boundary reflects nothing; eta <= 0 cannot transmit.
    CHECK(k::lamina_fresnel_dielectric(mode, 0.2f, 1.0f) == 0.0f);
    CHECK(k::lamina_fresnel_dielectric(mode, 0.2f, 0.0f) == 1.0f);
    // Grazing incidence from the rarer side reflects everything, normal incidence F0.
    CHECK(k::lamina_fresnel_dielectric(mode, 0.0f, 1.5f) == doctest::Approx(1.0).epsilon(1e-6).scale(0.0));
    CHECK(double(k::lamina_fresnel_dielectric(mode, 1.0f, 1.5f)) == rel(0.04));
  }
  // Schlick's error for glass stays below 0.036 (python3: max over cos of |schlick - exact| for
  // n = 1.5 is 0.0357), and for gold below 0.032 per channel.
  for (int i = 0; i <= 1000; ++i) {
    float c = float(i) / 1000.0f;
    CHECK(std::abs(k::lamina_fresnel_dielectric(1, c, 1.5f) - k::fresnel_dielectric(c, 1.5f)) <= 0.036f);
    vec3 d = glm::abs(k::lamina_fresnel_conductor(1, c, gold_n, gold_k) - k::fresnel_conductor(c, gold_n, gold_k));
    CHECK(std::max(d.x, std::max(d.y, d.z)) <= 0.032f);
  }
}

// ---------------------------------------------------------------------------------------------
// microfacet.glsl

TEST_CASE("kernels: the microfacet distributions match the papers' formulas") {
  // Walter et al. 2007, eq. 25 / Elek App. B with 1/pi, at cos_h 0.9, m 0.3:
  // python3 -c "import math; t=math.tan(math.acos(0.9)); print(math.exp(-(t/0.3)**2)/(math.pi*0.09*0.9**4))"
  CHECK(double(k::d_beckmann(0.9f, 0.3f)) == rel(0.3978611403040671));
  // At the peak: 1 / (pi m^2) = 1 / (pi 0.09) = 3.5367765131532297
  CHECK(double(k::d_beckmann(1.0f, 0.3f)) == rel(3.5367765131532297));
  // e = 2/m^2 - 2 = 2/0.09 - 2 = 20.2222...; (e+2)/(2 pi) 0.9^e:
  // python3 -c "import math; e=2/0.09-2; print(e, (e+2)/(2*math.pi)*0.9**e)"
  CHECK(double(k::blinn_exponent(0.3f)) == rel(20.22222222222222));
  CHECK(double(k::d_blinn(0.9f, 0.3f)) == rel(0.42003886415722874));
  // m above 1 would give a negative exponent: clamped to 0, a uniform 1/pi lobe.
  CHECK(k::blinn_exponent(2.0f) == 0.0f);
  CHECK(double(k::d_blinn(0.3f, 2.0f)) == rel(1.0 / kPi));
  // Walter et al. 2007, eq. 33: alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2):
  // python3 -c "import math; t=math.tan(math.acos(0.9)); print(0.09/(math.pi*0.9**4*(0.09+t*t)**2))"
  CHECK(double(k::d_ggx(0.9f, 0.3f)) == rel(0.4144875255607341));
  CHECK(double(k::d_ggx(1.0f, 0.3f)) == rel(3.5367765131532297));
  // The dispatch: 0 Beckmann, 1 Blinn, 2 GGX (alpha = m), anything else 0.
  CHECK(k::d_microfacet(0, 0.9f, 0.3f) == k::d_beckmann(0.9f, 0.3f));
  CHECK(k::d_microfacet(1, 0.9f, 0.3f) == k::d_blinn(0.9f, 0.3f));
  CHECK(k::d_microfacet(2, 0.9f, 0.3f) == k::d_ggx(0.9f, 0.3f));
  CHECK(k::d_microfacet(3, 0.9f, 0.3f) == 0.0f);
  CHECK(k::d_microfacet(-1, 0.9f, 0.3f) == 0.0f);
}

TEST_CASE("kernels: every microfacet distribution integrates with cos_h to 1 over the hemisphere") {
  // 2 pi * integral over theta in [0, pi/2] of D(cos theta) cos theta sin theta, Simpson's rule.
  const int n = 20000;
  for (int dist : {0, 1, 2}) {
    for (float m : {0.05f, 0.2f, 0.5f}) {
      CAPTURE(dist);
      CAPTURE(m);
      double h = (kPi / 2.0) / n, sum = 0.0;
      for (int i = 0; i <= n; ++i) {
        double t = h * i;
        double f = double(k::d_microfacet(dist, float(std::cos(t)), m)) * std::cos(t) * std::sin(t);
        sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
      }
      CHECK(std::abs(2.0 * kPi * sum * h / 3.0 - 1.0) < 1e-3);
    }
  }
}

TEST_CASE("kernels: the V-cavity term follows the course's geom and is symmetric in l and v") {
  // min(1, 2*0.95*0.3/0.6, 2*0.95*0.8/0.6) = min(1, 0.95, 2.5333) = 0.95
  CHECK(double(k::g_vcavity(0.8f, 0.3f, 0.95f, 0.6f)) == rel(0.95));
  CHECK(k::g_vcavity(0.8f, 0.9f, 0.95f, 0.6f) == 1.0f);
  // A vanishing v.h masks nothing instead of dividing by zero.
  CHECK(k::g_vcavity(0.5f, 0.5f, 0.9f, 1e-30f) == 1.0f);
  Uniform u(7);
  for (int i = 0; i < 1000; ++i) {
    float cl = u.next(), cv = u.next(), ch = u.next(), vh = u.next();
    CHECK(k::g_vcavity(cl, cv, ch, vh) == k::g_vcavity(cv, cl, ch, vh));
  }
}

TEST_CASE("kernels: the Smith GGX terms follow Walter et al. and tend to 1 at the normal") {
  // python3 -c "import math; G1=lambda c,a: 2/(1+math.sqrt(1+a*a*math.tan(math.acos(c))**2));
  //             print(G1(0.5,0.3), G1(0.5,0.3)*G1(0.8,0.3))"
  CHECK(double(k::g1_smith_ggx(0.5f, 0.3f)) == rel(0.9403167922849222));
  CHECK(double(k::g_smith_ggx(0.5f, 0.8f, 0.3f)) == rel(0.9287079429974541));
  for (float a : {k::LAMINA_MIN_SLOPE, 0.05f, 0.3f, 1.0f}) {
    CAPTURE(a);
    CHECK(k::g1_smith_ggx(1.0f, a) == 1.0f);
    CHECK(double(k::g1_smith_ggx(0.9999f, a)) == doctest::Approx(1.0).epsilon(1e-3).scale(0.0));
    // Below 1 away from the normal (for the smallest alpha, 1 - 5e-8 rounds to 1 in float).
    if (a >= 0.05f) CHECK(k::g1_smith_ggx(0.3f, a) < 1.0f);
  }
  CHECK(k::g_smith_ggx(0.5f, 0.8f, 0.3f) == k::g_smith_ggx(0.8f, 0.5f, 0.3f));
}

TEST_CASE("kernels: g_microfacet uses Smith for GGX and the V-cavity term otherwise") {
  CHECK(k::g_microfacet(2, 0.5f, 0.8f, 0.95f, 0.6f, 0.3f) == k::g_smith_ggx(0.5f, 0.8f, 0.3f));
  CHECK(k::g_microfacet(0, 0.8f, 0.3f, 0.95f, 0.6f, 0.3f) == k::g_vcavity(0.8f, 0.3f, 0.95f, 0.6f));
  CHECK(k::g_microfacet(1, 0.8f, 0.3f, 0.95f, 0.6f, 0.3f) == k::g_vcavity(0.8f, 0.3f, 0.95f, 0.6f));
  // Smith's chi+: a microfacet facing away from the view masks everything.
  CHECK(k::g_microfacet(2, 0.5f, 0.8f, 0.95f, -0.1f, 0.3f) == 0.0f);
}

TEST_CASE("kernels: torrance_sparrow is F D G / (4 cos_l cos_v)") {
  // F * 2 * 0.8 / (4 * 0.5 * 0.25) = F * 3.2
  CHECK_VEC3(k::torrance_sparrow(vec3(0.5f, 0.25f, 1.0f), 2.0f, 0.8f, 0.5f, 0.25f), 1.6, 0.8, 3.2);
}

TEST_CASE("kernels: sample_microfacet_normal inverts the papers' CDFs") {
  // GGX, Walter et al. 2007, eqs. 35-36: u = (0.5, 0.25): tan^2 = 0.09 * 0.5/0.5, theta = atan(0.3), phi = pi/2:
  // python3 -c "import math; t=math.atan(0.3); print(math.sin(t), math.cos(t))"
  vec3 h = k::sample_microfacet_normal(2, 0.3f, vec2(0.5f, 0.25f));
  CHECK(std::abs(h.x) < 1e-7f);  // 0.287 cos(pi/2)
  CHECK(double(h.y) == rel(0.28734788556634544));
  CHECK(double(h.z) == rel(0.9578262852211514));
  // Beckmann, eq. 28: u = (0.5, 0.125): tan^2 = -0.09 ln 0.5, phi = pi/4:
  // python3 -c "import math; t=math.atan(math.sqrt(-0.09*math.log(0.5))); p=math.pi/4;
  //             print(math.sin(t)*math.cos(p), math.sin(t)*math.sin(p), math.cos(t))"
  CHECK_VEC3(k::sample_microfacet_normal(0, 0.3f, vec2(0.5f, 0.125f)), 0.1713477400483107, 0.17134774004831066,
             0.9701958070207648);
  // Blinn: cos = (1 - u)^(1/(e+2)) with e = 2/0.09 - 2, u = (0.5, 0):
  // python3 -c "e=2/0.09-2; c=0.5**(1/(e+2)); print((1-c*c)**0.5, c)"
  h = k::sample_microfacet_normal(1, 0.3f, vec2(0.5f, 0.0f));
  CHECK(double(h.x) == rel(0.24592122882335352));
  CHECK(h.y == 0.0f);
  CHECK(double(h.z) == rel(0.969289816935065));
  // A narrow Blinn lobe (m = 0.01, u = 0.2) keeps sin's digits, where cos^2 is within 2e-6 of 1:
  // python3 -c "import math; e=2/0.0001-2; print(math.sqrt(-math.expm1(2*math.log(0.8)/(e+2))))"
  CHECK(double(k::sample_microfacet_normal(1, 0.01f, vec2(0.2f, 0.0f)).x) == rel(0.0047237809187186406, 1e-6));
  // u = 0 is the normal for every distribution; unknown distributions give vec3(0).
  for (int dist : {0, 1, 2})
    CHECK_VEC3_NEAR(k::sample_microfacet_normal(dist, 0.3f, vec2(0.0f, 0.3f)), vec3(0.0f, 0.0f, 1.0f), 1e-7f);
  CHECK(k::sample_microfacet_normal(5, 0.3f, vec2(0.5f, 0.5f)) == vec3(0.0f));
}

TEST_CASE("kernels: pdf_microfacet_normal is D cos_h") {
  // 0.4144875255607341 * 0.9 (GGX value above)
  CHECK(double(k::pdf_microfacet_normal(2, 0.3f, 0.9f)) == rel(0.4144875255607341 * 0.9));
  CHECK(k::pdf_microfacet_normal(0, 0.3f, 0.9f) == k::d_beckmann(0.9f, 0.3f) * 0.9f);
}

TEST_CASE("kernels: sample_microfacet_normal's histogram over cos_h matches pdf_microfacet_normal") {
  // Bins: 16 equal ones in cos_h over [cos(atan(3 m)), 1] and one below; expected mass of a bin is
  // 2 pi * integral of pdf(c) dc (d omega = dc dphi). Each observed fraction must lie within five
  // binomial standard deviations (plus the quadrature's error) of it. Also: unit length, and the
  // azimuth spread evenly over the four quadrants.
  const int samples = 200000, bins = 16;
  for (int dist : {0, 1, 2}) {
    for (float m : {0.05f, 0.2f, 0.5f}) {
      CAPTURE(dist);
      CAPTURE(m);
      const double lo = std::cos(std::atan(3.0 * m));
      auto mass = [&](double a, double b) {
        const int n = 400;
        double h = (b - a) / n, sum = 0.0;
        for (int i = 0; i <= n; ++i) {
          double f = k::pdf_microfacet_normal(dist, m, float(a + h * i));
          sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
        }
        return 2.0 * kPi * sum * h / 3.0;
      };
      std::vector<double> expected(bins + 1);
      expected[0] = mass(0.0, lo);
      for (int b = 0; b < bins; ++b)
        expected[b + 1] = mass(lo + (1.0 - lo) * b / bins, lo + (1.0 - lo) * (b + 1) / bins);
      double total = 0.0;
      for (double e : expected) total += e;
      CHECK(total == doctest::Approx(1.0).epsilon(1e-3).scale(0.0));

      std::vector<int> observed(bins + 1, 0);
      std::array<int, 4> quadrant{};
      Uniform u(1234);
      float worst_length = 0.0f;
      for (int i = 0; i < samples; ++i) {
        vec3 h = k::sample_microfacet_normal(dist, m, u.next2());
        worst_length = std::max(worst_length, std::abs(glm::length(h) - 1.0f));
        double c = h.z;
        int b = c < lo ? 0 : 1 + std::min(bins - 1, int((c - lo) / (1.0 - lo) * bins));
        ++observed[b];
        ++quadrant[(h.x >= 0.0f ? 0 : 1) + (h.y >= 0.0f ? 0 : 2)];
      }
      CHECK(worst_length < 1e-5f);
      for (int b = 0; b <= bins; ++b) {
        CAPTURE(b);
        double p = expected[b], seen = double(observed[b]) / samples;
        CHECK(std::abs(seen - p) <= 5.0 * std::sqrt(p * (1.0 - p) / samples) + 2e-4);
      }
      for (int q : quadrant) CHECK(std::abs(double(q) / samples - 0.25) <= 5.0 * std::sqrt(0.25 * 0.75 / samples));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// diffuse.glsl

TEST_CASE("kernels: lambert is albedo / pi and oren_nayar follows the course's shader") {
  // 0.5/pi, 0.25/pi, 1/pi
  CHECK_VEC3(k::lambert(vec3(0.5f, 0.25f, 1.0f)), 0.5 / kPi, 0.25 / kPi, 1.0 / kPi);
  // Gritz's shader (Weidlich and Wilkie course, sec. 3.3.1) in python, its radiance divided by cos_i and pi:
  // python3 -c "import math; pi=math.pi
  // def on(ti,tr,cp,Cs,sg):
  //   a=max(ti,tr); b=min(ti,tr); s2=sg*sg; C1=1-0.5*s2/(s2+0.33); C2=0.45*s2/(s2+0.09)
  //   C2*=math.sin(a) if cp>=0 else math.sin(a)-(2*b/pi)**3
  //   C3=0.125*s2/(s2+0.09)*((4*a*b)/(pi*pi))**2; ci=math.cos(ti)
  //   L1=Cs*(ci*(C1+cp*C2*math.tan(b)+(1-abs(cp))*C3*math.tan((a+b)/2)))
  //   L2=Cs*Cs*(0.17*ci*s2/(s2+0.13)*(1-cp*(4*b*b)/(pi*pi)))
  //   return (L1+L2)/ci/pi
  // r=math.radians
  // print([on(r(60),r(30),math.cos(r(45)),C,0.34) for C in (0.3,0.4,0.1)])
  // print([on(r(60),r(30),math.cos(r(135)),C,0.34) for C in (0.3,0.4,0.1)])
  // print([on(r(70),r(20),0.0,C,1.0) for C in (0.3,0.4,0.1)])"
  const vec3 latex(0.3f, 0.4f, 0.1f);
  CHECK_VEC3(k::oren_nayar(direction(60, 0), direction(30, 45), latex, 0.34f), 0.0938578587492222, 0.1260825662600609,
             0.030816575619191735);
  CHECK_VEC3(k::oren_nayar(direction(60, 0), direction(30, 135), latex, 0.34f), 0.07749883040246087,
             0.10443061728310085, 0.025283521760910466);
  CHECK_VEC3(k::oren_nayar(direction(70, 10), direction(20, 100), latex, 1.0f), 0.06423035963714711, 0.0875559726365942,
             0.020452373318850022);
}

TEST_CASE("kernels: oren_nayar keeps its digits at grazing directions on opposite sides of the normal") {
  // The course's formula (as in the test above) in double precision, at the float directions' own
  // angles: there sin(alpha) - (2 beta / pi)^3 cancels and tan(beta) multiplies it by up to 6000.
  auto course = [](vec3 wi, vec3 wo, double albedo, double sigma) {
    const double ti = std::acos(double(wi.z)), tr = std::acos(double(wo.z));
    const double cp = (double(wi.x) * wo.x + double(wi.y) * wo.y) /
                      (std::hypot(double(wi.x), double(wi.y)) * std::hypot(double(wo.x), double(wo.y)));
    const double a = std::max(ti, tr), b = std::min(ti, tr), s2 = sigma * sigma;
    const double c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    const double c2 = 0.45 * s2 / (s2 + 0.09) * (cp >= 0.0 ? std::sin(a) : std::sin(a) - std::pow(2.0 * b / kPi, 3.0));
    const double c3 = 0.125 * s2 / (s2 + 0.09) * std::pow(4.0 * a * b / (kPi * kPi), 2.0);
    const double direct = albedo * (c1 + cp * c2 * std::tan(b) + (1.0 - std::abs(cp)) * c3 * std::tan((a + b) / 2.0));
    const double inter = albedo * albedo * 0.17 * s2 / (s2 + 0.13) * (1.0 - cp * 4.0 * b * b / (kPi * kPi));
    return std::max(direct + inter, 0.0) / kPi;
  };
  // 75.5 and 75.6 deg lie either side of cos(beta) = 1/4, where the kernel changes how it computes
  // 1 - 2 beta / pi.
  for (double theta : {70.0, 75.5, 75.6, 80.0, 89.0, 89.9, 89.99})
    for (float sigma : {0.27f, 0.5f}) {
      CAPTURE(theta);
      CAPTURE(sigma);
      const vec3 wi = direction(theta, 0.0), wo = direction(theta - 0.004, 180.0);
      CHECK(double(k::oren_nayar(wi, wo, vec3(0.4f), sigma).x) == rel(course(wi, wo, 0.4, double(sigma)), 1e-5));
    }
}

TEST_CASE("kernels: oren_nayar with sigma 0 is exactly lambert, and it is symmetric and non-negative") {
  Uniform u(99);
  for (int i = 0; i < 2000; ++i) {
    vec3 wi = u.hemisphere(), wo = u.hemisphere();
    vec3 albedo(u.next(), u.next(), u.next());
    float sigma = u.next() * float(kPi) / 2.0f;
    CHECK(k::oren_nayar(wi, wo, albedo, 0.0f) == k::lambert(albedo));
    vec3 f = k::oren_nayar(wi, wo, albedo, sigma);
    CHECK(f == k::oren_nayar(wo, wi, albedo, sigma));
    CHECK(is_finite(f));
    CHECK((f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f));
  }
  // Along the normal the azimuth is undefined and cos_phi is taken as 0.
  vec3 n(0.0f, 0.0f, 1.0f);
  CHECK(is_finite(k::oren_nayar(n, n, vec3(0.5f), 0.5f)));
  CHECK(k::oren_nayar(n, direction(40, 0), vec3(0.5f), 0.5f) == k::oren_nayar(n, direction(40, 77), vec3(0.5f), 0.5f));
  // Where the course's formula itself goes negative it is clamped to 0: sigma 1, albedo 0.1, both
  // directions at cos 1e-6 on opposite sides of the normal: on(t, t, -1, 0.1, 1.0) with
  // t = math.acos(1e-6) gives -0.00428 in the python above.
  float s = std::sqrt(1.0f - 1e-12f);
  CHECK(k::oren_nayar(vec3(s, 0.0f, 1e-6f), vec3(-s, 0.0f, 1e-6f), vec3(0.1f), 1.0f) == vec3(0.0f));
}

TEST_CASE("kernels: oren_nayar_mean is the cosine-weighted mean of oren_nayar over both hemispheres") {
  // With x = cos^2 for each direction, cos dw = dx dphi / 2, so the mean (1 / pi^2) int int f cos cos
  // is the plain average of f over x_i, x_o and the azimuth difference: midpoints, in double.
  const int n = 160, azimuths = 64;
  for (float sigma : {0.0f, 0.26f, 0.5f, 1.0f, 1.5f}) {
    const vec3 albedo(1.0f, 0.5f, 0.2f);
    glm::dvec3 sum(0.0);
    for (int i = 0; i < n; ++i) {
      const double mu_i = std::sqrt((i + 0.5) / n);
      const vec3 wi(float(std::sqrt(1.0 - mu_i * mu_i)), 0.0f, float(mu_i));
      for (int o = 0; o < n; ++o) {
        const double mu_o = std::sqrt((o + 0.5) / n), s_o = std::sqrt(1.0 - mu_o * mu_o);
        for (int a = 0; a < azimuths; ++a) {
          const double phi = 2.0 * kPi * (a + 0.5) / azimuths;
          const vec3 wo(float(s_o * std::cos(phi)), float(s_o * std::sin(phi)), float(mu_o));
          sum += glm::dvec3(k::oren_nayar(wi, wo, albedo, sigma));
        }
      }
    }
    const glm::dvec3 mean = sum / double(n * n * azimuths);
    const vec3 closed = k::oren_nayar_mean(albedo, sigma);
    CAPTURE(sigma);
    for (int c = 0; c < 3; ++c) CHECK(double(closed[c]) == rel(mean[c], 2e-3));
  }
  // Lambert's mean is its value.
  CHECK_VEC3(k::oren_nayar_mean(vec3(0.3f, 0.6f, 0.9f), 0.0f), 0.3 / kPi, 0.6 / kPi, 0.9 / kPi);
}

TEST_CASE("kernels: sample_cosine is Malley's method and pdf_cosine its density") {
  // u = (0.25, 0.125): r = 0.5, phi = pi/4: (0.5 cos(pi/4), 0.5 sin(pi/4), sqrt(0.75))
  CHECK_VEC3(k::sample_cosine(vec2(0.25f, 0.125f)), 0.5 * std::sqrt(0.5), 0.5 * std::sqrt(0.5), std::sqrt(0.75));
  CHECK(k::sample_cosine(vec2(0.0f, 0.7f)) == vec3(0.0f, 0.0f, 1.0f));
  // 0.5 / pi
  CHECK(double(k::pdf_cosine(0.5f)) == rel(0.5 / kPi));
  // Histogram of cos^2, which is uniform on [0, 1) under cosine-weighted sampling (CDF of cos: c^2).
  Uniform u(5);
  std::array<int, 10> bins{};
  const int samples = 100000;
  for (int i = 0; i < samples; ++i) {
    vec3 w = k::sample_cosine(u.next2());
    CHECK(std::abs(glm::length(w) - 1.0f) < 1e-5f);
    ++bins[std::min(9, int(w.z * w.z * 10.0f))];
  }
  for (int b : bins) CHECK(std::abs(double(b) / samples - 0.1) <= 5.0 * std::sqrt(0.1 * 0.9 / samples));
}

// ---------------------------------------------------------------------------------------------
// layer.glsl

TEST_CASE("kernels: refract_down and refract_up obey Snell's law and undo each other") {
  // 45 degrees into eta 1.5: (sin 45 / 1.5, 0, sqrt(1 - 0.5/2.25))
  vec3 down45 = k::refract_down(direction(45, 0), 1.5f);
  CHECK(double(down45.x) == rel(0.47140452079103173));
  CHECK(down45.y == 0.0f);
  CHECK(double(down45.z) == rel(0.8819171036881969));
  // Total internal reflection: from glass (eta = 1/1.5 seen from above) beyond the critical angle.
  CHECK(k::refract_down(direction(60, 0), 1.0f / 1.5f) == vec3(0.0f));
  CHECK(k::refract_up(direction(60, 0), 1.5f) == vec3(0.0f));
  Uniform u(11);
  for (float eta : {1.0f, 1.5f, 1.0f / 1.5f, 2.4f, 0.5f}) {
    for (int i = 0; i < 500; ++i) {
      CAPTURE(eta);
      vec3 w = u.hemisphere();
      vec3 down = k::refract_down(w, eta);
      // The same as GLSL's refract through the macro normal, written by GLM.
      CHECK_VEC3_NEAR(down, -glm::refract(-w, vec3(0.0f, 0.0f, 1.0f), 1.0f / eta), 1e-6f);
      if (down == vec3(0.0f)) {
        // Only under total internal reflection: sin_above > eta.
        CHECK(1.0f - w.z * w.z > eta * eta * (1.0f - 1e-5f));
        continue;
      }
      // n1 sin1 = n2 sin2 with n1 = 1, n2 = eta; the azimuth is kept.
      float sin_above = std::sqrt(w.x * w.x + w.y * w.y), sin_below = std::sqrt(down.x * down.x + down.y * down.y);
      CHECK(std::abs(sin_above - eta * sin_below) <= 2e-6f);
      CHECK(std::abs(w.x * down.y - w.y * down.x) <= 1e-6f);
      CHECK(std::abs(glm::length(down) - 1.0f) <= 1e-6f);
      // Going back up recomputes cos from 1 - eta^2 sin_below^2, which cancels near grazing: compare
      // the azimuthal components directly and z through z^2 = 1 - sin^2.
      vec3 up = k::refract_up(down, eta);
      float scale = std::max(1.0f, eta * eta);
      CHECK(std::abs(up.x - w.x) <= 2e-6f * scale);
      CHECK(std::abs(up.y - w.y) <= 2e-6f * scale);
      CHECK(std::abs(up.z * up.z - w.z * w.z) <= 2e-6f * scale);
    }
  }
}

TEST_CASE("kernels: refraction_jacobian agrees with a finite-difference solid-angle ratio") {
  // cos_above / (eta^2 cos_below) = 0.8 / (2.25 * 0.9) = 0.395061728...
  CHECK(double(k::refraction_jacobian(0.8f, 0.9f, 1.5f)) == rel(0.39506172839506176));
  // The azimuth is unchanged and d omega = -d cos d phi, so d omega_below / d omega_above =
  // d cos_below / d cos_above: central differences of refract_down's z over cos_above +- 2^-10
  // (exact in float, so only the refracted cosines carry rounding).
  const float d = 0x1p-10f;
  auto above = [](float c) { return vec3(std::sqrt(1.0f - c * c), 0.0f, c); };
  int compared = 0;
  for (float eta : {1.5f, 1.0f / 1.5f, 2.4f}) {
    for (float c : {0.95f, 0.8f, 0.6f, 0.4f, 0.25f}) {
      CAPTURE(eta);
      CAPTURE(c);
      vec3 b0 = k::refract_down(above(c - d), eta), b1 = k::refract_down(above(c + d), eta);
      if (b0 == vec3(0.0f) || b1 == vec3(0.0f)) continue;  // beyond the critical angle
      double fd = (double(b1.z) - double(b0.z)) / (2.0 * double(d));
      double j = k::refraction_jacobian(c, k::refract_down(above(c), eta).z, eta);
      CHECK(j == rel(fd, 1e-3));
      ++compared;
    }
  }
  CHECK(compared == 12);  // eta = 1/1.5 refracts only for cos_above > sqrt(1 - 1/2.25) = 0.745
}

TEST_CASE("kernels: absorption is Bouguer-Lambert-Beer along both refracted paths") {
  // exp(-sigma 0.5 (1/0.8 + 1/0.6)) for sigma 0.6, 1, 1:
  // python3 -c "import math; print([math.exp(-s*0.5*(1/0.8+1/0.6)) for s in (0.6,1.0,1.0)])"
  CHECK_VEC3(k::absorption(vec3(0.6f, 1.0f, 1.0f), 0.5f, 0.8f, 0.6f), 0.41686201967850833, 0.23262365791729264,
             0.23262365791729264);
  // Normal incidence: exp(-2 sigma d).
  for (float sigma : {0.0f, 0.35f, 0.98f, 4.0f}) {
    for (float d : {0.0f, 0.2f, 1.5f}) {
      CAPTURE(sigma);
      CAPTURE(d);
      CHECK(double(k::absorption(vec3(sigma), d, 1.0f, 1.0f).x) == rel(std::exp(-2.0 * sigma * d)));
    }
  }
  // Never a gain.
  CHECK(k::absorption(vec3(-1.0f), 1.0f, 0.5f, 0.5f) == vec3(1.0f));
  // A layer without thickness transmits exactly everything, even along grazing paths.
  CHECK(k::absorption(vec3(5.0f), 0.0f, 1.0e-30f, 0.3f) == vec3(1.0f));
}

TEST_CASE("kernels: tir_compensation is Elek's eq. 4 per channel and mirror_across_horizon flips z") {
  // (1 - 0.8) + 0.96 * 0.8 = 0.968; (1 - 0.8) + 0.5 * 0.8 = 0.6
  const vec3 t = k::tir_compensation(vec3(0.96f, 0.5f, 0.96f), 0.8f);
  CHECK(double(t.x) == rel(0.968));
  CHECK(double(t.y) == rel(0.6));
  CHECK(t.z == t.x);
  CHECK(k::tir_compensation(vec3(0.5f), 0.0f) == vec3(1.0f));
  CHECK(k::tir_compensation(vec3(0.5f), 1.0f) == vec3(0.5f));
  CHECK(k::mirror_across_horizon(vec3(0.1f, -0.2f, 0.7f)) == vec3(0.1f, -0.2f, -0.7f));
}

// ---------------------------------------------------------------------------------------------
// texture.glsl

TEST_CASE("kernels: checker_value alternates squares, also for negative coordinates") {
  const vec2 s(8.0f);
  CHECK(k::checker_value(vec2(0.05f, 0.05f), s) == 0.0f);               // 0 + 0
  CHECK(k::checker_value(vec2(0.2f, 0.05f), s) == 1.0f);                // 1 + 0
  CHECK(k::checker_value(vec2(0.2f, 0.2f), s) == 0.0f);                 // 1 + 1
  CHECK(k::checker_value(vec2(-0.05f, 0.05f), s) == 1.0f);              // -1 + 0
  CHECK(k::checker_value(vec2(-0.05f, -0.05f), s) == 0.0f);             // -1 + -1
  CHECK(k::checker_value(vec2(0.3f, 0.7f), vec2(2.0f, 3.0f)) == 0.0f);  // floor(0.6) + floor(2.1) = 0 + 2
  CHECK(k::checker_value(vec2(0.3f, 0.4f), vec2(2.0f, 3.0f)) == 1.0f);  // floor(0.6) + floor(1.2) = 0 + 1
}

TEST_CASE("kernels: remap_value maps ranges linearly and clamps on request") {
  // 10 + (0.25 - 0)/(1 - 0) * (20 - 10) = 12.5
  CHECK(double(k::remap_value(0.25f, 0.0f, 1.0f, 10.0f, 20.0f, false)) == rel(12.5));
  CHECK(double(k::remap_value(1.5f, 0.0f, 1.0f, 10.0f, 20.0f, false)) == rel(25.0));
  CHECK(k::remap_value(1.5f, 0.0f, 1.0f, 10.0f, 20.0f, true) == 20.0f);
  // A reversed output range clamps to its own ends: 1 + (-0.5)(0 - 1) = 1.5 unclamped, 1 clamped.
  CHECK(double(k::remap_value(-0.5f, 0.0f, 1.0f, 1.0f, 0.0f, false)) == rel(1.5));
  CHECK(k::remap_value(-0.5f, 0.0f, 1.0f, 1.0f, 0.0f, true) == 1.0f);
  // 3 + (5 - 4)/(2 - 4) * (7 - 3) = 1 on a reversed input range.
  CHECK(double(k::remap_value(5.0f, 4.0f, 2.0f, 3.0f, 7.0f, false)) == rel(1.0));
  // An empty input range gives out_min rather than a division by zero.
  CHECK(k::remap_value(0.7f, 0.5f, 0.5f, 3.0f, 7.0f, false) == 3.0f);
}

TEST_CASE("kernels: srgb_to_linear is the IEC 61966-2-1 EOTF") {
  // ((0.5 + 0.055)/1.055)^2.4, 0.02/12.92, ((0.9 + 0.055)/1.055)^2.4
  CHECK_VEC3(k::srgb_to_linear(vec3(0.5f, 0.02f, 0.9f)), 0.21404114048223255, 0.0015479876160990713,
             0.7874122893956174);
  CHECK(k::srgb_to_linear(vec3(0.0f)) == vec3(0.0f));
  CHECK_VEC3(k::srgb_to_linear(vec3(1.0f)), 1.0, 1.0, 1.0);
  // The two branches meet at 0.04045 (0.04045 / 12.92 = 0.0031308).
  vec3 below = k::srgb_to_linear(vec3(0.04045f)), above = k::srgb_to_linear(vec3(0.0404501f));
  CHECK(std::abs(below.x - above.x) < 1e-6f);
  // Negative input takes the linear branch, without NaN.
  CHECK(double(k::srgb_to_linear(vec3(-0.1f)).x) == rel(-0.1 / 12.92));
}

TEST_CASE("kernels: srgb_from_linear is the IEC 61966-2-1 OETF, clamped, and inverts srgb_to_linear") {
  // 1.055 * 0.5^(1/2.4) - 0.055, 12.92 * 0.002, 1.055 * 0.9^(1/2.4) - 0.055
  CHECK_VEC3(k::srgb_from_linear(vec3(0.5f, 0.002f, 0.9f)), 0.7353569830524495, 0.02584, 0.9546871718858662);
  CHECK(k::srgb_from_linear(vec3(0.0f)) == vec3(0.0f));
  CHECK_VEC3(k::srgb_from_linear(vec3(1.0f)), 1.0, 1.0, 1.0);
  // Outside [0, 1] it clamps (a display value), without NaN.
  CHECK(k::srgb_from_linear(vec3(-0.5f, 2.0f, -1.0e30f)) == k::srgb_from_linear(vec3(0.0f, 1.0f, 0.0f)));
  // The two branches meet at 0.0031308.
  vec3 below = k::srgb_from_linear(vec3(0.0031308f)), above = k::srgb_from_linear(vec3(0.0031309f));
  CHECK(std::abs(below.x - above.x) < 1e-5f);
  // The EOTF undoes it: 0.21404114048223255 is the linear value of 0.5.
  CHECK(double(k::srgb_from_linear(vec3(0.21404114048223255f)).x) == rel(0.5));
  for (float c : {0.001f, 0.04f, 0.2f, 0.6f, 0.95f})
    CHECK(double(k::srgb_to_linear(k::srgb_from_linear(vec3(c))).x) == rel(double(c), 2e-6));
}

// ---------------------------------------------------------------------------------------------
// Every kernel, at and below the horizon and in the smooth limit.

TEST_CASE("kernels: directions below the horizon give exactly 0") {
  const vec3 up = direction(30, 20), below(0.3f, 0.1f, -0.9f);
  for (float c : {-0.5f, -1e-8f, 0.0f}) {
    CAPTURE(c);
    for (int dist : {0, 1, 2}) {
      CHECK(k::d_microfacet(dist, c, 0.3f) == 0.0f);
      CHECK(k::pdf_microfacet_normal(dist, 0.3f, c) == 0.0f);
      CHECK(k::g_microfacet(dist, c, 0.5f, 0.9f, 0.6f, 0.3f) == 0.0f);
      CHECK(k::g_microfacet(dist, 0.5f, c, 0.9f, 0.6f, 0.3f) == 0.0f);
    }
    CHECK(k::g_vcavity(0.5f, 0.5f, c, 0.6f) == 0.0f);
    CHECK(k::g_vcavity(0.5f, 0.5f, 0.9f, c) == 0.0f);
    CHECK(k::g1_smith_ggx(c, 0.3f) == 0.0f);
    CHECK(k::g_smith_ggx(c, 0.5f, 0.3f) == 0.0f);
    CHECK(k::torrance_sparrow(vec3(1.0f), 1.0f, 1.0f, c, 0.5f) == vec3(0.0f));
    CHECK(k::torrance_sparrow(vec3(1.0f), 1.0f, 1.0f, 0.5f, c) == vec3(0.0f));
    CHECK(k::pdf_cosine(c) == 0.0f);
    CHECK(k::refraction_jacobian(0.5f, c, 1.5f) == 0.0f);
    CHECK(k::refraction_jacobian(c, 0.5f, 1.5f) == 0.0f);
    CHECK(k::absorption(vec3(0.5f), 1.0f, c, 0.5f) == vec3(0.0f));
    CHECK(k::absorption(vec3(0.5f), 1.0f, 0.5f, c) == vec3(0.0f));
  }
  CHECK(k::oren_nayar(below, up, vec3(0.5f), 0.3f) == vec3(0.0f));
  CHECK(k::oren_nayar(up, below, vec3(0.5f), 0.3f) == vec3(0.0f));
  CHECK(k::oren_nayar(vec3(1.0f, 0.0f, 0.0f), up, vec3(0.5f), 0.3f) == vec3(0.0f));
  CHECK(k::refract_down(below, 1.5f) == vec3(0.0f));
  CHECK(k::refract_up(below, 1.5f) == vec3(0.0f));
}

TEST_CASE("kernels: no kernel returns NaN or inf for grazing, zero or smooth-limit arguments") {
  const float cosines[] = {0.0f, 1e-40f, 1e-30f, 1e-8f, 0.5f, 1.0f};
  const float slopes[] = {0.0f, k::LAMINA_MIN_SLOPE, 0.3f, 1.0f, 10.0f};
  const float etas[] = {1.0f, 1.5f, 1.0f / 1.5f, 1e-8f, 0.0f};
  const vec2 us[] = {vec2(0.0f), vec2(0.5f), vec2(0.99999994f), vec2(1.0f)};
  const vec3 gold_n(0.1f, 0.42f, 1.56f), gold_k(3.8f, 2.5f, 1.9f);
  for (float c : cosines) {
    CAPTURE(c);
    float s = std::sqrt(1.0f - c * c);
    vec3 w(s, 0.0f, c), w2(-s * 0.6f, s * 0.8f, c);
    CHECK(is_finite(k::lamina_safe_sqrt(c)));
    CHECK(is_finite(k::fresnel_schlick(c, 0.04f)));
    CHECK(is_finite(k::fresnel_conductor(c, gold_n, gold_k)));
    CHECK(is_finite(k::fresnel_conductor(c, vec3(0.0f), vec3(0.0f))));
    CHECK(is_finite(k::fresnel_lazanyi(c, gold_n, gold_k)));
    CHECK(is_finite(k::pdf_cosine(c)));
    CHECK(is_finite(k::tir_compensation(vec3(c), c)));
    for (float eta : etas) {
      CAPTURE(eta);
      CHECK(is_finite(k::fresnel_dielectric(c, eta)));
      CHECK(is_finite(k::fresnel_conductor(c, vec3(eta), vec3(0.0f))));
      CHECK(is_finite(k::refract_down(w, eta)));
      CHECK(is_finite(k::refract_up(w, eta)));
      for (float c2 : cosines) {
        CHECK(is_finite(k::refraction_jacobian(c, c2, eta)));
        CHECK(is_finite(k::absorption(vec3(0.0f, 0.5f, 100.0f), eta, c, c2)));
      }
    }
    for (float m : slopes) {
      CAPTURE(m);
      CHECK(is_finite(k::d_beckmann(c, m)));
      CHECK(is_finite(k::blinn_exponent(m)));
      CHECK(is_finite(k::d_blinn(c, m)));
      CHECK(is_finite(k::d_ggx(c, m)));
      CHECK(is_finite(k::g1_smith_ggx(c, m)));
      CHECK(is_finite(k::oren_nayar(w, w2, vec3(1.0f), m)));
      CHECK(is_finite(k::oren_nayar(w, -w2 * vec3(1.0f, 1.0f, -1.0f), vec3(1.0f), m)));
      for (int dist : {0, 1, 2}) {
        CHECK(is_finite(k::pdf_microfacet_normal(dist, m, c)));
        for (float c2 : cosines) {
          CHECK(is_finite(k::g_microfacet(dist, c, c2, c, c2, m)));
          float d = k::d_microfacet(dist, c, m);
          float g = k::g_microfacet(dist, c2, c2, c, c2, m);
          CHECK(is_finite(k::torrance_sparrow(vec3(1.0f), d, g, c2, c2)));
          CHECK(is_finite(k::torrance_sparrow(vec3(1.0f), d, 1.0f, c, c2)));
        }
        for (vec2 u : us) {
          vec3 h = k::sample_microfacet_normal(dist, m, u);
          CHECK(is_finite(h));
          CHECK(h.z >= 0.0f);
        }
      }
    }
  }
  for (vec2 u : us) CHECK(is_finite(k::sample_cosine(u)));
  CHECK(is_finite(k::remap_value(1.0f, 0.0f, 0.0f, 0.0f, 1.0f, false)));
  // The largest numbers a file may hold, and a range so narrow that t overflows: the result
  // saturates instead of becoming inf, and a chain of remaps never meets inf - inf.
  CHECK(double(k::LAMINA_MAX_VALUE) == lamina::kMaxNodeNumber);
  const float big = k::LAMINA_MAX_VALUE;
  CHECK(k::remap_value(big, 0.0f, 1.0e-30f, -big, big, false) == big);
  CHECK(k::remap_value(-big, 0.0f, 1.0e-30f, -big, big, false) == -big);
  float chained = k::remap_value(big, 0.0f, 1.0e-30f, 0.0f, big, false);
  CHECK(chained == big);
  CHECK(k::remap_value(chained, -big, big, big, big, false) == big);
  CHECK(is_finite(k::remap_value(big, -big, big, -big, big, false)));
  CHECK(is_finite(k::srgb_to_linear(vec3(-1.0f, 0.0f, 2.0f))));
}

// ---------------------------------------------------------------------------------------------
// stack.glsl

TEST_CASE("kernels: lamina_slope converts degrees to a tangent and clamps both forms") {
  // tan(30 deg) = 0.5773502691896257
  CHECK(double(k::lamina_slope(30.0f, true)) == rel(0.5773502691896257));
  CHECK(double(k::lamina_slope(60.0f, true)) == rel(1.0));  // clamped to 45 deg
  CHECK(k::lamina_slope(-5.0f, true) == 0.0f);
  CHECK(k::lamina_slope(0.3f, false) == 0.3f);
  CHECK(k::lamina_slope(1.7f, false) == 1.0f);
  CHECK(k::lamina_effective_slope(0.1f, 0.4f, true) == 0.4f);
  CHECK(k::lamina_effective_slope(0.1f, 0.4f, false) == 0.1f);
  CHECK(k::lamina_effective_slope(0.0f, 0.0f, false) == k::LAMINA_MIN_SLOPE);
}

TEST_CASE("kernels: lamina_positive_mod and lamina_wrap_index handle negative texel indices") {
  CHECK(k::lamina_positive_mod(-1, 4) == 3);
  CHECK(k::lamina_positive_mod(-4, 4) == 0);
  CHECK(k::lamina_positive_mod(-5, 4) == 3);
  CHECK(k::lamina_positive_mod(9, 4) == 1);
  CHECK(k::lamina_positive_mod(-1000000, 7) == ((-1000000 % 7) + 7) % 7);
  // repeat
  CHECK(k::lamina_wrap_index(-1, 4, 0) == 3);
  CHECK(k::lamina_wrap_index(4, 4, 0) == 0);
  // clamp to edge
  CHECK(k::lamina_wrap_index(-3, 4, 1) == 0);
  CHECK(k::lamina_wrap_index(7, 4, 1) == 3);
  // mirrored repeat: ... 1 0 | 0 1 2 3 | 3 2 1 0 | 0 ...
  CHECK(k::lamina_wrap_index(-1, 4, 2) == 0);
  CHECK(k::lamina_wrap_index(-2, 4, 2) == 1);
  CHECK(k::lamina_wrap_index(4, 4, 2) == 3);
  CHECK(k::lamina_wrap_index(7, 4, 2) == 0);
  CHECK(k::lamina_wrap_index(8, 4, 2) == 0);
}

TEST_CASE("kernels: lamina_bilinear_texels puts texel centres at (i + 0.5) / size") {
  glm::ivec4 t;
  // uv (0.5, 0.5) on 4 x 2: x = 1.5, y = 0.5 -> texels (1, 0, 2, 1), weights (0.5, 0.5).
  vec2 w = k::lamina_bilinear_texels(vec2(0.5f, 0.5f), 4, 2, 0, t);
  CHECK(t == glm::ivec4(1, 0, 2, 1));
  CHECK(w == vec2(0.5f, 0.5f));
  // uv (0, 0) repeats onto the last texel with weight 0.5: x = -0.5 -> x0 = -1 -> 3.
  w = k::lamina_bilinear_texels(vec2(0.0f), 4, 2, 0, t);
  CHECK(t == glm::ivec4(3, 1, 0, 0));
  CHECK(w == vec2(0.5f, 0.5f));
  // A NaN coordinate reads texel (0, 0) with weight 0.
  w = k::lamina_bilinear_texels(vec2(std::nanf(""), 0.5f), 4, 2, 0, t);
  CHECK(t == glm::ivec4(0));
  CHECK(w == vec2(0.0f));
}

TEST_CASE("kernels: lamina_image_uv rotates about the centre, then scales and offsets") {
  // (1, 0.5) rotated 90 deg about (0.5, 0.5) -> (0.5, 1); times (2, 3) plus (0.1, 0.2) -> (1.1, 3.2)
  vec2 uv = k::lamina_image_uv(vec2(1.0f, 0.5f), 90.0f, vec2(2.0f, 3.0f), vec2(0.1f, 0.2f));
  CHECK(double(uv.x) == doctest::Approx(1.1).epsilon(1e-6).scale(0.0));
  CHECK(double(uv.y) == doctest::Approx(3.2).epsilon(1e-6).scale(0.0));
}

TEST_CASE("kernels: the interface step passes T t down and returns the interface's own reflection") {
  const vec3 l = direction(30, 0), v = direction(45, 180);
  vec3 lb, vb, passed;
  const float m = 0.2f, eta = 1.5f;
  for (int mode : {0, 1, 2}) {
    CAPTURE(mode);
    const vec3 f = k::lamina_interface_eval(l, v, eta, 0, mode, m, lb, vb, passed);
    const vec3 h = glm::normalize(l + v);
    const float vh = 0.5f * (glm::dot(v, h) + glm::dot(l, h));
    // The Fresnel term the mode selects: exact, Schlick with F0 = 0.04, or Lazanyi with k = 0.
    const float fr = mode == 0   ? k::fresnel_dielectric(vh, eta)
                     : mode == 1 ? k::fresnel_schlick(vh, 0.04f)
                                 : k::fresnel_lazanyi(vh, vec3(eta), vec3(0.0f)).x;
    const float g = k::g_microfacet(0, l.z, v.z, h.z, vh, m);
    const vec3 want = k::torrance_sparrow(vec3(fr), k::d_microfacet_h(0, h, m), g, l.z, v.z);
    CHECK_VEC3(f, double(want.x), double(want.y), double(want.z));
    CHECK_VEC3_NEAR(lb, k::refract_down(l, eta), 0.0f);
    CHECK_VEC3_NEAR(passed, vec3((1.0f - fr) * ((1.0f - g) + (1.0f - fr) * g)), 1e-7f);
    // The lobe selection's (1 - F)^2 at wo uses the same mode.
    float factor = 0.0f;
    const vec3 below = k::lamina_selection_step(v, eta, mode, vec3(0.0f), 0.0f, factor);
    const float fv = k::lamina_fresnel_dielectric(mode, v.z, eta);
    CHECK(below == k::refract_down(v, eta));
    CHECK(double(factor) == rel(double(1.0f - fv) * double(1.0f - fv)));
  }
  // The conductor lobe: Torrance-Sparrow with the mode's conductor Fresnel term.
  const vec3 n(0.3f, 0.5f, 1.2f), kk(3.2f, 2.6f, 2.2f);
  for (int mode : {0, 1, 2}) {
    CAPTURE(mode);
    const vec3 h = glm::normalize(l + v);
    const float vh = 0.5f * (glm::dot(v, h) + glm::dot(l, h));
    const vec3 fr = mode == 0   ? k::fresnel_conductor(vh, n, kk)
                    : mode == 1 ? k::fresnel_schlick_rgb(vh, k::conductor_f0(n, kk))
                                : k::fresnel_lazanyi(vh, n, kk);
    const vec3 want =
        k::torrance_sparrow(fr, k::d_microfacet_h(2, h, m), k::g_microfacet(2, l.z, v.z, h.z, vh, m), l.z, v.z);
    CHECK_VEC3_NEAR(k::lamina_conductor_eval(l, v, n, kk, vec3(1.0f), 0.0f, 2, mode, m), want, 0.0f);
  }
}

TEST_CASE("kernels: lobe sampling stays in the upper hemisphere and its densities are positive there") {
  Uniform u(17);
  for (int i = 0; i < 2000; ++i) {
    const vec3 v = u.hemisphere();
    bool inside = false;
    const vec3 w = k::lamina_sample_microfacet_lobe(0, 0.3f, v, u.next2(), 1.5f, inside);
    if (w == vec3(0.0f)) continue;
    CHECK(w.z > 0.0f);
    CHECK(std::abs(glm::length(w) - 1.0f) < 1e-5f);
    if (inside) CHECK((1.0f - w.z * w.z) * 2.25f <= 1.0f);
    const vec3 d = k::lamina_sample_diffuse_lobe(u.next2(), 1.5f);
    CHECK(d.z >= k::lamina_cos_critical(1.5f) - 1e-6f);
  }
}

TEST_CASE("kernels: d_microfacet_h equals d_microfacet and keeps its accuracy near the normal") {
  // Same values as the cos_h forms where cos_h is well conditioned.
  for (int dist = 0; dist < 3; ++dist)
    for (float theta : {5.0f, 20.0f, 40.0f, 70.0f}) {
      const vec3 h = direction(theta, 30.0);
      for (float m : {0.1f, 0.3f, 0.7f}) {
        double want = k::d_microfacet(dist, h.z, m), got = k::d_microfacet_h(dist, h, m);
        if (want == 0.0)
          CHECK(got < 1e-30);  // both beyond the Beckmann cut-off
        else
          CHECK(got == doctest::Approx(want).epsilon(2e-4).scale(0.0));
      }
    }
  // A narrow lobe (m = tan 1 deg) near its peak, against double precision from the components:
  // python3: import math; t=math.radians(0.8); m=math.tan(math.radians(1)); s2=math.sin(t)**2;
  //   c2=math.cos(t)**2; beck=math.exp(-(s2/c2)/m**2)/(math.pi*m**2*c2*c2); a2=m*m;
  //   ggx=a2/(math.pi*(a2*c2+s2)**2); e=2/m**2-2; blinn=(e+2)/(2*math.pi)*math.cos(t)**e
  const vec3 h = direction(0.8, 10.0);
  const float m = std::tan(float(kPi) / 180.0f);
  double t = 0.8 * kPi / 180.0, md = std::tan(kPi / 180.0), s2 = std::sin(t) * std::sin(t), c2 = 1.0 - s2;
  double beckmann = std::exp(-(s2 / c2) / (md * md)) / (kPi * md * md * c2 * c2);
  double ggx = md * md / (kPi * std::pow(md * md * c2 + s2, 2.0));
  double e = 2.0 / (md * md) - 2.0, blinn = (e + 2.0) / (2.0 * kPi) * std::pow(std::cos(t), e);
  CHECK(double(k::d_microfacet_h(0, h, m)) == rel(beckmann, 2e-5));
  CHECK(double(k::d_microfacet_h(1, h, m)) == rel(blinn, 2e-5));
  CHECK(double(k::d_microfacet_h(2, h, m)) == rel(ggx, 2e-5));
  CHECK(k::d_microfacet_h(0, vec3(0.6f, 0.8f, 0.0f), 0.3f) == 0.0f);
  CHECK(k::d_microfacet_h(3, h, m) == 0.0f);
}
