#include "graph/document.h"

namespace lamina {

const Value* Node::find(std::string_view name) const {
  for (const auto& p : params)
    if (p.name == name) return &p.value;
  return nullptr;
}

const Node* Material::find_node(std::string_view id) const {
  for (const auto& n : nodes)
    if (n.id == id) return &n;
  return nullptr;
}

const Material* Document::find_material(std::string_view name) const {
  for (const auto& m : materials)
    if (m.name == name) return &m;
  return nullptr;
}

bool Document::same_content(const Document& other) const {
  return schema == other.schema && format == other.format && materials == other.materials;
}

}  // namespace lamina
