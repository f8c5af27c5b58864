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
  return root.dump(2) + "\n";
}

std::vector<std::byte> pack_uniforms(const MaterialInterface& material) {
  std::vector<std::byte> bytes(material.block_size);
  for (const UniformField& f : material.uniforms)
    std::memcpy(bytes.data() + f.offset, f.value.data(), f.value.size() * sizeof(float));
  return bytes;
}

}  // namespace lamina::glsl
