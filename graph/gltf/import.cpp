#include "graph/gltf/import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <vector>

#include "graph/cpu/image.h"
#include "graph/gltf/export.h"
#include "graph/gltf/pbr_to_layers.h"
#include "graph/gltf/uri.h"
#include "graph/json_read.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "graph/number_text.h"

namespace lamina::gltf {

namespace {

using Json = nlohmann::json;

// Extensions this importer reads; any other one is reported and ignored.
constexpr const char* kIor = "KHR_materials_ior";
constexpr const char* kSpecular = "KHR_materials_specular";
constexpr const char* kClearcoat = "KHR_materials_clearcoat";
const std::set<std::string> kReadExtensions{kExtensionName, kIor, kSpecular, kClearcoat};
// Extensions that carry no material data (lights, geometry encodings, instancing, metadata): a
// material import loses nothing by skipping them, so they give a note rather than a warning.
const std::set<std::string> kNotMaterialExtensions{"KHR_lights_punctual", "KHR_mesh_quantization",
                                                   "EXT_mesh_gpu_instancing", "KHR_xmp_json_ld"};

// glTF 2.0 sec. 5.26 (sampler.wrapS) enumerants.
constexpr int kWrapClamp = 33071;
constexpr int kWrapMirror = 33648;

// The images are extracted as they are stored, so the loader only keeps the encoded bytes.
bool keep_encoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                  int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

std::string extension_for(const std::vector<unsigned char>& bytes) {
  static const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  if (bytes.size() >= 8 && std::equal(png, png + 8, bytes.begin())) return ".png";
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return ".jpg";
  return "";
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

// A scratch directory holding the extracted textures while the imported document is checked.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    std::random_device random;
    const auto base = std::filesystem::temp_directory_path();
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = base / ("lamina-import-" + std::to_string(random()));
      if (std::filesystem::create_directory(path_)) return;
    }
    throw IoError("cannot create a scratch directory in " + base.string());
  }
  ~ScratchDirectory() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

  void write(const std::string& name, const std::vector<unsigned char>& bytes) const {
    std::ofstream out(path_ / name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw IoError("cannot write " + (path_ / name).string());
  }

 private:
  std::filesystem::path path_;
};

// Where an imported material came from, to give the checker's findings glTF pointers.
struct Origin {
  size_t gltf_index = 0;
  bool layered = false;  // from LAMINA_materials_layered
};

class Importer {
 public:
  Importer(const std::filesystem::path& path, Diagnostics& diagnostics)
      : path_(path), file_(path.string()), diagnostics_(diagnostics) {}

