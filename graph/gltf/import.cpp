#include "graph/gltf/import.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "graph/cpu/image.h"
#include "graph/gltf/export.h"
#include "graph/gltf/gltf_read.h"
#include "graph/gltf/pbr_to_layers.h"
#include "graph/gltf/uri.h"
#include "graph/json_read.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "graph/number_text.h"

namespace lamina::gltf {

namespace {

using Json = nlohmann::ordered_json;

// Extensions this importer reads; any other one is reported and ignored.
constexpr const char* kIor = "KHR_materials_ior";
constexpr const char* kSpecular = "KHR_materials_specular";
constexpr const char* kClearcoat = "KHR_materials_clearcoat";
const std::set<std::string> kReadExtensions{kExtensionName, kIor, kSpecular, kClearcoat};
// Extensions that carry no material data (lights, geometry encodings, instancing, metadata): a
// material import loses nothing by skipping them, so they give a note rather than a warning.
const std::set<std::string> kNotMaterialExtensions{"KHR_lights_punctual", "KHR_mesh_quantization",
                                                   "EXT_mesh_gpu_instancing", "KHR_xmp_json_ld"};

// ".png" or ".jpg" for the image formats glTF holds, by the bytes' signature; "" otherwise.
std::string extension_for(std::string_view bytes) {
  ImageFormat format;
  if (!image_format_of(bytes, format)) return "";
  return format == ImageFormat::Png ? ".png" : format == ImageFormat::Jpeg ? ".jpg" : "";
}

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A lamina identifier: letters, digits and '_', not starting with a digit.
std::string sanitise_identifier(const std::string& name) {
  std::string out;
  for (char c : name) {
    bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    char next = keep ? c : '_';
    if (next == '_' && !out.empty() && out.back() == '_') continue;
    out += next;
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  while (!out.empty() && out.front() == '_') out.erase(out.begin());
  if (!out.empty() && out[0] >= '0' && out[0] <= '9') out = "m_" + out;
  return out;
}

// A plain file name (no directories), safe on every file system.
std::string sanitise_file_name(const std::string& name) {
  std::string base = std::filesystem::path(name).filename().string();
  std::string out;
  for (char c : base) {
    bool keep =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    out += keep ? c : '_';
  }
  if (out.empty() || out.front() == '.') out = "image" + out;
  return out;
}

// Where an imported material came from, to give the checker's findings glTF pointers.
struct Origin {
  size_t gltf_index = 0;
  bool layered = false;  // from LAMINA_materials_layered
};

class Importer {
 public:
  Importer(std::string_view bytes, const std::filesystem::path& path, Diagnostics& diagnostics,
           const AssetPolicy& policy)
      : bytes_(bytes), path_(path), file_(path.string()), diagnostics_(diagnostics), policy_(policy) {}

  ImportResult run() {
    if (!load_model()) return std::move(result_);
    // Label materials (lamina's export marks them) show text, not a surface: they are left out,
    // and so are the extensions only they use.
    std::set<std::string> label_extensions, material_extensions;
    std::vector<bool> label_at(model_.materials.size());
    size_t labels = 0;
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const GltfMaterial& gm = model_.materials[i];
      const bool label = label_at[i] = is_label(gm);
      labels += label;
      for (const auto& [name, value] : gm.extensions.items())
        (label ? label_extensions : material_extensions).insert(name);
    }
    for (size_t i = 0; i < model_.extensions_used.size(); ++i) {
      const std::string& name = model_.extensions_used[i];
      if (kNotMaterialExtensions.count(name))
        result_.notes.push_back("extension '" + name + "' holds no material data; skipped");
      else if (label_extensions.count(name) && !material_extensions.count(name))
        result_.notes.push_back("extension '" + name + "' is used only by object labels; skipped");
      else if (!kReadExtensions.count(name))
        diagnostics_.warning(file_, "/extensionsUsed/" + std::to_string(i),
                             "extension '" + name + "' is not read by lamina import; it is ignored");
    }
    for (size_t i = 0; i < model_.materials.size(); ++i)
      if (!label_at[i]) import_material(i);
    if (labels > 0)
      result_.notes.push_back(std::to_string(labels) + " object label material" + (labels == 1 ? " was" : "s were") +
                              " left out");
    // An empty material file is not a valid one: say so rather than write it.
    if (diagnostics_.ok() && result_.document.materials.empty()) {
      if (model_.materials.empty())
        diagnostics_.error(file_, "", "the glTF file has no materials: there is nothing to import",
                           "lamina import converts materials; meshes, nodes, cameras and lights are not imported");
      else
        diagnostics_.error(file_, "/materials",
                           "the glTF file's materials are all object labels (extras \"" + std::string(kLabelExtra) +
                               "\"): there is nothing to import");
    }
    check_document();
    return std::move(result_);
  }

 private:
  bool load_model() {
    try {
      model_ = read_gltf(bytes_, path_, policy_);
    } catch (const Error& e) {
      for (const auto& d : e.diagnostics()) diagnostics_.error(d.file, d.pointer, d.message, d.hint);
      return false;
    }
    return true;
  }

  static bool is_label(const GltfMaterial& gm) { return gm.extras.is_object() && gm.extras.contains(kLabelExtra); }

  std::string unique_material_name(const std::string& wanted, size_t index) {
    std::string name = sanitise_identifier(wanted);
    if (name.empty()) name = "material_" + std::to_string(index);
    std::string candidate = name;
    for (int n = 2; names_.count(candidate); ++n) candidate = name + "_" + std::to_string(n);
    names_.insert(candidate);
    return candidate;
  }

  void import_material(size_t index) {
    const GltfMaterial& gm = model_.materials[index];
    const std::string pointer = "/materials/" + std::to_string(index);
    extensions_ = gm.extensions;
    for (const auto& [name, value] : extensions_.items()) {
      if (!kReadExtensions.count(name))
        diagnostics_.warning(file_, pointer + "/extensions/" + pointer_escape(name),
                             "extension '" + name + "' is not read by lamina import; it is ignored");
    }
    if (extensions_.contains(kExtensionName))
      import_layered(index, extensions_.at(kExtensionName));
    else
      import_pbr(index);
  }

  static std::string pointer_escape(const std::string& token) { return pointer_append("", token).substr(1); }

  // --- LAMINA_materials_layered: the exact graph -----------------------------------------------

  void import_layered(size_t index, const Json& extension) {
    const std::string base = "/materials/" + std::to_string(index) + "/extensions/" + kExtensionName;
    if (!extension.is_object()) {
      diagnostics_.error(file_, base, "expected an object with \"format\", \"material\" and \"textures\"");
      return;
    }
    for (const auto& [key, value] : extension.items())
      if (key != "format" && key != "material" && key != "textures" && key != "extensions" && key != "extras")
        diagnostics_.warning(file_, base + "/" + pointer_escape(key), "unknown property '" + key + "' is ignored",
                             "the extension has format, material and textures");
    const Json format = extension.value("format", Json());
    if (!format.is_number_integer() || format.get<int>() != kFormatVersion) {
      diagnostics_.error(file_, base + "/format",
                         format.is_number() ? "unsupported format " + format.dump() + "; this lamina reads 1"
                                            : "expected the integer 1 (the lamina material format version)");
      return;
    }
    const Json material = extension.value("material", Json());
    if (!material.is_object()) {
      diagnostics_.error(file_, base + "/material", "expected a lamina material object (as in a material file)");
      return;
    }
    // The regular reader, on a one-material document; its pointers are mapped back below.
    const Json wrapper{{"format", kFormatVersion}, {"materials", Json::array({material})}};
    Diagnostics read;
    Document single = read_document(wrapper.dump(), file_, read);
    append_mapped(read, [&](const std::string& p) { return map_pointer(p, base + "/material"); });
    if (!read.ok() || single.materials.size() != 1) return;
    Material m = std::move(single.materials.front());

    const Json textures = extension.value("textures", Json::object());
    if (!textures.is_object()) {
      diagnostics_.error(file_, base + "/textures",
                         "expected an object mapping image node ids to {\"index\": texture}");
      return;
    }
    bool ok = true;
    for (const auto& [id, entry] : textures.items()) {
      const Node* node = m.find_node(id);
      if (!node || node->type != "texture/image") {
        diagnostics_.error(file_, base + "/textures/" + pointer_escape(id),
                           "'" + id + "' is not a texture/image node of the material");
        ok = false;
      }
    }
    for (size_t n = 0; n < m.nodes.size(); ++n) {
      Node& node = m.nodes[n];
      if (node.type != "texture/image") continue;
      const std::string entry_pointer = base + "/textures/" + pointer_escape(node.id);
      if (!textures.contains(node.id)) {
        diagnostics_.error(file_, base + "/textures", "no texture for the image node '" + node.id + "'",
                           "add \"" + node.id + "\": {\"index\": <glTF texture>}");
        ok = false;
        continue;
      }
      const Json& entry = textures.at(node.id);
      if (!entry.is_object() || !entry.contains("index") || !entry.at("index").is_number_integer()) {
        diagnostics_.error(file_, entry_pointer, "expected {\"index\": <glTF texture index>}");
        ok = false;
        continue;
      }
      for (auto& param : node.params) {
        if (param.name != "file" || !std::holds_alternative<std::string>(param.value)) continue;
        // The graph keeps the original path; the extracted file takes its base name.
        const std::string wanted = std::filesystem::path(std::get<std::string>(param.value)).filename().string();
        const std::string file = texture_file(entry.at("index").get<int>(), entry_pointer + "/index", wanted);
        if (file.empty())
          ok = false;
        else
          param.value = file;
      }
    }
    if (!ok) return;
    // The graph's own name first: it is what the material file called it (the glTF name is a copy
    // a tool may have changed).
    const std::string wanted_name = m.name.empty() ? model_.materials[index].name : m.name;
    m.name = unique_material_name(wanted_name, index);
    add(std::move(m), Origin{index, true});
  }

  // "/materials/0/rest" of the one-material wrapper -> base + "/rest".
  static std::string map_pointer(const std::string& pointer, const std::string& base) {
    const std::string prefix = "/materials/0";
    if (pointer.compare(0, prefix.size(), prefix) == 0) return base + pointer.substr(prefix.size());
    return base;
  }

  template <class Map>
  void append_mapped(const Diagnostics& from, Map map) {
    for (const auto& d : from.errors()) diagnostics_.error(file_, map(d.pointer), d.message, d.hint);
    for (const auto& d : from.warnings()) diagnostics_.warning(file_, map(d.pointer), d.message, d.hint);
  }

  // --- textures --------------------------------------------------------------------------------

  // The encoded bytes of the image of glTF texture `texture`, read and decoded once (as an image
  // under the pixel budget: bytes that are no image are never extracted), or nullptr after an error.
  const std::string* image_of(int texture, const std::string& pointer) {
    if (texture < 0 || static_cast<size_t>(texture) >= model_.textures.size()) {
      diagnostics_.error(file_, pointer,
                         "texture " + std::to_string(texture) + " does not exist (the file has " +
                             std::to_string(model_.textures.size()) + " textures)");
      return nullptr;
    }
    const int source = model_.textures[static_cast<size_t>(texture)].source;
    if (source < 0) {
      diagnostics_.error(file_, "/textures/" + std::to_string(texture), "the texture has no \"source\" image",
                         "lamina reads textures with a source image");
      return nullptr;
    }
    auto [cached, first] = images_.emplace(source, std::nullopt);
    if (first) {
      const std::string image_pointer = "/images/" + std::to_string(source);
      try {
        std::string bytes = model_.image_bytes(source);
        decode_linear_image(bytes, false, policy_.max_image_pixels);
        cached->second = std::move(bytes);
      } catch (const Error& e) {
        for (const auto& d : e.diagnostics()) diagnostics_.error(d.file, d.pointer, d.message, d.hint);
      } catch (const ImageError& e) {
        diagnostics_.error(file_, image_pointer, std::string("the image does not decode: ") + e.what(),
                           "lamina extracts only images it can read");
      }
    }
    return cached->second ? &*cached->second : nullptr;
  }

  // The extracted file name for glTF texture `texture` (its image's bytes), or "" after an error.
  std::string texture_file(int texture, const std::string& pointer, const std::string& wanted) {
    const std::string* bytes = image_of(texture, pointer);
    if (!bytes) return "";
    const auto source = static_cast<size_t>(model_.textures[static_cast<size_t>(texture)].source);
    std::string name = sanitise_file_name(wanted.empty() ? default_image_name(source, *bytes) : wanted);
    // Keep the name truthful about the content (an exporter may have converted an EXR to PNG).
    const std::string kind = extension_for(*bytes);
    std::string ext = lowercase(std::filesystem::path(name).extension().string());
    if (ext == ".jpeg") ext = ".jpg";
    if (!kind.empty() && ext != kind) {
      std::string renamed = std::filesystem::path(name).replace_extension(kind).string();
      result_.notes.push_back("image '" + name + "' holds " + kind.substr(1) + " data; extracted as '" + renamed + "'");
      name = renamed;
    }
    return claim_file_name(name, *bytes);
  }

  std::string default_image_name(size_t source, const std::string& bytes) const {
    const GltfImage& image = model_.images[source];
    if (!image.name.empty()) return image.name;
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) return uri_decode(image.uri);
    return "image_" + std::to_string(source) + extension_for(bytes);
  }

