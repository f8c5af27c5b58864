#include "graph/gltf/import.h"

#include <memory>
#include <set>
#include <vector>

#include "graph/gltf/export.h"
#include "graph/gltf/import_layered.h"
#include "graph/gltf/import_load.h"
#include "graph/gltf/import_pbr.h"
#include "graph/json_write.h"
#include "graph/load.h"

namespace lamina::gltf {

namespace {

// Extensions this importer reads; any other one is reported and ignored.
const std::set<std::string> kReadExtensions{kExtensionName, kIor, kSpecular, kClearcoat, kIridescence};
// Extensions that carry no material data (lights, geometry encodings, instancing, metadata): a
// material import loses nothing by skipping them, so they give a note rather than a warning.
const std::set<std::string> kNotMaterialExtensions{"KHR_lights_punctual", "KHR_mesh_quantization",
                                                   "EXT_mesh_gpu_instancing", "KHR_xmp_json_ld"};

bool is_label(const GltfMaterial& gm) { return gm.extras.is_object() && gm.extras.contains(kLabelExtra); }

void import_material(ImportSession& s, size_t index) {
  const GltfMaterial& gm = s.model.materials[index];
  const std::string pointer = "/materials/" + std::to_string(index);
  for (const auto& [name, value] : gm.extensions.items()) {
    if (!kReadExtensions.count(name))
      s.diagnostics.warning(s.file, pointer + "/extensions/" + pointer_escape(name),
                            "extension '" + name + "' is not read by lamina import; it is ignored");
  }
  if (gm.extensions.contains(kExtensionName))
    import_layered(s, index, gm.extensions.at(kExtensionName));
  else
    import_pbr(s, index);
}

// The same checks as `lamina validate`, with the textures in memory.
void check_document(ImportSession& s) {
  for (int texture : s.wrap_notes)
    s.result.notes.push_back("texture " + std::to_string(texture) +
                             ": wrapT differs from wrapS; lamina wraps both ways alike (wrapS is used)");
  if (s.result.document.materials.empty()) return;
  // The document and its textures as they will be written, in a folder that exists only in
  // memory: the checks find the textures there and never look at the file system.
  const std::filesystem::path folder = std::filesystem::absolute(s.path).parent_path() / ".lamina-import";
  auto overlay = std::make_shared<FileOverlay>();
  for (const ExtractedTexture& t : s.result.textures)
    (*overlay)[(folder / t.file_name).lexically_normal()] = std::string(t.bytes.begin(), t.bytes.end());
  AssetPolicy policy = s.policy;
  policy.roots = {folder};
  policy.overlay = std::move(overlay);
  policy.overlay_only = true;
  CheckedFile checked = check_text(write_document(s.result.document), (folder / "imported.json").string(), policy);
  auto origin_of = [&](const std::string& pointer, std::string& rest) -> const Origin* {
    if (pointer.compare(0, 11, "/materials/") != 0) return nullptr;
    size_t end = pointer.find('/', 11);
    size_t k = std::stoul(pointer.substr(11, end == std::string::npos ? std::string::npos : end - 11));
    rest = end == std::string::npos ? "" : pointer.substr(end);
    return k < s.origins.size() ? &s.origins[k] : nullptr;
  };
  auto report = [&](const Diagnostic& d, bool error) {
    std::string rest;
    const Origin* origin = origin_of(d.pointer, rest);
    std::string pointer = origin ? "/materials/" + std::to_string(origin->gltf_index) : "";
    std::string message = d.message;
    if (origin && origin->layered)
      pointer += std::string("/extensions/") + kExtensionName + "/material" + rest;
    else
      message = "the lamina material made from it " + (error ? std::string("does not check") : "warns") + ": " +
                message + (rest.empty() ? "" : " (at " + rest + ")");
    if (error)
      s.diagnostics.error(s.file, pointer, message, d.hint);
    else
      s.diagnostics.warning(s.file, pointer, message, d.hint);
  };
  for (const auto& d : checked.diagnostics.errors()) report(d, true);
  for (const auto& d : checked.diagnostics.warnings()) report(d, false);
}

ImportResult run(ImportSession& s) {
  if (!s.load()) return std::move(s.result);
  // Label materials (lamina's export marks them) show text, not a surface: they are left out,
  // and so are the extensions only they use.
  std::set<std::string> label_extensions, material_extensions;
  std::vector<bool> label_at(s.model.materials.size());
  size_t labels = 0;
  for (size_t i = 0; i < s.model.materials.size(); ++i) {
    const GltfMaterial& gm = s.model.materials[i];
    const bool label = label_at[i] = is_label(gm);
    labels += label;
    for (const auto& [name, value] : gm.extensions.items())
      (label ? label_extensions : material_extensions).insert(name);
  }
  for (size_t i = 0; i < s.model.extensions_used.size(); ++i) {
    const std::string& name = s.model.extensions_used[i];
    if (kNotMaterialExtensions.count(name))
      s.result.notes.push_back("extension '" + name + "' holds no material data; skipped");
    else if (label_extensions.count(name) && !material_extensions.count(name))
      s.result.notes.push_back("extension '" + name + "' is used only by object labels; skipped");
    else if (!kReadExtensions.count(name))
      s.diagnostics.warning(s.file, "/extensionsUsed/" + std::to_string(i),
                            "extension '" + name + "' is not read by lamina import; it is ignored");
  }
  for (size_t i = 0; i < s.model.materials.size(); ++i)
    if (!label_at[i]) import_material(s, i);
  if (labels > 0)
    s.result.notes.push_back(std::to_string(labels) + " object label material" + (labels == 1 ? " was" : "s were") +
                             " left out");
  // An empty material file is not a valid one: say so rather than write it.
  if (s.diagnostics.ok() && s.result.document.materials.empty()) {
    if (s.model.materials.empty())
      s.diagnostics.error(s.file, "", "the glTF file has no materials: there is nothing to import",
                          "lamina import converts materials; meshes, nodes, cameras and lights are not imported");
    else
      s.diagnostics.error(s.file, "/materials",
                          "the glTF file's materials are all object labels (extras \"" + std::string(kLabelExtra) +
                              "\"): there is nothing to import");
  }
  check_document(s);
  return std::move(s.result);
}

}  // namespace

ImportResult import_gltf_bytes(std::string_view bytes, const std::filesystem::path& path, Diagnostics& diagnostics,
                               const AssetPolicy& policy) {
  ImportSession session(bytes, path, diagnostics, policy.with_default_root(path));
  return run(session);
}

ImportResult import_gltf(const std::filesystem::path& path, Diagnostics& diagnostics, const AssetPolicy& policy) {
  std::string bytes;
  try {
    bytes = read_input_file(path, kMaxBinaryFileBytes);  // IoError: not a user mistake
  } catch (const Error& e) {                             // too large
    for (const auto& d : e.diagnostics()) diagnostics.error(d.file, d.pointer, d.message, d.hint);
    return {};
  }
  return import_gltf_bytes(bytes, path, diagnostics, policy);
}

}  // namespace lamina::gltf
