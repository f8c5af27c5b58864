#include "graph/json_read.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "graph/json_values.h"
#include "graph/limits.h"
#include "graph/model.h"
#include "graph/number_text.h"

namespace lamina {

bool is_identifier(std::string_view text) {
  if (text.empty() || text.size() > kMaxIdentifierLength) return false;
  auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!alpha(text[0])) return false;
  for (char c : text)
    if (!alpha(c) && !digit(c)) return false;
  return true;
}

bool parse_link(std::string_view text, Link& link) {
  if (text.size() < 2 || text[0] != '@') return false;
  text.remove_prefix(1);
  auto dot = text.find('.');
  std::string_view node = text.substr(0, dot);
  std::string_view output = dot == std::string_view::npos ? std::string_view{} : text.substr(dot + 1);
  if (!is_identifier(node)) return false;
  if (dot != std::string_view::npos && !is_identifier(output)) return false;
  link = Link{std::string(node), std::string(output)};
  return true;
}

namespace {

class Reader {
 public:
  Reader(const std::string& file, Diagnostics& diagnostics, const NodeRegistry& registry)
      : file_(file), diag_(diagnostics), registry_(registry) {}

  Document read(std::string_view text) {
    Document doc;
    doc.path = file_;
    auto parsed = parse_json(text, file_, diag_, "a material file is a JSON object with \"format\" and \"materials\"");
    if (!parsed) return doc;
    const Json& root = *parsed;
    if (!root.is_object()) {
      error("", "expected an object with \"format\" and \"materials\", found " + json_kind(root));
      return doc;
    }
    check_keys(root, "", {"$schema", "format", "materials"});
    if (auto it = root.find("$schema"); it != root.end()) {
      if (it->is_string())
        doc.schema = it->get<std::string>();
      else
        error("/$schema", "expected a string (the schema's path or URI), found " + json_kind(*it));
    }
    read_format(root, doc);
    auto materials = root.find("materials");
    if (materials == root.end()) {
      error("", "missing \"materials\"",
            "add \"materials\": [ { \"name\": ..., \"surface\": ..., \"nodes\": [...] } ]");
    } else if (!materials->is_array()) {
      error("/materials", "expected an array of materials, found " + json_kind(*materials));
    } else if (materials->empty()) {
      error("/materials", "the file defines no material", "add at least one material");
    } else {
      std::map<std::string, size_t> seen;
      for (size_t i = 0; i < materials->size(); ++i) {
        std::string pointer = pointer_append("/materials", i);
        Material m = read_material((*materials)[i], pointer);
        if (!m.name.empty()) {
          auto [at, inserted] = seen.emplace(m.name, i);
          if (!inserted)
            error(pointer + "/name",
                  "duplicate material name '" + m.name + "' (also /materials/" + std::to_string(at->second) + ")");
        }
        doc.materials.push_back(std::move(m));
      }
    }
    return doc;
  }

 private:
  void error(const std::string& pointer, std::string message, std::string hint = {}) {
    diag_.error(file_, pointer, std::move(message), std::move(hint));
  }

  void check_keys(const Json& object, const std::string& pointer, const std::vector<std::string>& known) {
    check_known_keys(object, file_, pointer, known, diag_);
  }

  void read_format(const Json& root, Document& doc) {
    auto it = root.find("format");
    if (it == root.end()) {
      error("", "missing \"format\"", "add \"format\": " + std::to_string(kFormatVersion));
      return;
    }
    if (!it->is_number()) {
      error("/format", "expected the format version number, found " + json_kind(*it),
            "write \"format\": " + std::to_string(kFormatVersion));
      return;
    }
    double version = it->get<double>();
    if (version != kFormatVersion) {
      std::string written = version == std::floor(version) && std::abs(version) < 1e15
                                ? std::to_string(static_cast<long long>(version))
                                : number_text(version);
      error("/format",
            "unsupported format " + written + ": this lamina reads format " + std::to_string(kFormatVersion));
      return;
    }
    doc.format = kFormatVersion;
  }

  std::optional<std::string> optional_string(const Json& object, const std::string& pointer, const char* key) {
    auto it = object.find(key);
    if (it == object.end()) return std::nullopt;
    if (!it->is_string()) {
      error(pointer_append(pointer, key), std::string("expected a string, found ") + json_kind(*it));
      return std::nullopt;
    }
    return it->get<std::string>();
  }

