#include "graph/model.h"

#include <array>

#include "nodes/kernels/kernels.h"

namespace lamina {

namespace {

struct ModelEntry {
  std::string_view name;
  int number;
  std::string_view promise;
};

constexpr std::array kModels = {
    ModelEntry{"energy_conserving", kernels::LAMINA_MODEL_ENERGY_CONSERVING,
               "never reflects more than it receives, reciprocal"},
    ModelEntry{"weidlich_wilkie", kernels::LAMINA_MODEL_WEIDLICH_WILKIE, "the seeds' model as they give it"},
};
static_assert(kModels[0].name == kDefaultModel, "the default is listed first");

}  // namespace

const std::vector<std::string>& model_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ModelEntry& m : kModels) out.emplace_back(m.name);
    return out;
  }();
  return names;
}

int model_number(std::string_view name) {
  for (const ModelEntry& m : kModels)
    if (m.name == name) return m.number;
  return -1;
}

std::string_view model_name(int number) {
  for (const ModelEntry& m : kModels)
    if (m.number == number) return m.name;
  return {};
}

std::string model_summary() {
  std::string out;
  for (const ModelEntry& m : kModels) {
    if (!out.empty()) out += "; ";
    out += std::string(m.name) + " (" + std::string(m.promise) + (m.name == kDefaultModel ? ", the default)" : ")");
  }
  return out;
}

}  // namespace lamina
