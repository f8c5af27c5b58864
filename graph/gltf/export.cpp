#include "graph/gltf/export.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "graph/compile.h"
#include "graph/cpu/image.h"
#include "graph/gltf/constants.h"
#include "graph/gltf/gltf_buffer.h"
#include "graph/gltf/label_image.h"
#include "graph/gltf/png_encode.h"
#include "graph/gltf/uri.h"
#include "graph/json_read.h"
#include "graph/json_write.h"
#include "graph/parallel.h"

namespace lamina::gltf {

namespace {

constexpr const char* kUnlit = "KHR_materials_unlit";

// The shortest decimal that reads back to the same float, as a double: 0.8f is written 0.8, not
// 0.800000011920929.
double tidy(float value) {
  char text[32];
  auto end = std::to_chars(text, text + sizeof text, value).ptr;
  double out = 0.0;
  std::from_chars(text, end, out);
  return out;
}

Json tidy_array(std::initializer_list<float> values) {
  Json a = Json::array();
  for (float v : values) a.push_back(tidy(v));
  return a;
}

Json quaternion_json(const glm::dquat& q) { return Json::array({q.x, q.y, q.z, q.w}); }

// The rotation that turns a node's -Z axis (where glTF cameras look and lights shine) towards
// `forward`, keeping its +Y axis as close to `up` as possible.
glm::dquat rotation_towards(glm::dvec3 forward, glm::dvec3 up) {
  const glm::dvec3 z = -glm::normalize(forward);
  if (glm::length(glm::cross(up, z)) < 1e-9) up = std::abs(z.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 x = glm::normalize(glm::cross(up, z));
  const glm::dvec3 y = glm::cross(z, x);
  return glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
}

bool is_identity(const glm::dquat& q) { return q.w == 1.0 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0; }

// Labels (scene objects' "label"): text height and the gap above it as fractions of the object's
// width seen from the camera, and the widest a label may be, so that neighbours in a grid keep
// apart.
constexpr double kLabelHeight = 0.14;
constexpr double kLabelGap = 0.02;
constexpr double kLabelMaxWidth = 1.2;

struct Bounds {
  glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{std::numeric_limits<double>::lowest()};
  void add(glm::dvec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
};

glm::dmat4 object_matrix(const Transform& t) {
  return glm::translate(glm::dmat4(1.0), t.translation) * glm::mat4_cast(t.rotation) *
         glm::scale(glm::dmat4(1.0), t.scale);
}

// The glTF mimeType of images glTF holds as they are (PNG and JPEG), "" for the others.
std::string mime_of(std::string_view bytes) {
  ImageFormat format;
  if (!image_format_of(bytes, format)) return "";
  return format == ImageFormat::Png ? "image/png" : format == ImageFormat::Jpeg ? "image/jpeg" : "";
}

// Images glTF cannot hold (EXR, TIFF, HDR, ...) become 8-bit RGBA PNGs; values are clamped to
// [0, 1] and rounded, with no change of transfer curve.
std::vector<unsigned char> png_from_any_image(const std::string& bytes, std::uint64_t max_pixels) {
  const auto image = decode_linear_image(bytes, false, max_pixels);
  std::vector<uint8_t> pixels(image->texels.size() * 4);
  for (size_t i = 0; i < image->texels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      pixels[4 * i + static_cast<size_t>(c)] =
          static_cast<uint8_t>(std::lround(std::clamp(image->texels[i][c], 0.0f, 1.0f) * 255.0f));
  return encode_png(image->width, image->height, 4, pixels);
}

class Writer {
 public:
  Writer(const Scene& scene, const ExportOptions& options) : scene_(scene), options_(options), buffer_(arrays_) {
    // By name once: a sample sheet of thousands of materials looks each up per object.
    for (const auto& file : scene_.material_files)
      for (const auto& m : file.document.materials) defined_.emplace(m.name, std::make_pair(&m, &file));
  }

  Export run(const std::filesystem::path& output) {
    Export result;
    const bool binary = output.extension() == ".glb";
    Json scene_nodes = Json::array();
    for (const auto& camera : scene_.cameras) {
      if (camera.aperture_radius > 0.0)
        result.notes.push_back("camera '" + camera.name +
                               "' is written as a pinhole: glTF 2.0 cameras have no aperture or focus distance");
      scene_nodes.push_back(add_camera(camera));
    }
    for (const auto& light : scene_.lights) {
      if (light.type == LightType::Environment) {
        result.notes.push_back("environment light '" + light.name +
                               "' has no glTF 2.0 counterpart (KHR_lights_punctual has point, spot and "
                               "directional lights only); it is not written");
        continue;
      }
      if (light.angular_radius_deg > 0.0)
        result.notes.push_back("directional light '" + light.name +
                               "' is written as a point at infinity: KHR_lights_punctual has no angular radius");
      scene_nodes.push_back(add_light(light));
    }
    for (const auto& object : scene_.objects)
      if (object.emission != glm::dvec3(0.0))
        result.notes.push_back("object '" + object.name +
                               "' emits light, which is not written: a glTF material's emission belongs to the "
                               "material, shared by every object that uses it");
    fit_fallbacks();
    for (const auto& object : scene_.objects) scene_nodes.push_back(add_object(object));
    for (const auto& object : scene_.objects)
      if (!object.label.empty()) scene_nodes.push_back(add_label(object));

    Json root;
    root["asset"] = Json{{"version", "2.0"}, {"generator", std::string("lamina ") + LAMINA_VERSION}};
    std::vector<std::string> used(extensions_used_.begin(), extensions_used_.end());
    if (!used.empty()) root["extensionsUsed"] = used;  // sorted by the set; never extensionsRequired
    if (!lights_.empty()) root["extensions"] = Json{{"KHR_lights_punctual", Json{{"lights", lights_}}}};
    root["scene"] = 0;
    root["scenes"] =
        Json::array({Json{{"name", std::filesystem::path(scene_.path).stem().string()}, {"nodes", scene_nodes}}});
    for (const char* key :
         {"nodes", "cameras", "meshes", "materials", "textures", "images", "samplers", "accessors", "bufferViews"})
      if (auto it = arrays_.find(key); it != arrays_.end() && !it->empty()) root[key] = *it;
    const auto& bin = buffer_.bytes();
    const std::filesystem::path bin_name = output.stem().string() + ".bin";
    if (!bin.empty()) {
      Json buffer{{"byteLength", bin.size()}};
      if (!binary) buffer["uri"] = uri_encode(bin_name.string());
      root["buffers"] = Json::array({buffer});
    }

    std::string json = root.dump(binary ? -1 : 2);
    if (binary) {
      result.files.push_back({output, pack_glb(json, bin)});
    } else {
      json += "\n";
      result.files.push_back({output, std::vector<unsigned char>(json.begin(), json.end())});
      if (!bin.empty()) result.files.push_back({output.parent_path() / bin_name, bin});
    }
    result.materials = std::move(reports_);
    return result;
  }

 private:
  int push(const char* array, Json value) {
    Json& a = arrays_[array];
    if (a.is_null()) a = Json::array();
    a.push_back(std::move(value));
    return static_cast<int>(a.size()) - 1;
  }

  int add_camera(const Camera& camera) {
    Json perspective{{"yfov", camera.yfov_deg * std::numbers::pi / 180.0}, {"znear", camera.znear}};
    perspective["aspectRatio"] = camera.aspect;
    if (camera.zfar) perspective["zfar"] = *camera.zfar;
    int index = push("cameras", Json{{"name", camera.name}, {"type", "perspective"}, {"perspective", perspective}});
    Json node{{"name", camera.name}, {"camera", index}};
    node["rotation"] = quaternion_json(rotation_towards(camera.look_at - camera.position, camera.up));
    node["translation"] = Json::array({camera.position.x, camera.position.y, camera.position.z});
    return push("nodes", std::move(node));
  }

  // KHR_lights_punctual: point and spot intensity in candela, directional in lux; lights shine
  // along the node's -Z.
  int add_light(const Light& light) {
    extensions_used_.insert("KHR_lights_punctual");
    Json l{{"name", light.name}};
    l["color"] = Json::array({light.color.r, light.color.g, light.color.b});
    l["intensity"] = light.intensity;
    Json node{{"name", light.name}};
    switch (light.type) {
      case LightType::Point: l["type"] = "point"; break;
      case LightType::Directional: l["type"] = "directional"; break;
      case LightType::Spot:
        l["type"] = "spot";
        l["spot"] = Json{{"innerConeAngle", light.inner_cone_deg * std::numbers::pi / 180.0},
                         {"outerConeAngle", light.outer_cone_deg * std::numbers::pi / 180.0}};
        break;
      case LightType::Environment: break;  // filtered by the caller
    }
    if (light.range && light.type != LightType::Directional) l["range"] = *light.range;
    lights_.push_back(std::move(l));
    node["extensions"] = Json{{"KHR_lights_punctual", Json{{"light", lights_.size() - 1}}}};
    if (light.type != LightType::Point) {
      glm::dquat q = rotation_towards(light.direction, glm::dvec3(0, 1, 0));
      if (!is_identity(q)) node["rotation"] = quaternion_json(q);
    }
    if (light.type != LightType::Directional && light.position != glm::dvec3(0.0))
      node["translation"] = Json::array({light.position.x, light.position.y, light.position.z});
    return push("nodes", std::move(node));
  }

  int add_object(const SceneObject& object) {
    Json primitive{{"attributes", geometry(object)}, {"mode", 4}};
    primitive["indices"] = indices_[geometry_key(object)];
    primitive["material"] = material(object.material);
    int mesh = push("meshes", Json{{"name", object.name}, {"primitives", Json::array({primitive})}});
    Json node{{"name", object.name}, {"mesh", mesh}};
    const Transform& t = object.transform;
    if (!is_identity(t.rotation)) node["rotation"] = quaternion_json(t.rotation);
    if (t.scale != glm::dvec3(1.0)) node["scale"] = Json::array({t.scale.x, t.scale.y, t.scale.z});
    if (t.translation != glm::dvec3(0.0))
      node["translation"] = Json::array({t.translation.x, t.translation.y, t.translation.z});
    return push("nodes", std::move(node));
  }

  // The object's label: a quad under it, turned about y to face the first camera (all labels
  // parallel), showing the text with KHR_materials_unlit so that no light changes it. Its material
  // says in its extras that it is a label, so that lamina import leaves it out.
  int add_label(const SceneObject& object) {
    double facing = 0.0;  // angle about y from +z
    if (!scene_.cameras.empty()) {
      const glm::dvec3 forward = scene_.cameras.front().look_at - scene_.cameras.front().position;
      if (std::hypot(forward.x, forward.z) > 1e-9) facing = std::atan2(-forward.x, -forward.z);
    }
    // The label's axes in the scene: across (`right`), up, and towards the camera (`front`).
    const glm::dvec3 right(std::cos(facing), 0.0, -std::sin(facing)), front(std::sin(facing), 0.0, std::cos(facing));
    // The object's extent along these axes, from its vertices in the scene (a bounding box seen
    // from a corner would be wider than the object).
    const glm::dmat4 to_world = object_matrix(object.transform);
    Bounds seen;  // x across, y up, z towards the camera
    for (const glm::vec3& p : label_positions(object)) {
      const glm::dvec3 q(to_world * glm::dvec4(glm::dvec3(p), 1.0));
      seen.add(glm::dvec3(glm::dot(q, right), q.y, glm::dot(q, front)));
    }
    const double width_seen = std::max(seen.hi.x - seen.lo.x, 1e-6);

    const LabelImage image = render_label(object.label);
    double height = kLabelHeight * width_seen;
    double width = height * image.content_width / image.content_height;
    if (width > kLabelMaxWidth * width_seen) {
      height *= kLabelMaxWidth * width_seen / width;
      width = kLabelMaxWidth * width_seen;
    }

    const int source = image_from_pixels(image.width, image.height, 4, image.rgba, object.name + " label");
    const int texture = push("textures", Json{{"sampler", sampler(kClampToEdge)}, {"source", source}});
    Json material{{"name", object.name + " label"}};
    material["pbrMetallicRoughness"] =
        Json{{"baseColorTexture", Json{{"index", texture}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}};
    material["alphaMode"] = "BLEND";  // smooth glyph edges; labels do not overlap each other
    material["extensions"] = Json{{kUnlit, Json::object()}};
    material["extras"] = Json{{kLabelExtra, object.label}};
    extensions_used_.insert(kUnlit);
    const int material_index = push("materials", std::move(material));

    // The quad shows the image's content: the top-left part of the power-of-two texture.
    Json attributes = label_quad();
    const float u = static_cast<float>(image.content_width) / static_cast<float>(image.width);
    const float v = static_cast<float>(image.content_height) / static_cast<float>(image.height);
    const std::vector<glm::vec2> uvs{{0.0f, 0.0f}, {u, 0.0f}, {u, v}, {0.0f, v}};
    attributes["TEXCOORD_0"] = buffer_.add_vec2(uvs);
    Json primitive{{"attributes", attributes}, {"indices", label_quad_indices_}, {"material", material_index}};
    primitive["mode"] = 4;
    const int mesh = push("meshes", Json{{"name", object.name + " label"}, {"primitives", Json::array({primitive})}});
    Json node{{"name", object.name + " label"}, {"mesh", mesh}};
    if (facing != 0.0) node["rotation"] = quaternion_json(glm::angleAxis(facing, glm::dvec3(0.0, 1.0, 0.0)));
    node["scale"] = Json::array({width, height, 1.0});
    // Centred under the object as the camera sees it, its top a little below the object's lowest point.
    const glm::dvec3 at = right * (0.5 * (seen.lo.x + seen.hi.x)) + front * (0.5 * (seen.lo.z + seen.hi.z));
    node["translation"] = Json::array({at.x, seen.lo.y - kLabelGap * width_seen, at.z});
    return push("nodes", std::move(node));
  }

  // The vertices of a labelled object's shape (kept by geometry(), or read again when an object
  // without a label wrote the shape).
  const std::vector<glm::vec3>& label_positions(const SceneObject& object) {
    const std::string key = geometry_key(object);
    auto it = positions_.find(key);
    if (it == positions_.end()) it = positions_.emplace(key, object_mesh(object, scene_.policy).positions).first;
    return it->second;
  }

  // A unit quad facing +z, its top edge centred on the origin ([-0.5, 0.5] x [-1, 0]); positions,
  // normals and indices are written once and shared by every label, the uvs are each label's.
  Json label_quad() {
    if (!label_quad_.is_null()) return label_quad_;
    const std::vector<glm::vec3> positions{
        {-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.5f, -1.0f, 0.0f}, {-0.5f, -1.0f, 0.0f}};
    const std::vector<glm::vec3> normals(4, glm::vec3(0.0f, 0.0f, 1.0f));
    const std::vector<uint32_t> indices{0, 3, 2, 0, 2, 1};  // counter-clockwise seen from +z
    label_quad_["POSITION"] = buffer_.add_vec3(positions, true);
    label_quad_["NORMAL"] = buffer_.add_vec3(normals, false);
    label_quad_indices_ = buffer_.add_indices(indices, 4);
    return label_quad_;
  }

  // Vertex data is written once per distinct shape and shared by every primitive that uses it.
  Json geometry(const SceneObject& object) {
    const std::string key = geometry_key(object);
    if (auto it = attributes_.find(key); it != attributes_.end()) return it->second;
    TriangleMesh mesh = object_mesh(object, scene_.policy);
    Json attributes;
    attributes["POSITION"] = buffer_.add_vec3(mesh.positions, true);
    attributes["NORMAL"] = buffer_.add_vec3(mesh.normals, false);
    attributes["TANGENT"] = buffer_.add_vec4(mesh.tangents);
    attributes["TEXCOORD_0"] = buffer_.add_vec2(mesh.uvs);
    indices_[key] = buffer_.add_indices(mesh.indices, static_cast<uint32_t>(mesh.positions.size()));
    attributes_[key] = attributes;
    if (!object.label.empty()) positions_[key] = std::move(mesh.positions);
    return attributes;
  }

  int material(const std::string& name) {
    if (auto it = materials_.find(name); it != materials_.end()) return it->second;
    const auto [m, file] = defined(name);

    const size_t shared = fallback_of_.at(name);
    Fallback fallback = fallbacks_.at(shared);
    // Materials sharing a fit share its baked textures too.
    auto baked = [&](const BakedImage& image, int which) {
      auto [at, added] = shared_textures_.emplace(std::make_pair(shared, which), -1);
      if (added) at->second = baked_texture(image);
      return at->second;
    };
    Json gltf_material{{"name", name}};
    Json pbr;
    const PbrParams& p = fallback.params;
    pbr["baseColorFactor"] = tidy_array({p.base_color.r, p.base_color.g, p.base_color.b, 1.0f});
    if (fallback.base_color) pbr["baseColorTexture"] = Json{{"index", baked(*fallback.base_color, 0)}};
    pbr["metallicFactor"] = tidy(p.metallic);
    pbr["roughnessFactor"] = tidy(p.roughness);
    if (fallback.metallic_roughness)
      pbr["metallicRoughnessTexture"] = Json{{"index", baked(*fallback.metallic_roughness, 1)}};
    gltf_material["pbrMetallicRoughness"] = pbr;
    if (fallback.normal) gltf_material["normalTexture"] = Json{{"index", baked(*fallback.normal, 3)}};

    Json extensions = Json::object();
    if (fallback.uses_clearcoat) {
      Json c{{"clearcoatFactor", tidy(p.clearcoat)}, {"clearcoatRoughnessFactor", tidy(p.clearcoat_roughness)}};
      if (fallback.clearcoat) {
        int texture = baked(*fallback.clearcoat, 2);
        c["clearcoatTexture"] = Json{{"index", texture}};           // R
        c["clearcoatRoughnessTexture"] = Json{{"index", texture}};  // G
      }
      if (fallback.clearcoat_normal)
        c["clearcoatNormalTexture"] = Json{{"index", baked(*fallback.clearcoat_normal, 4)}};
      extensions["KHR_materials_clearcoat"] = c;
    }
    if (fallback.uses_ior) extensions["KHR_materials_ior"] = Json{{"ior", tidy(p.ior)}};
    if (fallback.uses_specular)
      extensions["KHR_materials_specular"] =
          Json{{"specularFactor", tidy(p.specular)},
               {"specularColorFactor", tidy_array({p.specular_color.r, p.specular_color.g, p.specular_color.b})}};
    if (fallback.uses_iridescence) {
      // KHR_materials_iridescence: without a thickness texture the film is iridescenceThicknessMaximum.
      Json i{{"iridescenceFactor", tidy(p.iridescence)},
             {"iridescenceIor", tidy(p.iridescence_ior)},
             {"iridescenceThicknessMinimum", tidy(fallback.iridescence_thickness_min)},
             {"iridescenceThicknessMaximum", tidy(p.iridescence_thickness)}};
      if (fallback.iridescence_thickness)
        i["iridescenceThicknessTexture"] = Json{{"index", baked(*fallback.iridescence_thickness, 5)}};
      extensions["KHR_materials_iridescence"] = i;
    }
    extensions[kExtensionName] = layered_extension(*m, *file);
    for (const auto& [key, value] : extensions.items()) extensions_used_.insert(key);
    gltf_material["extensions"] = extensions;

    int index = push("materials", std::move(gltf_material));
    materials_[name] = index;
    reports_.push_back({name, std::move(fallback)});
    return index;
  }

  std::pair<const Material*, const MaterialFileRef*> defined(const std::string& name) const {
    const auto it = defined_.find(name);
    if (it == defined_.end()) throw std::logic_error("export_scene: the scene was not checked (material " + name + ")");
    return it->second;
  }

  // The fallback of every material an object uses, before anything is written: materials that
  // differ only in their names (and read textures from the same folder) share one fit, and the fits
  // run on every core. Each fit is deterministic, so the output does not depend on the threads.
  void fit_fallbacks() {
    std::vector<Program> programs;
    std::map<std::string, size_t> by_content;
    for (const auto& object : scene_.objects) {
      if (fallback_of_.count(object.material)) continue;
      const auto [m, file] = defined(object.material);
      Document unnamed;
      unnamed.materials.push_back(*m);
      unnamed.materials.back().name = "m";
      const std::string key = file->resolved.parent_path().string() + "\n" + write_document(unnamed);
      auto [at, added] = by_content.emplace(key, programs.size());
      if (added) programs.push_back(compile(file->document, object.material));
      fallback_of_[object.material] = at->second;
    }
    fallbacks_.resize(programs.size());
    parallel_for(programs.size(), [&](size_t i) { fallbacks_[i] = fit_fallback(programs[i], options_.fallback); });
  }

  // The canonical material as lamina writes it, and a glTF texture per texture/image node.
  Json layered_extension(const Material& m, const MaterialFileRef& file) {
    Document single;
    single.materials.push_back(m);
    Json canonical = Json::parse(write_document(single))["materials"][0];
    Json textures = Json::object();
    for (const Node& node : m.nodes) {
      if (node.type != "texture/image") continue;
      const Value* f = node.find("file");
      if (!f || !std::holds_alternative<std::string>(*f)) continue;
      const Reference reference =
          resolve_reference(file.resolved, std::get<std::string>(*f), ReferenceScope::AssetRoots, file.document.policy);
      int wrap = kRepeat;
      if (const Value* w = node.find("wrap"); w && std::holds_alternative<std::string>(*w)) {
        const auto& mode = std::get<std::string>(*w);
        wrap = mode == "clamp" ? kClampToEdge : mode == "mirror" ? kMirroredRepeat : kRepeat;
      }
      textures[node.id] = Json{{"index", file_texture(reference, file.document.policy, wrap)}};
    }
    return Json{{"format", kFormatVersion}, {"material", canonical}, {"textures", textures}};
  }

  int sampler(int wrap) {
    if (auto it = samplers_.find(wrap); it != samplers_.end()) return it->second;
    int index = push(
        "samplers", Json{{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", wrap}, {"wrapT", wrap}});
    samplers_[wrap] = index;
    return index;
  }

  int image(const std::vector<unsigned char>& bytes, const std::string& mime, const std::string& name) {
    Json img{{"name", name}, {"mimeType", mime}};
    img["bufferView"] = buffer_.add_image_bytes(bytes);
    return push("images", std::move(img));
  }

  int image_from_pixels(int width, int height, int channels, const std::vector<uint8_t>& pixels,
                        const std::string& name) {
    return image(encode_png(width, height, channels, pixels), "image/png", name);
  }

  // The file's bytes as they are when glTF can hold them (PNG, JPEG), else re-encoded as PNG; the
  // file was decoded when the material was checked, and is decoded again here either way.
  int file_texture(const Reference& reference, const AssetPolicy& policy, int wrap) {
    const std::string key = reference.resolved.string() + "|" + std::to_string(wrap);
    if (auto it = file_textures_.find(key); it != file_textures_.end()) return it->second;
    const std::string name = reference.path.filename().string();
    const std::string text = read_reference(reference, kMaxBinaryFileBytes, policy);
    std::vector<unsigned char> bytes(text.begin(), text.end());
    std::string mime = mime_of(text);
    if (mime.empty()) {
      bytes = png_from_any_image(text, policy.max_image_pixels);
      mime = "image/png";
    } else {
      decode_linear_image(text, false, policy.max_image_pixels);
    }
    int source = image(bytes, mime, name);
    int texture = push("textures", Json{{"sampler", sampler(wrap)}, {"source", source}});
    file_textures_[key] = texture;
    return texture;
  }

  int baked_texture(const BakedImage& baked) {
    int source = image_from_pixels(baked.size, baked.size, baked.channels, baked.pixels,
                                   "lamina_fallback_" + std::to_string(++baked_count_));
    return push("textures", Json{{"sampler", sampler(kRepeat)}, {"source", source}});
  }

  const Scene& scene_;
  const ExportOptions& options_;
  Json arrays_ = Json::object();
  BufferBuilder buffer_;
  Json lights_ = Json::array();
  std::set<std::string> extensions_used_;
  std::map<std::string, Json> attributes_;
  std::map<std::string, std::vector<glm::vec3>> positions_;  // of labelled objects' shapes, in their own space
  Json label_quad_;
  int label_quad_indices_ = -1;
  std::map<std::string, int> indices_, materials_, file_textures_;
  std::map<int, int> samplers_;
  std::vector<MaterialReport> reports_;
  std::vector<Fallback> fallbacks_;            // fitted by fit_fallbacks()
  std::map<std::string, size_t> fallback_of_;  // material name -> index into fallbacks_
  std::map<std::string, std::pair<const Material*, const MaterialFileRef*>> defined_;  // by name
  std::map<std::pair<size_t, int>, int> shared_textures_;  // (fallback, which image) -> glTF texture
  int baked_count_ = 0;
};

}  // namespace

Export export_scene(const Scene& scene, const std::filesystem::path& output, const ExportOptions& options) {
  return Writer(scene, options).run(output);
}

}  // namespace lamina::gltf