  Material read_material(const Json& j, const std::string& pointer) {
    Material m;
    if (!j.is_object()) {
      error(pointer, "expected a material object, found " + json_kind(j));
      return m;
    }
    check_keys(j, pointer, {"name", "class", "source", "notes", "clamp_lower_roughness", "model", "surface", "nodes"});
    if (auto name = j.find("name"); name == j.end()) {
      error(pointer, "missing \"name\"", "materials are looked up by name");
    } else if (!name->is_string() || !is_identifier(name->get<std::string>())) {
      error(pointer + "/name",
            "expected a name of at most " + std::to_string(kMaxIdentifierLength) +
                " letters, digits and '_', not starting with a digit, found " + describe(*name),
            "names become GLSL and glTF identifiers");
    } else {
      m.name = name->get<std::string>();
    }
    m.class_tag = optional_string(j, pointer, "class");
    if (m.class_tag && !(m.class_tag->size() == 1 && (*m.class_tag)[0] >= 'a' && (*m.class_tag)[0] <= 'h')) {
      error(pointer + "/class", "unknown class " + quote_excerpt(*m.class_tag),
            "the course's classes are a, b, c, d, e, f, g or h");
      m.class_tag.reset();
    }
    m.source = optional_string(j, pointer, "source");
    if (auto clamp = j.find("clamp_lower_roughness"); clamp != j.end()) {
      if (clamp->is_boolean())
        m.clamp_lower_roughness = clamp->get<bool>();
      else
        error(pointer + "/clamp_lower_roughness", "expected true or false, found " + json_kind(*clamp));
    }
    m.notes = optional_string(j, pointer, "notes");
    m.model = optional_string(j, pointer, "model");
    if (m.model && model_number(*m.model) < 0) {
      error(pointer + "/model", "unknown model " + quote_excerpt(*m.model), "the models are " + model_summary());
      m.model.reset();
    }

    if (auto surface = j.find("surface"); surface == j.end()) {
      error(pointer, "missing \"surface\"", "name the top of the stack, e.g. \"surface\": \"@coat\"");
    } else if (!surface->is_string() || !parse_link(surface->get<std::string>(), m.surface)) {
      error(pointer + "/surface", "expected a link to the top node, found " + describe(*surface),
            "write \"@\" and the node's id, e.g. \"@coat\"");
    }

    auto nodes = j.find("nodes");
    if (nodes == j.end()) {
      error(pointer, "missing \"nodes\"", "add \"nodes\": [ ... ]");
    } else if (!nodes->is_array()) {
      error(pointer + "/nodes", "expected an array of nodes, found " + json_kind(*nodes));
    } else if (nodes->empty()) {
      error(pointer + "/nodes", "the material has no nodes", "a material needs at least a substrate");
    } else {
      std::map<std::string, size_t> seen;
      for (size_t i = 0; i < nodes->size(); ++i) {
        std::string node_pointer = pointer_append(pointer + "/nodes", i);
        Node n = read_node((*nodes)[i], node_pointer);
        if (!n.id.empty()) {
          auto [at, inserted] = seen.emplace(n.id, i);
          if (!inserted)
            error(node_pointer + "/id",
                  "duplicate node id '" + n.id + "' (also " + pointer + "/nodes/" + std::to_string(at->second) + ")");
        }
        m.nodes.push_back(std::move(n));
      }
    }
    return m;
  }

  static std::string describe(const Json& j) { return json_describe(j); }

