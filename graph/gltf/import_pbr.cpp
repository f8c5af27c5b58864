#include "graph/gltf/import_pbr.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "graph/cpu/image.h"
#include "graph/gltf/pbr_to_layers.h"
#include "graph/json_type.h"
#include "graph/number_text.h"

namespace lamina::gltf {

namespace {

// A number of a KHR extension object; a wrong type is an error of the glTF.
double number(ImportSession& s, const Json& v, const std::string& pointer, double fallback) {
  if (v.is_number()) return v.get<double>();
  s.diagnostics.error(s.file, pointer, "expected a number");
  return fallback;
}
double number(ImportSession& s, const Json& object, const std::string& key, double fallback,
              const std::string& pointer) {
  return object.contains(key) ? number(s, object.at(key), pointer + "/" + key, fallback) : fallback;
}

const Json* khr_extension(ImportSession& s, const Json& extensions, const char* name, const std::string& pointer) {
  auto it = extensions.find(name);
  if (it == extensions.end()) return nullptr;
  if (!it->is_object()) {
    s.diagnostics.error(s.file, pointer + "/extensions/" + name, "expected an object");
    return nullptr;
  }
  return &*it;
}

std::string wrap_of(ImportSession& s, int texture) {
  const int sampler = s.model.textures[static_cast<size_t>(texture)].sampler;
  if (sampler < 0 || static_cast<size_t>(sampler) >= s.model.samplers.size()) return "repeat";
  const auto& sm = s.model.samplers[static_cast<size_t>(sampler)];
  const int wrap = sm.wrap_s;
  if (sm.wrap_t != sm.wrap_s) s.wrap_notes.insert(texture);
  return wrap == kClampToEdge ? "clamp" : wrap == kMirroredRepeat ? "mirror" : "repeat";
}

// glTF 2.0 sec. 3.9.2: metalness is the texture's blue channel, roughness its green one, both
// multiplying the factors. lamina cannot route one channel to a parameter, so the means are used.
void average_metallic_roughness(ImportSession& s, int texture, const std::string& pointer, const std::string& name,
                                PbrMaterial& pbr) {
  // Decoded in memory, not extracted: no node refers to it.
  const std::string* image = s.image_of(texture, pointer + "/index");
  if (!image) return;
  double green = 0.0, blue = 0.0;
  try {
    auto decoded = decode_linear_image(*image, false, s.policy.max_image_pixels);
    for (const auto& t : decoded->texels) {
      green += t.g;
      blue += t.b;
    }
    const double count = static_cast<double>(decoded->texels.size());
    green /= count;
    blue /= count;
  } catch (const ImageError& e) {
    s.diagnostics.warning(s.file, pointer, std::string("cannot read the texture: ") + e.what(),
                          "the metallic and roughness factors are used alone");
    return;
  }
  pbr.metallic *= blue;
  pbr.roughness *= green;
  s.result.notes.push_back(name + ": metallicRoughnessTexture is replaced by its means (metallic x " +
                           number_text(blue) + ", roughness x " + number_text(green) + ")");
}

}  // namespace

void import_pbr(ImportSession& s, size_t index) {
  const GltfMaterial& gm = s.model.materials[index];
  const std::string pointer = "/materials/" + std::to_string(index);
  const std::string name = s.unique_material_name(gm.name, index);
  std::vector<std::string>& notes = s.result.notes;
  const size_t errors_before = s.diagnostics.errors().size();

  PbrMaterial pbr;
  for (size_t c = 0; c < 3; ++c) pbr.base_color[c] = gm.base_color_factor[c];
  pbr.metallic = gm.metallic_factor;
  pbr.roughness = gm.roughness_factor;

  if (gm.base_color_texture.index >= 0) {
    const std::string tp = pointer + "/pbrMetallicRoughness/baseColorTexture";
    std::string file = s.texture_file(gm.base_color_texture.index, tp + "/index", "");
    if (!file.empty()) pbr.base_color_texture = PbrMaterial::Texture{file, wrap_of(s, gm.base_color_texture.index)};
    if (gm.base_color_texture.tex_coord != 0)
      notes.push_back(name + ": baseColorTexture uses TEXCOORD_" + std::to_string(gm.base_color_texture.tex_coord) +
                      "; lamina has one uv set");
    if (pbr.base_color != std::array<double, 3>{1.0, 1.0, 1.0})
      notes.push_back(name + ": baseColorFactor does not multiply the texture (lamina has no colour product node)");
  }
  if (gm.metallic_roughness_texture.index >= 0)
    average_metallic_roughness(s, gm.metallic_roughness_texture.index,
                               pointer + "/pbrMetallicRoughness/metallicRoughnessTexture", name, pbr);

  if (const auto* ior = khr_extension(s, gm.extensions, kIor, pointer)) {
    const std::string ep = pointer + "/extensions/" + kIor;
    pbr.ior = number(s, *ior, "ior", 1.5, ep);
    // KHR_materials_ior allows ior = 0 (no refraction) and values below 1; lamina needs >= 1.
    if (pbr.ior < 1.0) {
      notes.push_back(name + ": ior " + number_text(pbr.ior) + " is below 1; using 1.5");
      pbr.ior = 1.5;
    }
  }
  if (const auto* spec = khr_extension(s, gm.extensions, kSpecular, pointer)) {
    const std::string ep = pointer + "/extensions/" + kSpecular;
    pbr.specular = number(s, *spec, "specularFactor", 1.0, ep);
    if (spec->contains("specularColorFactor")) {
      const Json& color = spec->at("specularColorFactor");
      if (!color.is_array() || color.size() != 3)
        s.diagnostics.error(s.file, ep + "/specularColorFactor", "expected an array of 3 numbers");
      else
        for (int c = 0; c < 3; ++c)
          pbr.specular_color[static_cast<size_t>(c)] =
              number(s, color.at(static_cast<size_t>(c)), ep + "/specularColorFactor/" + std::to_string(c), 1.0);
    }
    if (pbr.specular_color[0] != pbr.specular_color[1] || pbr.specular_color[1] != pbr.specular_color[2])
      notes.push_back(name + ": the specular colour's tint is averaged into one ior (lamina interfaces are untinted)");
    if (spec->contains("specularTexture") || spec->contains("specularColorTexture"))
      notes.push_back(name + ": specular textures are not imported; the factors are used");
  }
  if (const auto* coat = khr_extension(s, gm.extensions, kClearcoat, pointer)) {
    const std::string ep = pointer + "/extensions/" + kClearcoat;
    pbr.clearcoat = number(s, *coat, "clearcoatFactor", 0.0, ep);
    pbr.clearcoat_roughness = number(s, *coat, "clearcoatRoughnessFactor", 0.0, ep);
    for (const char* t : {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"})
      if (coat->contains(t)) notes.push_back(name + ": " + t + " is not imported; the factors are used");
  }
  if (const auto* film = khr_extension(s, gm.extensions, kIridescence, pointer)) {
    const std::string ep = pointer + "/extensions/" + kIridescence;
    pbr.iridescence = number(s, *film, "iridescenceFactor", 0.0, ep);
    pbr.iridescence_ior = number(s, *film, "iridescenceIor", 1.3, ep);
    const double thinnest = number(s, *film, "iridescenceThicknessMinimum", 100.0, ep);
    pbr.iridescence_thickness = number(s, *film, "iridescenceThicknessMaximum", 400.0, ep);
    if (film->contains("iridescenceThicknessTexture")) {
      // thickness = mix(minimum, maximum, texture.g): without the texture's green channel (a
      // texture/image node reads colour or its mean), the middle of the range.
      pbr.iridescence_thickness = 0.5 * (thinnest + pbr.iridescence_thickness);
      notes.push_back(name + ": iridescenceThicknessTexture is not imported; the film is " +
                      number_text(pbr.iridescence_thickness) + " nm thick, the middle of its range");
    }
    if (film->contains("iridescenceTexture"))
      notes.push_back(name + ": iridescenceTexture is not imported; iridescenceFactor is used");
  }
  if (gm.normal_texture.index >= 0) notes.push_back(name + ": normalTexture is not imported");
  if (gm.occlusion_texture.index >= 0) notes.push_back(name + ": occlusionTexture is not imported");
  if (gm.emissive_texture.index >= 0 ||
      std::any_of(gm.emissive_factor.begin(), gm.emissive_factor.end(), [](double e) { return e != 0.0; }))
    notes.push_back(name + ": emission is not imported (lamina materials do not emit)");
  if (gm.alpha_mode != "OPAQUE") notes.push_back(name + ": alphaMode " + gm.alpha_mode + " is not imported (opaque)");

  if (s.diagnostics.errors().size() != errors_before) return;
  s.add(layered_from_pbr(name, pbr, notes), Origin{index, false});
}

}  // namespace lamina::gltf
