#include "graph/gltf/import_load.h"

#include <algorithm>

#include "graph/cpu/image.h"
#include "graph/gltf/uri.h"
#include "graph/json_read.h"

namespace lamina::gltf {

namespace {

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

}  // namespace

ImportSession::ImportSession(std::string_view bytes_in, const std::filesystem::path& path_in,
                             Diagnostics& diagnostics_in, const AssetPolicy& policy_in)
    : bytes(bytes_in), path(path_in), file(path_in.string()), diagnostics(diagnostics_in), policy(policy_in) {}

bool ImportSession::load() {
  try {
    model = read_gltf(bytes, path, policy);
  } catch (const Error& e) {
    for (const auto& d : e.diagnostics()) diagnostics.error(d.file, d.pointer, d.message, d.hint);
    return false;
  }
  return true;
}

std::string ImportSession::unique_material_name(const std::string& wanted, size_t index) {
  std::string name = sanitise_identifier(wanted);
  if (name.empty()) name = "material_" + std::to_string(index);
  std::string candidate = name;
  for (int n = 2; names_.count(candidate); ++n) candidate = name + "_" + std::to_string(n);
  names_.insert(candidate);
  return candidate;
}

const std::string* ImportSession::image_of(int texture, const std::string& pointer) {
  if (texture < 0 || static_cast<size_t>(texture) >= model.textures.size()) {
    diagnostics.error(file, pointer,
                      "texture " + std::to_string(texture) + " does not exist (the file has " +
                          std::to_string(model.textures.size()) + " textures)");
    return nullptr;
  }
  const int source = model.textures[static_cast<size_t>(texture)].source;
  if (source < 0) {
    diagnostics.error(file, "/textures/" + std::to_string(texture), "the texture has no \"source\" image",
                      "lamina reads textures with a source image");
    return nullptr;
  }
  auto [cached, first] = images_.emplace(source, std::nullopt);
  if (first) {
    const std::string image_pointer = "/images/" + std::to_string(source);
    try {
      std::string image = model.image_bytes(source);
      decode_linear_image(image, false, policy.max_image_pixels);
      cached->second = std::move(image);
    } catch (const Error& e) {
      for (const auto& d : e.diagnostics()) diagnostics.error(d.file, d.pointer, d.message, d.hint);
    } catch (const ImageError& e) {
      diagnostics.error(file, image_pointer, std::string("the image does not decode: ") + e.what(),
                        "lamina extracts only images it can read");
    }
  }
  return cached->second ? &*cached->second : nullptr;
}

std::string ImportSession::texture_file(int texture, const std::string& pointer, const std::string& wanted) {
  const std::string* image = image_of(texture, pointer);
  if (!image) return "";
  const auto source = static_cast<size_t>(model.textures[static_cast<size_t>(texture)].source);
  std::string name = sanitise_file_name(wanted.empty() ? default_image_name(source, *image) : wanted);
  // Keep the name truthful about the content (an exporter may have converted an EXR to PNG).
  const std::string kind = extension_for(*image);
  std::string ext = lowercase(std::filesystem::path(name).extension().string());
  if (ext == ".jpeg") ext = ".jpg";
  if (!kind.empty() && ext != kind) {
    std::string renamed = std::filesystem::path(name).replace_extension(kind).string();
    result.notes.push_back("image '" + name + "' holds " + kind.substr(1) + " data; extracted as '" + renamed + "'");
    name = renamed;
  }
  return claim_file_name(name, *image);
}

std::string ImportSession::default_image_name(size_t source, const std::string& image_bytes) const {
  const GltfImage& image = model.images[source];
  if (!image.name.empty()) return image.name;
  if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) return uri_decode(image.uri);
  return "image_" + std::to_string(source) + extension_for(image_bytes);
}

// Same name and same bytes share one file; a name already taken by other bytes gets a suffix.
std::string ImportSession::claim_file_name(const std::string& name, const std::string& image) {
  const std::filesystem::path p(name);
  std::string candidate = name;
  for (int n = 2;; ++n) {
    auto it = std::find_if(result.textures.begin(), result.textures.end(),
                           [&](const ExtractedTexture& t) { return t.file_name == candidate; });
    if (it == result.textures.end()) break;
    if (it->bytes.size() == image.size() && std::equal(image.begin(), image.end(), it->bytes.begin())) return candidate;
    candidate = p.stem().string() + "_" + std::to_string(n) + p.extension().string();
  }
  result.textures.push_back({candidate, std::vector<unsigned char>(image.begin(), image.end())});
  return candidate;
}

void ImportSession::add(Material m, Origin origin) {
  result.document.materials.push_back(std::move(m));
  origins.push_back(origin);
}

std::string pointer_escape(const std::string& token) { return pointer_append("", token).substr(1); }

}  // namespace lamina::gltf
