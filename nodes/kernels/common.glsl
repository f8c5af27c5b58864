// lamina kernels: shared constants and helpers.
//
// Every file in nodes/kernels/ is written once, in the common subset of GLSL (330 core, 450 core,
// ES 3.00) and C++20 with GLM; kernels.h includes them into C++, the GLSL back end pastes them
// verbatim after a prelude. Conventions for all kernels:
//   - local shading frame, z is the macro normal, cos_theta(w) = w.z; directions have unit length;
//   - wi and wo both point away from the surface; BRDFs exclude the cosine;
//   - a direction below the horizon gives 0, and no argument produces NaN or inf: every division
//     and square root is guarded;
//   - m is the Beckmann RMS slope, tan of the course's roughness angle.
// Rules of the subset: float literals carry the f suffix, conversions are explicit (float(i)),
// no overloading, recursion, default arguments, swizzle assignment, inout, struct constructors or
// struct initialisers (assign members one by one). Structs and arrays of them are fine; array and
// struct parameters are written with the macros below, and an array parameter's size is always
// LAMINA_STACK, or for a blend of parts (stack.glsl) LAMINA_PARTS, LAMINA_PARTS * LAMINA_STACK or
// LAMINA_BLEND.

// The macros the kernels are written with. kernels.h defines them for C++ before it includes the
// files; this is their GLSL meaning, which the GLSL back end embeds with the kernels:
//   LAMINA_FN              before every kernel function: empty (`inline` in C++)
//   LAMINA_OUT(T)          an output parameter: `out T` (`T&`)
//   LAMINA_IN(T)           a struct parameter read only: `T` (`const T&`)
//   LAMINA_IN_ARRAY(T)     an array parameter read only: `T` (`const T`, so `T name[N]` decays to
//                          a pointer to const)
//   LAMINA_OUT_ARRAY(T)    an array parameter written: `out T` (`T`)
// and LAMINA_STACK, the length of the arrays the stack composition (stack.glsl) works on: the
// number of stack entries of the largest material in a GLSL module (or of the longest part of a
// blend), defined by the back end before the kernels (128 in C++, kMaxStackEntries), with
// LAMINA_PARTS, the most parts a blend of the module has, and LAMINA_BLEND, its blend's entries.
#ifndef LAMINA_FN
#define LAMINA_FN
#define LAMINA_OUT(T) out T
#define LAMINA_IN(T) T
#define LAMINA_IN_ARRAY(T) T
#define LAMINA_OUT_ARRAY(T) out T
#endif

const float LAMINA_PI = 3.14159265358979f;
const float LAMINA_INV_PI = 0.318309886183791f;

// The smallest denominator a kernel divides by where the true quotient may grow without bound
// at grazing angles (1/cos): quotients stay below about 1e20 times the numerator, finite in
// float and in GLSL highp. Not part of the pinned API; kernels use it internally.
const float LAMINA_MIN_DENOM = 1.0e-20f;

// The largest magnitude a texture operation outputs (graph/limits.h's kMaxNodeNumber, the largest a
// node parameter may be): values past it saturate, so that chained operations stay finite.
const float LAMINA_MAX_VALUE = 1.0e9f;

LAMINA_FN float lamina_sqr(float x) { return x * x; }

// The diagonal matrix of a vector (mat3 is column-major in glm and GLSL alike).
LAMINA_FN mat3 lamina_diagonal(vec3 d) {
  return mat3(vec3(d.x, 0.0f, 0.0f), vec3(0.0f, d.y, 0.0f), vec3(0.0f, 0.0f, d.z));
}

// Relative luminance of linear sRGB / Rec. 709 primaries (ITU-R BT.709-6, item 3.2).
LAMINA_FN float lamina_luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

LAMINA_FN float lamina_safe_sqrt(float x) { return sqrt(max(x, 0.0f)); }