  // Same name and same bytes share one file; a name already taken by other bytes gets a suffix.
  std::string claim_file_name(const std::string& name, const std::string& bytes) {
    const std::filesystem::path p(name);
    std::string candidate = name;
    for (int n = 2;; ++n) {
      auto it = std::find_if(result_.textures.begin(), result_.textures.end(),
                             [&](const ExtractedTexture& t) { return t.file_name == candidate; });
      if (it == result_.textures.end()) break;
      if (it->bytes.size() == bytes.size() && std::equal(bytes.begin(), bytes.end(), it->bytes.begin()))
        return candidate;
      candidate = p.stem().string() + "_" + std::to_string(n) + p.extension().string();
    }
    result_.textures.push_back({candidate, std::vector<unsigned char>(bytes.begin(), bytes.end())});
    return candidate;
  }

  // --- core metallic-roughness and the KHR extensions: an approximation ------------------------

  // A number of a KHR extension object; a wrong type is an error of the glTF.
  double number(const Json& v, const std::string& pointer, double fallback) {
    if (v.is_number()) return v.get<double>();
    diagnostics_.error(file_, pointer, "expected a number");
    return fallback;
  }
  double number(const Json& object, const std::string& key, double fallback, const std::string& pointer) {
    return object.contains(key) ? number(object.at(key), pointer + "/" + key, fallback) : fallback;
  }

