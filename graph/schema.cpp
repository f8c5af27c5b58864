#include "graph/schema.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "graph/diagnostics.h"
#include "graph/document.h"
#include "graph/json_type.h"
#include "graph/json_write.h"
#include "graph/limits.h"
#include "graph/model.h"
#include "graph/number_text.h"
#include "graph/param_schema.h"

namespace lamina {

namespace {

// Identifiers of at most kMaxIdentifierLength (64) characters: one leading, up to 63 more.
constexpr const char* kIdentifierPattern = "^[A-Za-z_][A-Za-z0-9_]{0,63}$";
constexpr const char* kLinkPattern = "^@[A-Za-z_][A-Za-z0-9_]{0,63}(\\.[A-Za-z_][A-Za-z0-9_]{0,63})?$";
static_assert(kMaxIdentifierLength == 64, "the patterns above spell out the identifier length");

Json node_schema(const NodeDecl& d) {
  Json properties;
  properties["id"] = schema_ref("identifier");
  properties["type"] = Json{{"const", d.type}};
  Json required = Json::array({"id", "type"});
  for (const auto& p : d.params) {
    properties[p.name] = param_schema(p);
    if (p.required() && !d.in_alternative(p.name)) required.push_back(p.name);
  }
  Json s{{"description", d.doc},
         {"type", "object"},
         {"properties", properties},
         {"required", required},
         {"additionalProperties", false}};
  // Members of one set come together (dependentRequired); a member of one set forbids the
  // members of the others (dependentSchemas); a required choice needs a first member of some set.
  Json together = Json::object();
  Json excludes = Json::object();
  Json all_of = Json::array();
  for (const auto& alt : d.alternatives) {
    for (size_t a = 0; a < alt.sets.size(); ++a) {
      for (const auto& member : alt.sets[a]) {
        for (const auto& other : alt.sets[a])
          if (other != member) together[member].push_back(other);
        for (size_t b = 0; b < alt.sets.size(); ++b)
          if (b != a)
            for (const auto& banned : alt.sets[b]) excludes[member]["properties"][banned] = false;
      }
    }
    if (!alt.optional) {
      Json none_given = Json::object();
      for (const auto& set : alt.sets) none_given[set.front()] = false;
      all_of.push_back(Json{{"not", Json{{"properties", none_given}}}});
    }
  }
  if (!together.empty()) s["dependentRequired"] = together;
  if (!excludes.empty()) s["dependentSchemas"] = excludes;
  if (!all_of.empty()) s["allOf"] = all_of;
  return s;
}

std::string type_text(const ParamDecl& p) {
  std::string t(type_name(p.type));
  if (p.type == ValueType::Enum) t = join_alternatives(p.choices);
  if (p.linkable && !is_closure(p.type)) t += " or link";
  if (is_closure(p.type)) t = "link to " + t;
  return t;
}

std::string range_cell(const ParamDecl& p) {
  if (!p.has_range()) return "";
  std::string r = p.range_text();
  return r;
}

std::string default_cell(const NodeDecl& d, const ParamDecl& p) {
  if (p.fallback) return default_text(p);
  if (p.omissible) return "(none)";
  return d.in_alternative(p.name) ? "(alternative)" : "required";
}

std::string alternatives_text(const Alternatives& alt, const std::string& quote) {
  std::vector<std::string> sets;
  for (const auto& set : alt.sets) {
    std::string s;
    for (const auto& member : set) s += (s.empty() ? "" : " + ") + quote + member + quote;
    sets.push_back(s);
  }
  return join_alternatives(sets);
}

}  // namespace

std::string default_text(const ParamDecl& p) {
  if (!p.fallback) return "";
  // An optional link's default is "not linked" (a layer without a medium is clear).
  return std::holds_alternative<Link>(*p.fallback) ? "(none)" : value_json(*p.fallback);
}

std::string material_schema(const NodeRegistry& registry) {
  Json defs;
  defs["identifier"] = Json{{"type", "string"}, {"pattern", kIdentifierPattern}};
  defs["link"] = Json{{"description", "a link to a node's output: \"@node_id\" or \"@node_id.output\""},
                      {"type", "string"},
                      {"pattern", kLinkPattern}};
  Json node_types = Json::array();
  Json dispatch = Json::array();
  for (const auto& d : registry.all()) {
    node_types.push_back(d.type);
    std::string def = "node_" + d.type;
    std::replace(def.begin(), def.end(), '/', '_');
    defs[def] = node_schema(d);
    dispatch.push_back(
        Json{{"if", Json{{"properties", Json{{"type", Json{{"const", d.type}}}}}, {"required", {"type"}}}},
             {"then", schema_ref(def)}});
  }
  Json node{{"type", "object"},
            {"properties", Json{{"id", schema_ref("identifier")}, {"type", Json{{"enum", node_types}}}}},
            {"required", Json::array({"id", "type"})},
            {"allOf", dispatch}};
  defs["node"] = node;
  Json classes = Json::array({"a", "b", "c", "d", "e", "f", "g", "h"});
  defs["material"] =
      Json{{"type", "object"},
           {"properties",
            Json{{"name", schema_ref("identifier")},
                 {"class",
                  Json{{"description", "the course's class a)-h); checked against the structure"}, {"enum", classes}}},
                 {"source", Json{{"type", "string"}}},
                 {"notes", Json{{"type", "string"}}},
                 {"clamp_lower_roughness",
                  Json{{"description",
                        "raise each interface's roughness to at least the one above it (Elek sec. 3); default true"},
                       {"type", "boolean"},
                       {"default", true}}},
                 {"model", Json{{"description", "how the stack is composed: " + model_summary()},
                                {"enum", model_names()},
                                {"default", kDefaultModel}}},
                 {"surface", schema_ref("link")},
                 {"nodes", Json{{"type", "array"}, {"minItems", 1}, {"items", schema_ref("node")}}}}},
           {"required", Json::array({"name", "surface", "nodes"})},
           {"additionalProperties", false}};
  Json schema{
      {"$schema", "https://json-schema.org/draft/2020-12/schema"},
      {"$id", "urn:lamina:schema:material:1"},
      {"title", "lamina material file"},
      {"description",
       "Generated by `lamina schema` from the node declarations; do not edit. The lamina checker is "
       "stricter: it also resolves links, matches types across links, rejects cycles, duplicate ids, "
       "non-finite numbers and missing texture files."},
      {"type", "object"},
      {"properties", Json{{"$schema", Json{{"type", "string"}}},
                          {"format", Json{{"const", kFormatVersion}}},
                          {"materials", Json{{"type", "array"}, {"minItems", 1}, {"items", schema_ref("material")}}}}},
      {"required", Json::array({"format", "materials"})},
      {"additionalProperties", false},
      {"$defs", defs}};
  return schema.dump(2) + "\n";
}

std::string node_reference_text(const NodeDecl& d) {
  std::string out = d.type + " (" + std::string(kind_name(d.kind)) + "): " + d.doc + "\n";
  if (d.params.empty()) out += "  no parameters\n";
  for (const auto& p : d.params) {
    out += "  " + p.name + ": " + type_text(p);
    if (!p.unit.empty()) out += ", " + p.unit;
    if (p.has_range()) out += ", " + range_cell(p);
    out += ", " + (p.fallback ? "default " + default_text(p) : default_cell(d, p)) + "\n";
    out += "      " + p.doc + "\n";
    for (size_t i = 0; i < p.choice_docs.size(); ++i) out += "        " + p.choices[i] + ": " + p.choice_docs[i] + "\n";
  }
  for (const auto& alt : d.alternatives)
    out += std::string("  ") + (alt.optional ? "at most one of: " : "exactly one of: ") + alternatives_text(alt, "") +
           "\n";
  out += "  outputs:";
  for (size_t i = 0; i < d.outputs.size(); ++i)
    out += std::string(i ? "," : "") + " " + d.outputs[i].name + " (" + std::string(type_name(d.outputs[i].type)) +
           (i == 0 ? ", default" : "") + ")";
  return out + "\n";
}

std::string node_reference_markdown(const NodeRegistry& registry) {
  std::string out =
      "# lamina node reference\n\nGenerated by `lamina schema` from the node declarations; do not edit.\n"
      "A link is written `\"@node_id\"` (the node's first output) or `\"@node_id.output\"`.\n"
      "Besides its range, every number has a magnitude of at most 1e9.\n";
  static_assert(kMaxNodeNumber == 1.0e9, "the sentence above spells out the limit");
  for (const auto& d : registry.all()) {
    out += "\n## `" + d.type + "`\n\n" + d.doc + ".\n\n";
    if (!d.params.empty()) {
      out += "| parameter | type | unit | range | default | description |\n|---|---|---|---|---|---|\n";
      for (const auto& p : d.params)
        out += "| `" + p.name + "` | " + type_text(p) + " | " + p.unit + " | " + range_cell(p) + " | " +
               default_cell(d, p) + " | " + p.doc + " |\n";
      out += "\n";
      for (const auto& p : d.params) {
        if (p.choice_docs.empty()) continue;
        out += "Values of `" + p.name + "`:\n\n";
        for (size_t i = 0; i < p.choice_docs.size(); ++i) out += "- `" + p.choices[i] + "`: " + p.choice_docs[i] + "\n";
        out += "\n";
      }
    }
    for (const auto& alt : d.alternatives)
      out += std::string(alt.optional ? "Give at most one of " : "Give exactly one of ") + alternatives_text(alt, "`") +
             ".\n\n";
    out += "Outputs: ";
    for (size_t i = 0; i < d.outputs.size(); ++i)
      out += std::string(i ? ", " : "") + "`" + d.outputs[i].name + "` (" + std::string(type_name(d.outputs[i].type)) +
             (i == 0 ? ", default" : "") + ": " + d.outputs[i].doc + ")";
    out += ".\n";
  }
  return out;
}

std::string node_table_markdown(const NodeRegistry& registry) {
  std::string out = "| type | what it is |\n|---|---|\n";
  for (const auto& d : registry.all()) {
    out += "| `" + d.type + "` | " + d.doc;
    for (size_t i = 0; i < d.params.size(); ++i) {
      const ParamDecl& p = d.params[i];
      out += std::string(i ? ", " : "; parameters ") + "`" + p.name + "`";
      if (!p.choices.empty()) {
        out += " (";
        for (size_t c = 0; c < p.choices.size(); ++c) out += (c ? ", " : "") + p.choices[c];
        out += ")";
      }
    }
    for (size_t i = 0; i < d.outputs.size(); ++i)
      out += std::string(i ? ", " : "; outputs ") + "`" + d.outputs[i].name + "`";
    out += " |\n";
  }
  return out;
}

}  // namespace lamina