// arccos as a polynomial (Abramowitz and Stegun, Handbook of Mathematical Functions, 4.4.46):
// acos(x) = sqrt(1 - x) (a0 + a1 x + ... + a7 x^7) for 0 <= x <= 1, |error| <= 2e-8, and
// acos(-x) = pi - acos(x). The kernels' own arithmetic rather than the platform's acos, whose
// rounding differs between C++ libraries and GLSL implementations by far more than float's: a
// formula that cancels (Oren-Nayar near grazing) would turn that into visible CPU/GPU differences.
LAMINA_FN float lamina_acos(float x) {
  float a = min(abs(x), 1.0f);
  float p = -0.0012624911f;
  p = p * a + 0.0066700901f;
  p = p * a - 0.0170881256f;
  p = p * a + 0.0308918810f;
  p = p * a - 0.0501743046f;
  p = p * a + 0.0889789874f;
  p = p * a - 0.2145988016f;
  p = p * a + 1.5707963050f;
  float r = sqrt(1.0f - a) * p;
  return x < 0.0f ? LAMINA_PI - r : r;
}

// 1 - exp(-y) for y >= 0, accurate to float precision also where exp(-y) is within rounding of 1
// (1 - exp(-y) loses every digit there): below 1/4 the Taylor series to y^6, whose remainder
// y^7 / 5040 is under 5e-8 of the value; above, the subtraction loses less than 3e-7.
LAMINA_FN float lamina_one_minus_exp(float y) {
  float series =
      y * (1.0f - y * (0.5f - y * (1.0f / 6.0f - y * (1.0f / 24.0f - y * (1.0f / 120.0f - y * (1.0f / 720.0f))))));
  return y < 0.25f ? series : 1.0f - exp(-y);
}

// erfc(x) for x >= 0, Abramowitz and Stegun 7.1.26 (absolute error below 1.5e-7), in the form
// poly(t) exp(-x^2) so that the exponential factors out of lamina_smith_lambda.
LAMINA_FN float lamina_erfc_poly(float x) {
  float t = 1.0f / (1.0f + 0.3275911f * x);
  return t * (0.254829592f + t * (-0.284496736f + t * (1.421413741f + t * (-1.453152027f + t * 1.061405429f))));
}

// erf(x) for any x: 1 - erfc(|x|) by lamina_erfc_poly, with erf's odd symmetry.
LAMINA_FN float lamina_erf(float x) {
  float a = abs(x);
  float e = 1.0f - lamina_erfc_poly(a) * exp(-a * a);
  return x < 0.0f ? -e : e;
}

// The standard normal's distribution function Phi(z) and density phi(z).
LAMINA_FN float lamina_normal_cdf(float z) { return 0.5f * (1.0f + lamina_erf(z * 0.70710678f)); }
LAMINA_FN float lamina_normal_pdf(float z) { return 0.39894228f * exp(-0.5f * z * z); }

// The inverse error function on (-1, 1): Giles 2010 ("Approximating the erfinv function", GPU
// Computing Gems), single-precision form, two polynomials in w = -log((1 - x)(1 + x)), the second
// in sqrt(w) for the tails (relative error near 1e-7; the test checks it against an inversion of
// erf in double). Both are evaluated and one selected, without a branch; x is clamped to within
// 2^-24 of +-1, so the result stays finite (|erfinv| < 3.9).
LAMINA_FN float lamina_erfinv(float x) {
  float y = clamp(x, -0.99999994f, 0.99999994f);
  float w = -log((1.0f - y) * (1.0f + y));
  float c = w - 2.5f;
  float central = 2.81022636e-08f;
  central = 3.43273939e-07f + central * c;
  central = -3.5233877e-06f + central * c;
  central = -4.39150654e-06f + central * c;
  central = 0.00021858087f + central * c;
  central = -0.00125372503f + central * c;
  central = -0.00417768164f + central * c;
  central = 0.246640727f + central * c;
  central = 1.50140941f + central * c;
  float t = sqrt(w) - 3.0f;
  float tail = -0.000200214257f;
  tail = 0.000100950558f + tail * t;
  tail = 0.00134934322f + tail * t;
  tail = -0.00367342844f + tail * t;
  tail = 0.00573950773f + tail * t;
  tail = -0.0076224613f + tail * t;
  tail = 0.00943887047f + tail * t;
  tail = 1.00167406f + tail * t;
  tail = 2.83297682f + tail * t;
  return (w < 5.0f ? central : tail) * y;
}
