// The reference solver (graph/cpu/reference.h) and the rough boundary it walks through
// (nodes/kernels/boundary.glsl), each checked on its own: the boundary against a double-precision
// transcription of Walter et al. 2007 and against its own sampler, the walks against closed forms,
// against each other and against the laws every BRDF obeys.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

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

double walter_g1(int distribution, double cos_v, double m) {
  const double tan_v = std::sqrt(1.0 - cos_v * cos_v) / cos_v;
  if (distribution == 2) return 2.0 / (1.0 + std::sqrt(1.0 + m * m * tan_v * tan_v));  // eq. 34
  const double e = 2.0 / (m * m) - 2.0;
  const double a = distribution == 0 ? 1.0 / (m * tan_v) : std::sqrt(0.5 * e + 1.0) / tan_v;  // sec. 5.2
  if (a >= 1.6) return 1.0;
  return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);  // eq. 27
}

double walter_bsdf(dvec3 i, dvec3 o, const BoundaryCase& c) {
  const double eta_i = i.z > 0.0 ? 1.0 : c.eta, eta_o = o.z > 0.0 ? 1.0 : c.eta;
  const dvec3 n(0.0, 0.0, 1.0);
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
    const vec3 l = random_direction(rng), e = random_direction(rng);
    if (std::abs(l.z) < 0.05f || std::abs(e.z) < 0.05f) continue;  // float V.H cancels at grazing
    const double expected = walter_bsdf(test::to_double(l), test::to_double(e), c);
    const double got = k::lamina_boundary_eval(l, e, c.eta, c.distribution, 0, c.m);
    if (expected < 1e-6 && got < 1e-6) continue;
    ++compared;
    INFO("distribution " << c.distribution << " m " << c.m << " eta " << c.eta << " l " << l.x << "," << l.y << ","
                         << l.z << " e " << e.x << "," << e.y << "," << e.z);
    CHECK(got == doctest::Approx(expected).epsilon(2e-3));
  }
  CHECK(compared > 2000);
}

