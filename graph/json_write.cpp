#include "graph/json_write.h"

#include <nlohmann/json.hpp>

#include "graph/number_text.h"

namespace lamina {

namespace {

std::string quoted(const std::string& text) { return nlohmann::json(text).dump(); }

class Writer {
 public:
  explicit Writer(const NodeRegistry& registry) : registry_(registry) {}

  std::string write(const Document& doc) {
    out_ = "{\n";
    std::vector<std::string> fields;
    if (doc.schema) fields.push_back(key(1, "$schema") + quoted(*doc.schema));
    fields.push_back(key(1, "format") + std::to_string(doc.format));
    std::string materials = key(1, "materials") + "[";
    for (size_t i = 0; i < doc.materials.size(); ++i)
      materials += (i ? ",\n" : "\n") + indent(2) + material(doc.materials[i]);
    materials += "\n" + indent(1) + "]";
    fields.push_back(materials);
    out_ += join(fields) + "\n}\n";
    return out_;
  }

 private:
  static std::string indent(int level) { return std::string(static_cast<size_t>(level) * 2, ' '); }
  static std::string key(int level, const std::string& name) { return indent(level) + quoted(name) + ": "; }
  static std::string join(const std::vector<std::string>& fields) {
    std::string out;
    for (size_t i = 0; i < fields.size(); ++i) out += (i ? ",\n" : "") + fields[i];
    return out;
  }

  std::string material(const Material& m) {
    std::vector<std::string> fields;
    fields.push_back(key(3, "name") + quoted(m.name));
    if (m.class_tag) fields.push_back(key(3, "class") + quoted(*m.class_tag));
    if (m.source) fields.push_back(key(3, "source") + quoted(*m.source));
    if (m.notes) fields.push_back(key(3, "notes") + quoted(*m.notes));
    if (m.clamp_lower_roughness)
      fields.push_back(key(3, "clamp_lower_roughness") + (*m.clamp_lower_roughness ? "true" : "false"));
    if (m.model) fields.push_back(key(3, "model") + quoted(*m.model));
    fields.push_back(key(3, "surface") + quoted(to_string(m.surface)));
    std::string nodes = key(3, "nodes") + "[";
    for (size_t i = 0; i < m.nodes.size(); ++i) nodes += (i ? ",\n" : "\n") + indent(4) + node(m.nodes[i]);
    nodes += m.nodes.empty() ? "]" : "\n" + indent(3) + "]";
    fields.push_back(nodes);
    return "{\n" + join(fields) + "\n" + indent(2) + "}";
  }

  // One node per line: nodes are short, and a changed parameter then shows as one changed line.
  std::string node(const Node& n) {
    std::string out = "{\"id\": " + quoted(n.id) + ", \"type\": " + quoted(n.type);
    const NodeDecl* decl = registry_.find(n.type);
    auto emit = [&](const Param& p) { out += ", " + quoted(p.name) + ": " + value_json(p.value); };
    if (decl) {
      for (const auto& p : decl->params)
        for (const auto& given : n.params) {
          if (given.name != p.name) continue;
          // Whole-number parameters (counts, seeds) are written as JSON integers: 4, not 4.0.
          const double* whole = p.type == ValueType::Integer ? std::get_if<double>(&given.value) : nullptr;
          if (whole)
            out += ", " + quoted(p.name) + ": " + std::to_string(static_cast<long long>(*whole));
          else
            emit(given);
        }
    } else {
      for (const auto& given : n.params) emit(given);
    }
    return out + "}";
  }

  const NodeRegistry& registry_;
  std::string out_;
};

// A parameter value as JSON text.
struct ValueText {
  std::string operator()(double d) const { return number_text(d); }
  template <size_t N>
  std::string operator()(const std::array<double, N>& a) const {
    std::string out = "[";
    for (size_t i = 0; i < N; ++i) out += (i ? ", " : "") + number_text(a[i]);
    return out + "]";
  }
  std::string operator()(bool b) const { return b ? "true" : "false"; }
  std::string operator()(const std::string& s) const { return quoted(s); }
  std::string operator()(const Link& l) const { return quoted(to_string(l)); }
};

}  // namespace

std::string value_json(const Value& v) { return std::visit(ValueText{}, v); }

std::string write_document(const Document& document, const NodeRegistry& registry) {
  return Writer(registry).write(document);
}

}  // namespace lamina