  Node read_node(const Json& j, const std::string& pointer) {
    Node n;
    if (!j.is_object()) {
      error(pointer, "expected a node object {\"id\": ..., \"type\": ...}, found " + json_kind(j));
      return n;
    }
    if (auto id = j.find("id"); id == j.end()) {
      error(pointer, "missing \"id\"", "links name nodes by id, e.g. \"id\": \"varnish\"");
    } else if (!id->is_string() || !is_identifier(id->get<std::string>())) {
      error(pointer + "/id", "expected an id of at most " + std::to_string(kMaxIdentifierLength) +
                                 " letters, digits and '_', not starting with a digit, found " + describe(*id));
    } else {
      n.id = id->get<std::string>();
    }
    auto type = j.find("type");
    if (type == j.end()) {
      error(pointer, "missing \"type\"", "valid types: " + join_alternatives(registry_.type_names()));
      return n;
    }
    if (!type->is_string()) {
      error(pointer + "/type", "expected a node type string, found " + json_kind(*type));
      return n;
    }
    n.type = type->get<std::string>();
    const NodeDecl* decl = registry_.find(n.type);
    if (!decl) {
      std::string suggestion = closest_match(n.type, registry_.type_names());
      error(pointer + "/type", "unknown node type " + quote_excerpt(n.type),
            (suggestion.empty() ? std::string() : "did you mean \"" + suggestion + "\"? ") +
                "valid types: " + join_alternatives(registry_.type_names()));
      return n;
    }
    // Parameters in declaration order, so that a document reads back exactly as it writes.
    for (const auto& [key, value] : j.items()) {
      if (key == "id" || key == "type" || decl->find_param(key)) continue;
      report_unknown_param(*decl, n.id, key, pointer);
    }
    for (const auto& p : decl->params) {
      auto it = j.find(p.name);
      if (it == j.end()) continue;
      if (auto v = read_value(p, *it, pointer_append(pointer, p.name))) n.params.push_back({p.name, std::move(*v)});
    }
    check_presence(*decl, j, pointer);
    return n;
  }

  void report_unknown_param(const NodeDecl& decl, const std::string& id, const std::string& key,
                            const std::string& pointer) {
    std::string at = pointer_append(pointer, key);
    if (decl.kind == NodeKind::Substrate && key == "base") {
      error(at, "a substrate is opaque: it is always the bottom of a stack and cannot lie on a base",
            "put a layer over it instead: {\"type\": \"layer\", \"interface\": ..., \"base\": \"@" + id + "\"}");
      return;
    }
    std::string suggestion = closest_match(key, decl.param_names());
    std::string hint =
        suggestion.empty()
            ? (decl.params.empty() ? decl.type + " takes no parameters"
                                   : "parameters of " + decl.type + ": " + join_alternatives(decl.param_names()))
            : "did you mean \"" + suggestion + "\"?";
    error(at, "unknown parameter \"" + key + "\" for " + decl.type, hint);
  }

  void check_presence(const NodeDecl& decl, const Json& j, const std::string& pointer) {
    for (const auto& p : decl.params) {
      if (p.required() && !decl.in_alternative(p.name) && !j.contains(p.name))
        error(pointer, "missing required parameter \"" + p.name + "\" of " + decl.type, p.doc);
    }
    for (const auto& alt : decl.alternatives) {
      std::vector<size_t> present_sets;
      std::vector<std::string> descriptions;
      for (size_t s = 0; s < alt.sets.size(); ++s) {
        const auto& set = alt.sets[s];
        size_t present = 0;
        for (const auto& member : set) present += j.contains(member) ? 1 : 0;
        std::string description;
        for (const auto& member : set)
          description += (description.empty() ? "" : " and ") + std::string("\"") + member + "\"";
        descriptions.push_back(description);
        if (present == set.size()) {
          present_sets.push_back(s);
        } else if (present > 0) {
          error(pointer, "incomplete parameters: " + description + " go together", "give all of them");
          present_sets.push_back(s);  // counted as an attempt at this set
        }
      }
      if (present_sets.size() > 1) {
        error(pointer_append(pointer, alt.sets[present_sets[1]].front()),
              "give only one of " + join_alternatives(descriptions), "they describe the same thing");
      } else if (present_sets.empty() && !alt.optional) {
        error(pointer, decl.type + " needs " + join_alternatives(descriptions));
      }
    }
  }

  bool check_number(const ParamDecl& p, double v, const std::string& pointer, const std::string& label) {
    if (!std::isfinite(v)) {
      error(pointer, label + " is not a finite number", "JSON numbers beyond 1.8e308 overflow to infinity");
      return false;
    }
    if (std::abs(v) > kMaxNodeNumber) {
      static_assert(kMaxNodeNumber == 1.0e9, "the message spells out the limit");
      error(pointer, label + " = " + number_text(v) + " is too large: expected a magnitude of at most 1e9",
            "the back ends compute in single precision");
      return false;
    }
    if (!p.in_range(v)) {
      error(pointer,
            label + " = " + number_text(v) + " is out of range: expected " +
                p.range_text(label == p.name ? p.name : "value"),
            p.doc);
      return false;
    }
    return true;
  }

