#include "graph/gltf/import_layered.h"

#include "graph/gltf/export.h"
#include "graph/json_read.h"
#include "graph/json_type.h"

namespace lamina::gltf {

namespace {

// "/materials/0/rest" of the one-material wrapper -> base + "/rest".
std::string map_pointer(const std::string& pointer, const std::string& base) {
  const std::string prefix = "/materials/0";
  if (pointer.compare(0, prefix.size(), prefix) == 0) return base + pointer.substr(prefix.size());
  return base;
}

template <class Map>
void append_mapped(ImportSession& s, const Diagnostics& from, Map map) {
  for (const auto& d : from.errors()) s.diagnostics.error(s.file, map(d.pointer), d.message, d.hint);
  for (const auto& d : from.warnings()) s.diagnostics.warning(s.file, map(d.pointer), d.message, d.hint);
}

}  // namespace

void import_layered(ImportSession& s, size_t index, const Json& extension) {
  const std::string base = "/materials/" + std::to_string(index) + "/extensions/" + kExtensionName;
  if (!extension.is_object()) {
    s.diagnostics.error(s.file, base, "expected an object with \"format\", \"material\" and \"textures\"");
    return;
  }
  for (const auto& [key, value] : extension.items())
    if (key != "format" && key != "material" && key != "textures" && key != "extensions" && key != "extras")
      s.diagnostics.warning(s.file, base + "/" + pointer_escape(key), "unknown property '" + key + "' is ignored",
                            "the extension has format, material and textures");
  const Json format = extension.value("format", Json());
  if (!format.is_number_integer() || format.get<int>() != kFormatVersion) {
    s.diagnostics.error(s.file, base + "/format",
                        format.is_number() ? "unsupported format " + format.dump() + "; this lamina reads 1"
                                           : "expected the integer 1 (the lamina material format version)");
    return;
  }
  const Json material = extension.value("material", Json());
  if (!material.is_object()) {
    s.diagnostics.error(s.file, base + "/material", "expected a lamina material object (as in a material file)");
    return;
  }
  // The regular reader, on a one-material document; its pointers are mapped back below.
  const Json wrapper{{"format", kFormatVersion}, {"materials", Json::array({material})}};
  Diagnostics read;
  Document single = read_document(wrapper.dump(), s.file, read);
  append_mapped(s, read, [&](const std::string& p) { return map_pointer(p, base + "/material"); });
  if (!read.ok() || single.materials.size() != 1) return;
  Material m = std::move(single.materials.front());

  const Json textures = extension.value("textures", Json::object());
  if (!textures.is_object()) {
    s.diagnostics.error(s.file, base + "/textures",
                        "expected an object mapping image node ids to {\"index\": texture}");
    return;
  }
  bool ok = true;
  for (const auto& [id, entry] : textures.items()) {
    const Node* node = m.find_node(id);
    if (!node || node->type != "texture/image") {
      s.diagnostics.error(s.file, base + "/textures/" + pointer_escape(id),
                          "'" + id + "' is not a texture/image node of the material");
      ok = false;
    }
  }
  for (size_t n = 0; n < m.nodes.size(); ++n) {
    Node& node = m.nodes[n];
    if (node.type != "texture/image") continue;
    const std::string entry_pointer = base + "/textures/" + pointer_escape(node.id);
    if (!textures.contains(node.id)) {
      s.diagnostics.error(s.file, base + "/textures", "no texture for the image node '" + node.id + "'",
                          "add \"" + node.id + "\": {\"index\": <glTF texture>}");
      ok = false;
      continue;
    }
    const Json& entry = textures.at(node.id);
    if (!entry.is_object() || !entry.contains("index") || !entry.at("index").is_number_integer()) {
      s.diagnostics.error(s.file, entry_pointer, "expected {\"index\": <glTF texture index>}");
      ok = false;
      continue;
    }
    for (auto& param : node.params) {
      if (param.name != "file" || !std::holds_alternative<std::string>(param.value)) continue;
      // The graph keeps the original path; the extracted file takes its base name.
      const std::string wanted = std::filesystem::path(std::get<std::string>(param.value)).filename().string();
      const std::string file = s.texture_file(entry.at("index").get<int>(), entry_pointer + "/index", wanted);
      if (file.empty())
        ok = false;
      else
        param.value = file;
    }
  }
  if (!ok) return;
  // The graph's own name first: it is what the material file called it (the glTF name is a copy
  // a tool may have changed).
  const std::string wanted_name = m.name.empty() ? s.model.materials[index].name : m.name;
  m.name = s.unique_material_name(wanted_name, index);
  s.add(std::move(m), Origin{index, true});
}

}  // namespace lamina::gltf
