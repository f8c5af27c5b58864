#include "nodes/metals.h"

#include <array>

#include "graph/number_text.h"

namespace lamina {

namespace {

// Channels are red, green, blue, sampled near 650, 550 and 450 nm.
constexpr std::array kMetals = {
    Metal{
        "aluminium", {1.94, 1.0, 0.6}, {8.21, 6.69, 4.86}, "Weidlich and Wilkie course, 'Type d) - Metal Foil' slide"},
    Metal{"chromium",
          {3.535, 2.901, 2.145},
          {4.348, 4.231, 3.862},
          "Rakic et al., Appl. Opt. 37(22):5271 (1998), Lorentz-Drude model of Cr evaluated at 650/550/450 nm"},
    Metal{"copper",
          {0.214, 1.037, 1.169},
          {3.67, 2.59, 2.36},
          "Hagemann, Gudat and Kunz, DESY SR-74/7 (1974), Cu table at 652.5/539.1/442.8 nm"},
    Metal{"gold", {0.1, 0.42, 1.56}, {3.8, 2.5, 1.9}, "Weidlich and Wilkie course, 'Type d) - Metal Foil' slide"},
    Metal{"silver",
          {0.14, 0.13, 0.157},
          {4.44, 3.25, 2.40},
          "Weidlich and Wilkie course, 'Type d) - Metal Foil' slide (the example slides round n_b to 0.16)"},
};

}  // namespace

std::span<const Metal> metals() { return kMetals; }

const Metal* find_metal(std::string_view name) {
  for (const auto& m : kMetals)
    if (m.name == name) return &m;
  return nullptr;
}

namespace {

// Each named metal with its constants and their source, for `lamina nodes` and schema/nodes.md.
std::vector<std::pair<std::string, std::string>> described_metals() {
  auto triple = [](const Vec3d& v) { return number_text(v[0]) + ", " + number_text(v[1]) + ", " + number_text(v[2]); };
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& m : metals())
    out.emplace_back(m.name, "n (" + triple(m.n) + "), k (" + triple(m.k) + "); " + std::string(m.source));
  return out;
}

// A named metal's tabulated n and k, as the constants the parameters would have given.
InputRef metal_constant(NodeLowering& n, const char* parameter, const Vec3d& value) {
  InputRef r;
  r.constant = glm::vec3(float(value[0]), float(value[1]), float(value[2]));
  r.size = 3;
  r.node = n.id();
  r.parameter = parameter;
  return r;
}

}  // namespace

void add_metal_params(NodeDecl& d) {
  d.params.push_back(param("metal", ValueType::Enum)
                         .one_of_described(described_metals())
                         .described("a named metal with tabulated n and k; give this or n and k"));
  d.params.push_back(param("n", ValueType::Color)
                         .above(0.0)
                         .at_most(kMaxConductorIndex)
                         .links()
                         .described("real part of the metal's index of refraction per channel"));
  d.params.push_back(param("k", ValueType::Color)
                         .range(0.0, kMaxConductorIndex)
                         .links()
                         .described("extinction coefficient (imaginary part of the index) per channel"));
  d.alternatives.push_back({{{"metal"}, {"n", "k"}}, false});
}

void lower_metal_params(NodeLowering& n) {
  StackEntry& e = n.entry();
  if (n.given("metal")) {
    const Metal* metal = find_metal(n.text("metal"));
    e.colour0 = metal_constant(n, "n", metal->n);
    e.colour1 = metal_constant(n, "k", metal->k);
    e.note = n.text("metal");
  } else {
    e.colour0 = n.input("n");
    e.colour1 = n.input("k");
  }
}

}  // namespace lamina