  const Json* khr_extension(const char* name, const std::string& pointer) {
    auto it = extensions_.find(name);
    if (it == extensions_.end()) return nullptr;
    if (!it->is_object()) {
      diagnostics_.error(file_, pointer + "/extensions/" + name, "expected an object");
      return nullptr;
    }
    return &*it;
  }

  void import_pbr(size_t index) {
    const GltfMaterial& gm = model_.materials[index];
    const std::string pointer = "/materials/" + std::to_string(index);
    const std::string name = unique_material_name(gm.name, index);
    std::vector<std::string>& notes = result_.notes;
    const size_t errors_before = diagnostics_.errors().size();

    PbrMaterial pbr;
    for (size_t c = 0; c < 3; ++c) pbr.base_color[c] = gm.base_color_factor[c];
    pbr.metallic = gm.metallic_factor;
    pbr.roughness = gm.roughness_factor;

    if (gm.base_color_texture.index >= 0) {
      const std::string tp = pointer + "/pbrMetallicRoughness/baseColorTexture";
      std::string file = texture_file(gm.base_color_texture.index, tp + "/index", "");
      if (!file.empty()) pbr.base_color_texture = PbrMaterial::Texture{file, wrap_of(gm.base_color_texture.index)};
      if (gm.base_color_texture.tex_coord != 0)
        notes.push_back(name + ": baseColorTexture uses TEXCOORD_" + std::to_string(gm.base_color_texture.tex_coord) +
                        "; lamina has one uv set");
      if (pbr.base_color != std::array<double, 3>{1.0, 1.0, 1.0})
        notes.push_back(name + ": baseColorFactor does not multiply the texture (lamina has no colour product node)");
    }
    if (gm.metallic_roughness_texture.index >= 0)
      average_metallic_roughness(gm.metallic_roughness_texture.index,
                                 pointer + "/pbrMetallicRoughness/metallicRoughnessTexture", name, pbr);

    if (const auto* ior = khr_extension(kIor, pointer)) {
      const std::string ep = pointer + "/extensions/" + kIor;
      pbr.ior = number(*ior, "ior", 1.5, ep);
      // KHR_materials_ior allows ior = 0 (no refraction) and values below 1; lamina needs >= 1.
      if (pbr.ior < 1.0) {
        notes.push_back(name + ": ior " + number_text(pbr.ior) + " is below 1; using 1.5");
        pbr.ior = 1.5;
      }
    }
    if (const auto* spec = khr_extension(kSpecular, pointer)) {
      const std::string ep = pointer + "/extensions/" + kSpecular;
      pbr.specular = number(*spec, "specularFactor", 1.0, ep);
      if (spec->contains("specularColorFactor")) {
        const Json& color = spec->at("specularColorFactor");
        if (!color.is_array() || color.size() != 3)
          diagnostics_.error(file_, ep + "/specularColorFactor", "expected an array of 3 numbers");
        else
          for (int c = 0; c < 3; ++c)
            pbr.specular_color[static_cast<size_t>(c)] =
                number(color.at(static_cast<size_t>(c)), ep + "/specularColorFactor/" + std::to_string(c), 1.0);
      }
      if (pbr.specular_color[0] != pbr.specular_color[1] || pbr.specular_color[1] != pbr.specular_color[2])
        notes.push_back(name +
                        ": the specular colour's tint is averaged into one ior (lamina interfaces are untinted)");
      if (spec->contains("specularTexture") || spec->contains("specularColorTexture"))
        notes.push_back(name + ": specular textures are not imported; the factors are used");
    }
    if (const auto* coat = khr_extension(kClearcoat, pointer)) {
      const std::string ep = pointer + "/extensions/" + kClearcoat;
      pbr.clearcoat = number(*coat, "clearcoatFactor", 0.0, ep);
      pbr.clearcoat_roughness = number(*coat, "clearcoatRoughnessFactor", 0.0, ep);
      for (const char* t : {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"})
        if (coat->contains(t)) notes.push_back(name + ": " + t + " is not imported; the factors are used");
    }
    if (gm.normal_texture.index >= 0) notes.push_back(name + ": normalTexture is not imported");
    if (gm.occlusion_texture.index >= 0) notes.push_back(name + ": occlusionTexture is not imported");
    if (gm.emissive_texture.index >= 0 ||
        std::any_of(gm.emissive_factor.begin(), gm.emissive_factor.end(), [](double e) { return e != 0.0; }))
      notes.push_back(name + ": emission is not imported (lamina materials do not emit)");
    if (gm.alpha_mode != "OPAQUE") notes.push_back(name + ": alphaMode " + gm.alpha_mode + " is not imported (opaque)");

    if (diagnostics_.errors().size() != errors_before) return;
    add(layered_from_pbr(name, pbr, notes), Origin{index, false});
  }

  std::string wrap_of(int texture) const {
    const int sampler = model_.textures[static_cast<size_t>(texture)].sampler;
    if (sampler < 0 || static_cast<size_t>(sampler) >= model_.samplers.size()) return "repeat";
    const auto& s = model_.samplers[static_cast<size_t>(sampler)];
    const int wrap = s.wrap_s;
    if (s.wrap_t != s.wrap_s) wrap_notes_.insert(texture);
    return wrap == kClampToEdge ? "clamp" : wrap == kMirroredRepeat ? "mirror" : "repeat";
  }

  // glTF 2.0 sec. 3.9.2: metalness is the texture's blue channel, roughness its green one, both
  // multiplying the factors. lamina cannot route one channel to a parameter, so the means are used.
  void average_metallic_roughness(int texture, const std::string& pointer, const std::string& name, PbrMaterial& pbr) {
    // Decoded in memory, not extracted: no node refers to it.
    const std::string* image = image_of(texture, pointer + "/index");
    if (!image) return;
    double green = 0.0, blue = 0.0;
    try {
      auto decoded = decode_linear_image(*image, false, policy_.max_image_pixels);
      for (const auto& t : decoded->texels) {
        green += t.g;
        blue += t.b;
      }
      const double count = static_cast<double>(decoded->texels.size());
      green /= count;
      blue /= count;
    } catch (const ImageError& e) {
      diagnostics_.warning(file_, pointer, std::string("cannot read the texture: ") + e.what(),
                           "the metallic and roughness factors are used alone");
      return;
    }
    pbr.metallic *= blue;
    pbr.roughness *= green;
    result_.notes.push_back(name + ": metallicRoughnessTexture is replaced by its means (metallic x " +
                            number_text(blue) + ", roughness x " + number_text(green) + ")");
  }

  void add(Material m, Origin origin) {
    result_.document.materials.push_back(std::move(m));
    origins_.push_back(origin);
  }

  // --- the same checks as `lamina validate`, with the textures in memory -------------------------

  void check_document() {
    for (int texture : wrap_notes_)
      result_.notes.push_back("texture " + std::to_string(texture) +
                              ": wrapT differs from wrapS; lamina wraps both ways alike (wrapS is used)");
    if (result_.document.materials.empty()) return;
    // The document and its textures as they will be written, in a folder that exists only in
    // memory: the checks find the textures there and never look at the file system.
    const std::filesystem::path folder = std::filesystem::absolute(path_).parent_path() / ".lamina-import";
    auto overlay = std::make_shared<FileOverlay>();
    for (const ExtractedTexture& t : result_.textures)
      (*overlay)[(folder / t.file_name).lexically_normal()] = std::string(t.bytes.begin(), t.bytes.end());
    AssetPolicy policy = policy_;
    policy.roots = {folder};
    policy.overlay = std::move(overlay);
    policy.overlay_only = true;
    CheckedFile checked = check_text(write_document(result_.document), (folder / "imported.json").string(), policy);
    auto origin_of = [&](const std::string& pointer, std::string& rest) -> const Origin* {
      if (pointer.compare(0, 11, "/materials/") != 0) return nullptr;
      size_t end = pointer.find('/', 11);
      size_t k = std::stoul(pointer.substr(11, end == std::string::npos ? std::string::npos : end - 11));
      rest = end == std::string::npos ? "" : pointer.substr(end);
      return k < origins_.size() ? &origins_[k] : nullptr;
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
        diagnostics_.error(file_, pointer, message, d.hint);
      else
        diagnostics_.warning(file_, pointer, message, d.hint);
    };
    for (const auto& d : checked.diagnostics.errors()) report(d, true);
    for (const auto& d : checked.diagnostics.warnings()) report(d, false);
  }

  std::string_view bytes_;
  std::filesystem::path path_;
  std::string file_;
  Diagnostics& diagnostics_;
  AssetPolicy policy_;
  GltfAsset model_;
  std::map<int, std::optional<std::string>> images_;  // per image index: its bytes once read and decoded
  ImportResult result_;
  std::vector<Origin> origins_;
  std::set<std::string> names_;
  mutable std::set<int> wrap_notes_;
  Json extensions_;  // the current material's extensions, as written in the file
};

}  // namespace

ImportResult import_gltf_bytes(std::string_view bytes, const std::filesystem::path& path, Diagnostics& diagnostics,
                               const AssetPolicy& policy) {
  return Importer(bytes, path, diagnostics, policy.with_default_root(path)).run();
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