TEST_CASE("a rough boundary obeys the radiance law of refraction: f(l, e) / n_e^2 = f(e, l) / n_l^2") {
  std::mt19937_64 rng(12);
  for (int n = 0; n < 20000; ++n) {
    const BoundaryCase c = random_boundary(rng);
    const vec3 l = random_direction(rng), e = random_direction(rng);
    const double n_l = l.z > 0.0f ? 1.0 : c.eta, n_e = e.z > 0.0f ? 1.0 : c.eta;
    const double forward = k::lamina_boundary_eval(l, e, c.eta, c.distribution, c.fresnel, c.m) / (n_e * n_e);
    const double backward = k::lamina_boundary_eval(e, l, c.eta, c.distribution, c.fresnel, c.m) / (n_l * n_l);
    CHECK(forward == doctest::Approx(backward).epsilon(1e-4));
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
    // Quadrature needs lobes wider than its cells. Blinn's G1 borrows Beckmann's through Walter's
    // mapping (sec. 5.2), which overestimates it for broad lobes: at slope 1 a boundary scatters up
    // to 11% more than it receives (README, "Reference solver"), so Blinn is held to slopes <= 0.45.
    c.m = float(0.2 + (c.distribution == 1 ? 0.25 : 0.4) * test::uniform(rng));
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
    CHECK(density == doctest::Approx(double(kept) / draws).epsilon(0.01));
    CHECK(mean == doctest::Approx(scattered).epsilon(0.01 + 4.0 * error / scattered));
    CHECK(scattered <= 1.0 + 0.005);
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

TEST_CASE("over a black base the reference is exactly the top boundary's reflection") {
  const cpu::Evaluator e =
      test::evaluator_from_text(coat_over(R"({"id": "base", "type": "substrate/lambert", "albedo": [0, 0, 0]})", 15.0));
  const cpu::ShadingPoint point = e.bind({});
  const cpu::ReferenceOptions options{2000, 1000, 0};
  for (auto [ti, to] : {std::pair{10.0, 30.0}, std::pair{45.0, 60.0}, std::pair{70.0, 5.0}}) {
    const vec3 wi = direction_at(ti, 0.0), wo = direction_at(to, 180.0);
    const cpu::ReferenceEstimate r = cpu::reference_eval(point, wi, wo, options);
    const auto& p = point.stack().params[0];
    const auto& x = point.stack().entries[0];
    const double expected = k::lamina_boundary_eval(wi, wo, p.eta, x.distribution, x.fresnel, p.m);
    CHECK(r.value.r == doctest::Approx(expected).epsilon(1e-6));
    CHECK(r.std_error.r == 0.0);
  }
}

TEST_CASE("a smooth lossless coat over a white Lambert base reflects all the light it receives") {
  // A 1 degree coat loses under 1e-3 to its microfacets' masking; a rough one loses more (the
  // boundary is single-scattering), which the README's reference section states.
  const cpu::Evaluator e =
      test::evaluator_from_text(coat_over(R"({"id": "base", "type": "substrate/lambert", "albedo": [1, 1, 1]})", 1.0));
  const cpu::ShadingPoint point = e.bind({});
  const cpu::ReferenceOptions options{40000 / test::kSanitizerDivisor, 1000, 3};
  for (double theta : {0.0, 40.0, 75.0}) {
    const cpu::ReferenceEstimate r = cpu::reference_albedo(point, direction_at(theta, 0.0), options);
    INFO("theta " << theta << " albedo " << r.value.r << " +- " << r.std_error.r);
    CHECK(within(r.value, dvec3(1.0), r.std_error, 4.0, 1e-3));
    CHECK(r.truncated_walks == 0);
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
  for (int c = 0; c < 3; ++c) CHECK(r.value[c] == doctest::Approx(expected[c]).epsilon(1e-5));
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
    return list;
  }();
  return all;
}

TEST_CASE("the reference BRDF integrates to the reference albedo: two estimators, one answer") {
  // The albedo walk only follows light out; the BRDF estimator joins walks to wi through the top
  // boundary in two ways weighed against each other. The cosine-weighted mean of pi f over wi is
  // the albedo, so a wrong weight or density shows here. Rough interfaces keep the quadrature's
  // variance low; every example with a rough top takes part.
  std::mt19937_64 rng(14);
  const int directions = 384 / test::kSanitizerDivisor, walks = 256;
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
        // Cosine-weighted wi: the estimate of the albedo is pi f(wi, wo).
        const double u1 = (i + test::uniform(rng)) / directions, u2 = test::uniform(rng);
        const vec3 wi = test::to_float(test::from_cosine(std::sqrt(1.0 - u1), 2.0 * test::kPi * u2));
        if (!(wi.z > 0.0f)) continue;
        const dvec3 x = test::kPi * cpu::reference_eval(point, wi, wo, {walks, 1000, uint64_t(i)}).value;
        sum += x;
        sum_sq += x * x;
      }
      const dvec3 integral = sum / double(directions);
      const dvec3 error =
          glm::sqrt(glm::max(sum_sq / double(directions) - integral * integral, dvec3(0.0)) / double(directions));
      const cpu::ReferenceEstimate albedo = cpu::reference_albedo(point, wo, {20000, 1000, 0});
      INFO(m.name << " theta " << theta << " integral " << integral.r << " " << integral.g << " " << integral.b
                  << " +- " << error.r << " albedo " << albedo.value.r << " " << albedo.value.g << " " << albedo.value.b
                  << " +- " << albedo.std_error.r);
      CHECK(within(integral, albedo.value, glm::sqrt(error * error + albedo.std_error * albedo.std_error), 4.5, 2e-3));
      ++compared;
    }
  }
  CHECK(compared >= 8);
}

TEST_CASE("the reference never creates energy and is reciprocal within its error, for every example") {
  test::parallel_for(materials().size(), [&](size_t index) {
    const Material& m = materials()[index];
    const cpu::ShadingPoint point = m.evaluator.bind({});
    for (double theta : {0.0, 50.0, 85.0}) {
      const cpu::ReferenceEstimate a = cpu::reference_albedo(point, direction_at(theta, 0.0), {20000, 1000, 0});
      INFO(m.name << " theta " << theta << " albedo " << a.value.r << " " << a.value.g << " " << a.value.b);
      CHECK(within(glm::min(a.value, dvec3(1.0)), a.value, a.std_error, 4.0, 1e-3));
      CHECK(a.value.r >= 0.0);
    }
    for (auto [wi, wo] : {std::pair{direction_at(20.0, 0.0), direction_at(50.0, 120.0)},
                          std::pair{direction_at(70.0, 30.0), direction_at(35.0, 250.0)}}) {
      const cpu::ReferenceEstimate forward = cpu::reference_eval(point, wi, wo, {20000, 1000, 0});
      const cpu::ReferenceEstimate backward = cpu::reference_eval(point, wo, wi, {20000, 1000, 0});
      const dvec3 error = glm::sqrt(forward.std_error * forward.std_error + backward.std_error * backward.std_error);
      INFO(m.name << " f(wi, wo) " << forward.value.r << " " << forward.value.g << " " << forward.value.b
                  << " f(wo, wi) " << backward.value.r << " " << backward.value.g << " " << backward.value.b);
      CHECK(within(forward.value, backward.value, error, 4.5, 1e-4 * (1.0 + forward.value.g)));
    }
  });
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