  std::optional<Value> read_value(const ParamDecl& p, const Json& j, const std::string& pointer) {
    if (j.is_string() && (p.linkable || is_closure(p.type))) {
      const auto& text = j.get<std::string>();
      Link link;
      if (parse_link(text, link)) return Value{link};
      if (is_closure(p.type) || (!text.empty() && text[0] == '@')) {
        error(pointer, quote_excerpt(text) + " is not a valid link", "write \"@node_id\" or \"@node_id.output\"");
        return std::nullopt;
      }
    }
    auto expected = [&](const std::string& what) {
      error(pointer,
            "expected " + what + (p.linkable && !is_closure(p.type) ? " or a link \"@node\"" : "") + ", found " +
                describe(j),
            p.doc);
      return std::nullopt;
    };
    switch (p.type) {
      case ValueType::Float: {
        if (!j.is_number()) return expected(p.expected_text());
        double v = j.get<double>();
        if (!check_number(p, v, pointer, p.name)) return std::nullopt;
        return Value{v};
      }
      case ValueType::Color:
      case ValueType::Vec3:
      case ValueType::Vec2: {
        const size_t size = size_t(value_components(p.type));
        const std::string shape = p.expected_text();
        if (!j.is_array() || j.size() != size) {
          if (j.is_array())
            error(pointer, "expected " + shape + " of " + std::to_string(size) + " numbers, found " +
                               std::to_string(j.size()) + " elements");
          else
            return expected(shape);
          return std::nullopt;
        }
        std::array<double, 3> v{};
        bool ok = true;
        for (size_t i = 0; i < size; ++i) {
          const auto& e = j[i];
          std::string at = pointer_append(pointer, i);
          if (!e.is_number()) {
            error(at, "expected a number, found " + describe(e));
            ok = false;
            continue;
          }
          v[i] = e.get<double>();
          ok = check_number(p, v[i], at, p.name + "[" + std::to_string(i) + "]") && ok;
        }
        if (!ok) return std::nullopt;
        if (size == 2) return Value{Vec2d{v[0], v[1]}};
        return Value{Vec3d{v[0], v[1], v[2]}};
      }
      case ValueType::Bool:
        if (!j.is_boolean()) return expected(p.expected_text());
        return Value{j.get<bool>()};
      case ValueType::Enum: {
        if (!j.is_string()) return expected(p.expected_text());
        auto text = j.get<std::string>();
        if (std::find(p.choices.begin(), p.choices.end(), text) == p.choices.end()) {
          std::string suggestion = closest_match(text, p.choices);
          error(pointer, "unknown " + p.name + " " + quote_excerpt(text),
                (suggestion.empty() ? std::string() : "did you mean \"" + suggestion + "\"? ") +
                    "valid values: " + join_alternatives(p.choices));
          return std::nullopt;
        }
        return Value{text};
      }
      case ValueType::String:
        if (!j.is_string()) return expected(p.expected_text());
        if (j.get<std::string>().empty()) {
          error(pointer, "expected a non-empty string", p.doc);
          return std::nullopt;
        }
        return Value{j.get<std::string>()};
      case ValueType::Interface:
      case ValueType::Medium:
      case ValueType::Stack:
        error(pointer, "expected " + p.expected_text() + ", found " + describe(j), p.doc);
        return std::nullopt;
      case ValueType::Integer: {
        // Counts and seeds: constants only (registry_test.cpp keeps them unlinkable).
        if (!j.is_number()) return expected(p.expected_text());
        double v = j.get<double>();
        if (v != std::floor(v)) {
          error(pointer, p.name + " = " + number_text(v) + " is not a whole number", p.doc);
          return std::nullopt;
        }
        if (!check_number(p, v, pointer, p.name)) return std::nullopt;
        return Value{v};
      }
      case ValueType::Quaternion:
      case ValueType::Object:
        // Scene-file types: tests/nodes/registry_test.cpp keeps them out of node declarations.
        throw std::logic_error("parameter " + p.name + " of a node has a scene-file type");
    }
    return std::nullopt;
  }

  const std::string& file_;
  Diagnostics& diag_;
  const NodeRegistry& registry_;
};

}  // namespace

Document read_document(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                       const NodeRegistry& registry) {
  return Reader(file, diagnostics, registry).read(text);
}

}  // namespace lamina