  ImportResult run() {
    if (!load_model()) return std::move(result_);
    // Label materials (lamina's export marks them) show text, not a surface: they are left out,
    // and so are the extensions only they use.
    std::set<std::string> label_extensions, material_extensions;
    std::vector<bool> label_at(model_.materials.size());
    size_t labels = 0;
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& gm = model_.materials[i];
      const bool label = label_at[i] = is_label(gm);
      labels += label;
      const Json extensions = parse_object(gm.extensions_json_string);
      for (const auto& [name, value] : extensions.items())
        (label ? label_extensions : material_extensions).insert(name);
    }
    for (size_t i = 0; i < model_.extensionsUsed.size(); ++i) {
      const std::string& name = model_.extensionsUsed[i];
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
    const std::string text = read_input_file(path_, kMaxBinaryFileBytes);  // IoError: not a user mistake
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_encoded, nullptr);
    // tinygltf drops extension values that are not objects; the original text keeps them, so a
    // wrong type is reported rather than ignored.
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
    std::string err, warn;
    const std::string base_dir = path_.parent_path().string();
    const bool binary = text.size() >= 4 && text.compare(0, 4, "glTF") == 0;
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model_, &err, &warn, reinterpret_cast<const unsigned char*>(text.data()),
                                             static_cast<unsigned int>(text.size()), base_dir)
               : loader.LoadASCIIFromString(&model_, &err, &warn, text.data(), static_cast<unsigned int>(text.size()),
                                            base_dir);
    report_lines(warn, Severity::Warning);
    report_lines(err, Severity::Error);
    if (!ok && err.empty())
      diagnostics_.error(file_, "",
                         std::string("not a valid glTF 2.0 ") + (binary ? "binary (.glb)" : "JSON") + " file");
    return ok;
  }

  // tinygltf reports one problem per line, without a JSON pointer.
  void report_lines(const std::string& text, Severity severity) {
    size_t start = 0;
    while (start < text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      if (!line.empty()) {
        if (severity == Severity::Error)
          diagnostics_.error(file_, "", "glTF: " + line);
        else
          diagnostics_.warning(file_, "", "glTF: " + line);
      }
      start = end + 1;
    }
  }

  // tinygltf keeps the original text of extensions and extras; it parsed, so it parses again.
  static Json parse_object(const std::string& text) {
    if (text.empty()) return Json::object();
    Json j = Json::parse(text, nullptr, false);
    return j.is_object() ? j : Json::object();
  }

  static bool is_label(const tinygltf::Material& gm) {
    return parse_object(gm.extras_json_string).contains(kLabelExtra);
  }

  std::string unique_material_name(const std::string& wanted, size_t index) {
    std::string name = sanitise_identifier(wanted);
    if (name.empty()) name = "material_" + std::to_string(index);
    std::string candidate = name;
    for (int n = 2; names_.count(candidate); ++n) candidate = name + "_" + std::to_string(n);
    names_.insert(candidate);
    return candidate;
  }

  void import_material(size_t index) {
    const tinygltf::Material& gm = model_.materials[index];
    const std::string pointer = "/materials/" + std::to_string(index);
    // tinygltf wrote this text from a parsed object, so it parses.
    extensions_ = gm.extensions_json_string.empty() ? Json::object() : Json::parse(gm.extensions_json_string);
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

  // The image of glTF texture `texture`, with its bytes, or nullptr after an error.
  const tinygltf::Image* image_of(int texture, const std::string& pointer) {
    if (texture < 0 || static_cast<size_t>(texture) >= model_.textures.size()) {
      diagnostics_.error(file_, pointer,
                         "texture " + std::to_string(texture) + " does not exist (the file has " +
                             std::to_string(model_.textures.size()) + " textures)");
      return nullptr;
    }
    const int source = model_.textures[static_cast<size_t>(texture)].source;
    if (source < 0 || static_cast<size_t>(source) >= model_.images.size()) {
      diagnostics_.error(file_, "/textures/" + std::to_string(texture) + "/source",
                         "expected the index of an image of the file");
      return nullptr;
    }
    const tinygltf::Image& image = model_.images[static_cast<size_t>(source)];
    if (image.image.empty()) {
      diagnostics_.error(
          file_, "/images/" + std::to_string(source),
          "image " + (image.uri.empty() ? std::to_string(source) : "'" + image.uri + "'") + " could not be read");
      return nullptr;
    }
    return &image;
  }

  // The extracted file name for glTF texture `texture` (its image's bytes), or "" after an error.
  std::string texture_file(int texture, const std::string& pointer, const std::string& wanted) {
    const tinygltf::Image* found = image_of(texture, pointer);
    if (!found) return "";
    const tinygltf::Image& image = *found;
    const auto source = static_cast<size_t>(model_.textures[static_cast<size_t>(texture)].source);
    std::string name = sanitise_file_name(wanted.empty() ? default_image_name(source) : wanted);
    // Keep the name truthful about the content (an exporter may have converted an EXR to PNG).
    const std::string kind = extension_for(image.image);
    std::string ext = lowercase(std::filesystem::path(name).extension().string());
    if (ext == ".jpeg") ext = ".jpg";
    if (!kind.empty() && ext != kind) {
      std::string renamed = std::filesystem::path(name).replace_extension(kind).string();
      result_.notes.push_back("image '" + name + "' holds " + kind.substr(1) + " data; extracted as '" + renamed + "'");
      name = renamed;
    }
    return claim_file_name(name, image.image);
  }

  std::string default_image_name(size_t source) const {
    const tinygltf::Image& image = model_.images[source];
    if (!image.name.empty()) return image.name;
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) return uri_decode(image.uri);
    return "image_" + std::to_string(source) + extension_for(image.image);
  }

  // Same name and same bytes share one file; a name already taken by other bytes gets a suffix.
  std::string claim_file_name(const std::string& name, const std::vector<unsigned char>& bytes) {
    const std::filesystem::path p(name);
    std::string candidate = name;
    for (int n = 2;; ++n) {
      auto it = std::find_if(result_.textures.begin(), result_.textures.end(),
                             [&](const ExtractedTexture& t) { return t.file_name == candidate; });
      if (it == result_.textures.end()) break;
      if (it->bytes == bytes) return candidate;
      candidate = p.stem().string() + "_" + std::to_string(n) + p.extension().string();
    }
    scratch_.write(candidate, bytes);
    result_.textures.push_back({candidate, bytes});
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
    const tinygltf::Material& gm = model_.materials[index];
    const std::string pointer = "/materials/" + std::to_string(index);
    const std::string name = unique_material_name(gm.name, index);
    const auto& pbr_in = gm.pbrMetallicRoughness;
    std::vector<std::string>& notes = result_.notes;
    const size_t errors_before = diagnostics_.errors().size();

    PbrMaterial pbr;
    for (size_t c = 0; c < 3 && c < pbr_in.baseColorFactor.size(); ++c) pbr.base_color[c] = pbr_in.baseColorFactor[c];
    pbr.metallic = pbr_in.metallicFactor;
    pbr.roughness = pbr_in.roughnessFactor;

    if (pbr_in.baseColorTexture.index >= 0) {
      const std::string tp = pointer + "/pbrMetallicRoughness/baseColorTexture";
      std::string file = texture_file(pbr_in.baseColorTexture.index, tp + "/index", "");
      if (!file.empty()) pbr.base_color_texture = PbrMaterial::Texture{file, wrap_of(pbr_in.baseColorTexture.index)};
      if (pbr_in.baseColorTexture.texCoord != 0)
        notes.push_back(name + ": baseColorTexture uses TEXCOORD_" + std::to_string(pbr_in.baseColorTexture.texCoord) +
                        "; lamina has one uv set");
      if (pbr.base_color != std::array<double, 3>{1.0, 1.0, 1.0})
        notes.push_back(name + ": baseColorFactor does not multiply the texture (lamina has no colour product node)");
    }
    if (pbr_in.metallicRoughnessTexture.index >= 0)
      average_metallic_roughness(pbr_in.metallicRoughnessTexture.index,
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
    if (gm.normalTexture.index >= 0) notes.push_back(name + ": normalTexture is not imported");
    if (gm.occlusionTexture.index >= 0) notes.push_back(name + ": occlusionTexture is not imported");
    if (gm.emissiveTexture.index >= 0 ||
        std::any_of(gm.emissiveFactor.begin(), gm.emissiveFactor.end(), [](double e) { return e != 0.0; }))
      notes.push_back(name + ": emission is not imported (lamina materials do not emit)");
    if (gm.alphaMode != "OPAQUE") notes.push_back(name + ": alphaMode " + gm.alphaMode + " is not imported (opaque)");

    if (diagnostics_.errors().size() != errors_before) return;
    add(layered_from_pbr(name, pbr, notes), Origin{index, false});
  }

  std::string wrap_of(int texture) const {
    const int sampler = model_.textures[static_cast<size_t>(texture)].sampler;
    if (sampler < 0 || static_cast<size_t>(sampler) >= model_.samplers.size()) return "repeat";
    const auto& s = model_.samplers[static_cast<size_t>(sampler)];
    const int wrap = s.wrapS;
    if (s.wrapT != s.wrapS) wrap_notes_.insert(texture);
    return wrap == kWrapClamp ? "clamp" : wrap == kWrapMirror ? "mirror" : "repeat";
  }

  // glTF 2.0 sec. 3.9.2: metalness is the texture's blue channel, roughness its green one, both
  // multiplying the factors. lamina cannot route one channel to a parameter, so the means are used.
  void average_metallic_roughness(int texture, const std::string& pointer, const std::string& name, PbrMaterial& pbr) {
    const tinygltf::Image* image = image_of(texture, pointer + "/index");
    if (!image) return;
    // Read from the scratch directory, not extracted: no node refers to it.
    const std::string file = ".metallic_roughness_" + std::to_string(texture) + extension_for(image->image);
    scratch_.write(file, image->image);
    double green = 0.0, blue = 0.0;
    try {
      auto decoded =
          decode_linear_image(std::string_view(reinterpret_cast<const char*>(image->image.data()), image->image.size()),
                              file, false, kDefaultMaxImagePixels);
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

  // --- the same checks as `lamina validate`, with the textures in the scratch directory ---------

  void check_document() {
    for (int texture : wrap_notes_)
      result_.notes.push_back("texture " + std::to_string(texture) +
                              ": wrapT differs from wrapS; lamina wraps both ways alike (wrapS is used)");
    if (result_.document.materials.empty()) return;
    const std::filesystem::path checked_path = scratch_.path() / "imported.json";
    CheckedFile checked = check_text(write_document(result_.document), checked_path.string());
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

  std::filesystem::path path_;
  std::string file_;
  Diagnostics& diagnostics_;
  tinygltf::Model model_;
  ScratchDirectory scratch_;
  ImportResult result_;
  std::vector<Origin> origins_;
  std::set<std::string> names_;
  mutable std::set<int> wrap_notes_;
  Json extensions_;  // the current material's extensions, as written in the file
};

}  // namespace

ImportResult import_gltf(const std::filesystem::path& path, Diagnostics& diagnostics) {
  return Importer(path, diagnostics).run();
}

}  // namespace lamina::gltf
