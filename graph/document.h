// A material file as written: materials of nodes with parameters, before any defaults are
// applied. Reading and writing it are exact inverses.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graph/file_access.h"
#include "graph/value.h"

namespace lamina {

struct Param {
  std::string name;
  Value value;
  bool operator==(const Param&) const = default;
};

struct Node {
  std::string id;
  std::string type;
  std::vector<Param> params;  // only those written in the file, in declaration order

  const Value* find(std::string_view name) const;
  bool operator==(const Node&) const = default;
};

struct Material {
  std::string name;
  std::optional<std::string> class_tag;  // "a".."h", the author's claim, checked against structure
  std::optional<std::string> source;
  std::optional<std::string> notes;
  // Elek sec. 3: a point evaluation cannot blur a lower lobe seen through a rough upper
  // interface, so each interface's roughness is raised to at least the one above it.
  std::optional<bool> clamp_lower_roughness;  // default true
  // How the stack is composed (graph/model.h): "energy_conserving" when absent, or
  // "weidlich_wilkie", the seeds' model as they give it (nodes/kernels/stack.glsl, LAMINA_MODEL_*).
  std::optional<std::string> model;
  Link surface;
  std::vector<Node> nodes;

  const Node* find_node(std::string_view id) const;
  bool operator==(const Material&) const = default;
};

inline constexpr int kFormatVersion = 1;

struct Document {
  std::string path;                   // where it was read from; not part of the content
  AssetPolicy policy;                 // how its references are followed; not part of the content
  std::optional<std::string> schema;  // "$schema", kept so editors keep their completion
  int format = kFormatVersion;
  std::vector<Material> materials;

  const Material* find_material(std::string_view name) const;
  // Content equality: the path is not compared.
  bool same_content(const Document& other) const;
};

}  // namespace lamina
