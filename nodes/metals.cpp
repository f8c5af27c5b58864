#include "nodes/metals.h"

#include <array>

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

}  // namespace lamina
