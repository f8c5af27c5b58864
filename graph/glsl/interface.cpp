// The host's side of a generated module: the uniform side file and the std140 bytes.
#include <cstring>
#include <nlohmann/json.hpp>

#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"

namespace lamina::glsl {

namespace {

// The float as the shortest decimal that reads back as it (1.94, not 1.940000057220459).
nlohmann::ordered_json number(float x) {
  std::string text = float_literal(x);
  return std::stod(text.substr(0, text.size() - 1));
}

}  // namespace

std::string interface_json(const Module& module, const Options& options) {
  nlohmann::ordered_json root;
  root["generator"] = "lamina " + options.lamina_version;
  root["target"] = target_name(options.target);
  root["uniforms"] = options.uniforms;
  nlohmann::ordered_json materials = nlohmann::ordered_json::array();
  for (const MaterialInterface& m : module.materials) {
    nlohmann::ordered_json entry;
    entry["material"] = m.material;
    entry["functions"] = {m.prefix + "_eval", m.prefix + "_pdf", m.prefix + "_sample"};
    if (!m.block.empty()) {
      entry["block"] = {{"name", m.block}, {"instance", m.instance}, {"layout", "std140"}, {"size", m.block_size}};
      nlohmann::ordered_json members = nlohmann::ordered_json::array();
      for (const UniformField& f : m.uniforms) {
        nlohmann::ordered_json value = nlohmann::ordered_json::array();
        for (float x : f.value) value.push_back(number(x));
        if (f.value.size() == 1) value = value[0];
        members.push_back({{"name", f.name},
                           {"type", f.type},
                           {"offset", f.offset},
                           {"value", value},
                           {"node", f.node},
                           {"parameter", f.parameter}});
      }
      entry["block"]["members"] = members;
    }
    nlohmann::ordered_json samplers = nlohmann::ordered_json::array();
    for (const SamplerBinding& b : m.samplers)
      samplers.push_back(
          {{"name", b.name}, {"node", b.node}, {"file", b.file}, {"width", b.width}, {"height", b.height}});
    entry["samplers"] = samplers;
    materials.push_back(entry);
  }
  root["materials"] = materials;
  // A table's texels, one line per row of the texture: a placeholder here, replaced below (nlohmann
  // would give every number a line of its own).
  nlohmann::ordered_json tables = nlohmann::ordered_json::array();
  for (size_t t = 0; t < module.tables.size(); ++t) {
    const TableBinding& b = module.tables[t];
    tables.push_back({{"name", b.name},
                      {"type", "usampler2D"},
                      {"format", b.format},
                      {"width", b.width},
                      {"height", b.height},
                      {"contents", b.contents},
                      {"texels", "@texels " + std::to_string(t)}});
  }
  root["tables"] = tables;
  std::string text = root.dump(2) + "\n";
  for (size_t t = 0; t < module.tables.size(); ++t) {
    const TableBinding& b = module.tables[t];
    const std::string placeholder = "\"@texels " + std::to_string(t) + "\"";
    const size_t at = text.rfind(placeholder);  // the tables come last: a material name cannot match
    const size_t line = text.rfind('\n', at) + 1;
    const std::string indent(text.find_first_not_of(' ', line) - line + 2, ' ');
    std::string rows = "[";
    for (int y = 0; y < b.height; ++y) {
      rows += "\n" + indent;
      for (int x = 0; x < b.width; ++x)
        rows += std::to_string(b.texels[size_t(y) * size_t(b.width) + size_t(x)]) + (x + 1 < b.width ? "," : "");
      rows += y + 1 < b.height ? "," : "";
    }
    rows += "\n" + indent.substr(2) + "]";
    text.replace(at, placeholder.size(), rows);
  }
  return text;
}

std::vector<std::byte> pack_uniforms(const MaterialInterface& material) {
  std::vector<std::byte> bytes(material.block_size);
  for (const UniformField& f : material.uniforms)
    std::memcpy(bytes.data() + f.offset, f.value.data(), f.value.size() * sizeof(float));
  return bytes;
}

}  // namespace lamina::glsl
