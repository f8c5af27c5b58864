#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <set>

#include "graph/registry.h"
#include "nodes/metals.h"

using namespace lamina;

TEST_CASE("the node types this release promises are all registered") {
  std::set<std::string> expected = {"interface/dielectric",
                                    "medium/clear",
                                    "medium/absorbing",
                                    "substrate/lambert",
                                    "substrate/oren_nayar",
                                    "substrate/conductor",
                                    "layer",
                                    "mix",
                                    "texture/image",
                                    "texture/checker",
                                    "math/remap"};
  // A promise is kept while its types stay; new types join without editing this list.
  auto names = NodeRegistry::builtin().type_names();
  const std::set<std::string> registered(names.begin(), names.end());
  for (const std::string& type : expected) CHECK_MESSAGE(registered.count(type) == 1, type << " is not registered");
}

TEST_CASE("every declaration is complete and its defaults obey its own ranges") {
  for (const auto& d : NodeRegistry::builtin().all()) {
    CAPTURE(d.type);
    CHECK_FALSE(d.doc.empty());
    REQUIRE_FALSE(d.outputs.empty());
    CHECK(d.type.find(std::string(kind_name(d.kind))) == 0);
    std::set<std::string> names;
    for (const auto& p : d.params) {
      CAPTURE(p.name);
      CHECK(names.insert(p.name).second);
      CHECK_FALSE(p.doc.empty());
      CHECK((p.lo < p.hi || !p.has_range()));
      // Quaternions, nested objects and text lengths are scene-file declarations: the material
      // reader has no case for them. Whole numbers (counts, seeds) are constants: a texture
      // register holds a float, not a count.
      if (p.type == ValueType::Integer) CHECK_FALSE(p.linkable);
      CHECK(p.type != ValueType::Quaternion);
      CHECK(p.type != ValueType::Object);
      CHECK(p.max_length == 0);
      if (p.type == ValueType::Enum) {
        CHECK_FALSE(p.choices.empty());
        if (p.fallback)
          CHECK(std::find(p.choices.begin(), p.choices.end(), std::get<std::string>(*p.fallback)) != p.choices.end());
      }
      if (!p.fallback) continue;
      auto in_range = [&](double v) { return (p.lo_open ? v > p.lo : v >= p.lo) && v <= p.hi; };
      if (const auto* v = std::get_if<double>(&*p.fallback)) CHECK(in_range(*v));
      if (const auto* v = std::get_if<Vec3d>(&*p.fallback))
        for (double c : *v) CHECK(in_range(c));
      if (const auto* v = std::get_if<Vec2d>(&*p.fallback))
        for (double c : *v) CHECK(in_range(c));
      bool type_fits = false;
      switch (p.type) {
        case ValueType::Float:
        case ValueType::Integer: type_fits = std::holds_alternative<double>(*p.fallback); break;
        case ValueType::Color:
        case ValueType::Vec3: type_fits = std::holds_alternative<Vec3d>(*p.fallback); break;
        case ValueType::Vec2: type_fits = std::holds_alternative<Vec2d>(*p.fallback); break;
        case ValueType::Bool: type_fits = std::holds_alternative<bool>(*p.fallback); break;
        case ValueType::Enum:
        case ValueType::String: type_fits = std::holds_alternative<std::string>(*p.fallback); break;
        default: type_fits = std::holds_alternative<Link>(*p.fallback); break;
      }
      CHECK(type_fits);
    }
    for (const auto& alt : d.alternatives)
      for (const auto& set : alt.sets)
        for (const auto& member : set) CHECK(d.find_param(member) != nullptr);
  }
}

TEST_CASE("structural inputs take the closure types that make a stack") {
  const auto* layer = NodeRegistry::builtin().find("layer");
  REQUIRE(layer);
  CHECK(layer->find_param("interface")->type == ValueType::Interface);
  CHECK(layer->find_param("interface")->required());
  CHECK(layer->find_param("medium")->type == ValueType::Medium);
  CHECK_FALSE(layer->find_param("medium")->required());
  CHECK(layer->find_param("base")->type == ValueType::Stack);
  for (const auto& d : NodeRegistry::builtin().all())
    if (d.kind == NodeKind::Substrate) CHECK(d.find_param("base") == nullptr);
}

TEST_CASE("the course's metal constants are carried exactly") {
  const Metal* gold = find_metal("gold");
  REQUIRE(gold);
  CHECK(gold->n == Vec3d{0.1, 0.42, 1.56});
  CHECK(gold->k == Vec3d{3.8, 2.5, 1.9});
  CHECK(find_metal("silver")->n == Vec3d{0.14, 0.13, 0.157});
  CHECK(find_metal("silver")->k == Vec3d{4.44, 3.25, 2.40});
  CHECK(find_metal("aluminium")->n == Vec3d{1.94, 1.0, 0.6});
  CHECK(find_metal("aluminium")->k == Vec3d{8.21, 6.69, 4.86});
  CHECK(find_metal("unobtainium") == nullptr);
  for (const auto& m : metals()) CHECK_FALSE(m.source.empty());
}

TEST_CASE("chromium's n and k follow from Rakic's Lorentz-Drude model at 650, 550 and 450 nm") {
  // Rakic et al. 1998, Table 1 (Cr): plasma energy 10.75 eV; Drude f0 = 0.168, gamma0 = 0.047 eV;
  // oscillators (f, gamma, omega) in eV. eps(w) = 1 - f0 wp^2 / (w (w + i gamma0))
  //                                               + sum f_j wp^2 / (w_j^2 - w^2 - i w gamma_j).
  const double wp = 10.75;
  const double osc[4][3] = {{0.151, 3.175, 0.121}, {0.150, 1.305, 0.543}, {1.149, 2.676, 1.970}, {0.825, 1.335, 8.775}};
  const Metal* cr = find_metal("chromium");
  REQUIRE(cr);
  const double wavelengths[3] = {650.0, 550.0, 450.0};
  for (int c = 0; c < 3; ++c) {
    double w = 1239.84193 / wavelengths[c];  // photon energy in eV
    std::complex<double> eps = 1.0 - 0.168 * wp * wp / (w * std::complex<double>(w, 0.047));
    for (const auto& o : osc) eps += o[0] * wp * wp / std::complex<double>(o[2] * o[2] - w * w, -w * o[1]);
    std::complex<double> index = std::sqrt(eps);
    CHECK(cr->n[c] == doctest::Approx(index.real()).epsilon(1e-3).scale(0.0));
    CHECK(cr->k[c] == doctest::Approx(index.imag()).epsilon(1e-3).scale(0.0));
  }
}

TEST_CASE("copper comes from the Hagemann-Gudat-Kunz table rows nearest 650, 550 and 450 nm") {
  const Metal* cu = find_metal("copper");
  REQUIRE(cu);
  CHECK(cu->n == Vec3d{0.214, 1.037, 1.169});
  CHECK(cu->k == Vec3d{3.67, 2.59, 2.36});
  // Copper reflects red far more than blue at normal incidence: R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
  auto reflectance = [&](int c) {
    double n = cu->n[c], k = cu->k[c];
    return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
  };
  CHECK(reflectance(0) > 0.9);
  CHECK(reflectance(2) < 0.65);
}
