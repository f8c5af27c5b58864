#include "graph/scene/scene.h"

#include <nlohmann/json.hpp>

namespace lamina {

const Material* Scene::find_material(std::string_view name, const MaterialFileRef** file) const {
  for (const auto& f : material_files) {
    if (const Material* m = f.document.find_material(name)) {
      if (file) *file = &f;
      return m;
    }
  }
  if (file) *file = nullptr;
  return nullptr;
}

bool looks_like_scene(std::string_view text) {
  auto root = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded())  // malformed: judge by the key so the scene reader reports the syntax error
    return text.find("\"objects\"") != std::string_view::npos;
  return root.is_object() && root.contains("objects");
}

}  // namespace lamina
