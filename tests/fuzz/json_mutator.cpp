#include "json_mutator.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "graph/gltf/constants.h"
#include "graph/json_values.h"
#include "graph/limits.h"
#include "graph/registry.h"
#include "graph/scene/scene_fields.h"

namespace lamina::fuzz {

namespace {

// Values at the edges of what readers accept: zero and its sign, denormals, float and integer
// limits, the lengths of lamina's own limits.
void add_boundary_numbers(std::vector<double>& numbers) {
  for (double x : {0.0,          -0.0,
                   1.0,          -1.0,
                   0.5,          2.0,
                   1e-320,       1e-38,
                   1e-7,         1e7,
                   1e38,         3.5e38,
                   1e300,        255.0,
                   256.0,        65535.0,
                   65536.0,      2147483647.0,
                   4294967295.0, 4294967296.0,
                   1e12,         9007199254740993.0})
    numbers.push_back(x);
  for (double limit : {static_cast<double>(kMaxStackNodes), static_cast<double>(kMaxLobes),
                       static_cast<double>(kMaxSlots), static_cast<double>(kMaxIdentifierLength)})
    for (double d : {-1.0, 0.0, 1.0}) numbers.push_back(limit + d);
}

void sort_unique(std::vector<std::string>& words) {
  std::sort(words.begin(), words.end());
  words.erase(std::unique(words.begin(), words.end()), words.end());
}

void finish(Vocabulary& v) {
  sort_unique(v.keys);
  sort_unique(v.strings);
  std::sort(v.numbers.begin(), v.numbers.end());
  v.numbers.erase(std::unique(v.numbers.begin(), v.numbers.end(),
                              [](double a, double b) { return a == b && std::signbit(a) == std::signbit(b); }),
                  v.numbers.end());
}

using Json = nlohmann::ordered_json;

struct Place {
  Json* value;
  Json* parent;  // nullptr for the root
};

void collect(Json& j, Json* parent, std::vector<Place>& places) {
  places.push_back({&j, parent});
  if (j.is_object() || j.is_array())
    for (Json& child : j) collect(child, &j, places);
}

template <typename T>
const T& pick(const std::vector<T>& items, std::mt19937& rng) {
  return items[std::uniform_int_distribution<size_t>(0, items.size() - 1)(rng)];
}

bool chance(std::mt19937& rng, int one_in) { return std::uniform_int_distribution<int>(0, one_in - 1)(rng) == 0; }

// The ids and names the document defines: links and material references point at them.
std::vector<std::string> defined_names(const std::vector<Place>& places) {
  std::vector<std::string> names;
  for (const Place& p : places) {
    if (!p.value->is_object()) continue;
    for (const char* key : {"id", "name"}) {
      auto it = p.value->find(key);
      if (it != p.value->end() && it->is_string()) names.push_back(it->get<std::string>());
    }
  }
  return names;
}

Json some_value(const Vocabulary& v, const std::vector<std::string>& names, std::mt19937& rng) {
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0: return v.numbers.empty() ? Json(0.5) : Json(pick(v.numbers, rng));
    case 1: return v.strings.empty() ? Json("") : Json(pick(v.strings, rng));
    case 2: return names.empty() ? Json("@") : Json("@" + pick(names, rng));
    case 3: return Json(chance(rng, 2));
    case 4: {
      const double x = v.numbers.empty() ? 0.5 : pick(v.numbers, rng);
      return Json::array({x, x, x});
    }
    default: return Json::array({0.25, 0.5});
  }
}

double perturbed(double x, std::mt19937& rng) {
  switch (std::uniform_int_distribution<int>(0, 4)(rng)) {
    case 0: return -x;
    case 1: return x * 2.0;
    case 2: return x / 2.0;
    case 3: return std::nextafter(x, chance(rng, 2) ? 1e308 : -1e308);
    default: return x + 1.0;
  }
}

// One edit somewhere in the tree.
void edit(Json& root, const Vocabulary& v, std::mt19937& rng) {
  std::vector<Place> places;
  collect(root, nullptr, places);
  const std::vector<std::string> names = defined_names(places);
  auto places_where = [&](auto&& predicate) {
    std::vector<Place> chosen;
    for (const Place& p : places)
      if (predicate(p)) chosen.push_back(p);
    return chosen;
  };
  switch (std::uniform_int_distribution<int>(0, 8)(rng)) {
    case 0: {  // a number becomes a boundary value or moves a little
      auto numbers = places_where([](const Place& p) { return p.value->is_number(); });
      if (numbers.empty()) return;
      Json& x = *pick(numbers, rng).value;
      x = (chance(rng, 2) && !v.numbers.empty()) ? pick(v.numbers, rng) : perturbed(x.get<double>(), rng);
      return;
    }
    case 1: {  // a string becomes a word of the format, a link, or another string of the file
      auto strings = places_where([](const Place& p) { return p.value->is_string(); });
      if (strings.empty()) return;
      Json& s = *pick(strings, rng).value;
      const int how = std::uniform_int_distribution<int>(0, 3)(rng);
      if (how == 0 && !v.strings.empty()) {
        s = pick(v.strings, rng);
      } else if (how == 1 && !names.empty()) {
        std::string link = "@" + pick(names, rng);
        if (chance(rng, 3) && !v.strings.empty()) link += "." + pick(v.strings, rng);
        s = link;
      } else if (how == 2) {
        s = pick(strings, rng).value->get<std::string>();
      } else {
        std::string text = s.get<std::string>();
        s = text.substr(0, text.size() / 2) + (chance(rng, 2) ? "../" : "");
      }
      return;
    }
    case 2: {  // a member or element goes
      auto children = places_where([](const Place& p) { return p.parent != nullptr; });
      if (children.empty()) return;
      const Place& p = pick(children, rng);
      if (p.parent->is_array()) {
        for (size_t i = 0; i < p.parent->size(); ++i)
          if (&(*p.parent)[i] == p.value) {
            p.parent->erase(i);
            return;
          }
      } else {
        for (auto it = p.parent->begin(); it != p.parent->end(); ++it)
          if (&*it == p.value) {
            p.parent->erase(it.key());
            return;
          }
      }
      return;
    }
    case 3: {  // an element is repeated (a node, a material, an object), renamed when it has an id
      auto arrays = places_where([](const Place& p) { return p.value->is_array() && !p.value->empty(); });
      if (arrays.empty()) return;
      Json& a = *pick(arrays, rng).value;
      Json copy = a[std::uniform_int_distribution<size_t>(0, a.size() - 1)(rng)];
      if (copy.is_object())
        for (const char* key : {"id", "name"})
          if (copy.contains(key) && copy[key].is_string())
            copy[key] = copy[key].get<std::string>() + "_" + std::to_string(a.size());
      a.push_back(std::move(copy));
      return;
    }
    case 4: {  // a member is added: a key of the format with a plausible value
      auto objects = places_where([](const Place& p) { return p.value->is_object(); });
      if (objects.empty() || v.keys.empty()) return;
      (*pick(objects, rng).value)[pick(v.keys, rng)] = some_value(v, names, rng);
      return;
    }
    case 5: {  // one part of the file is copied over another
      const Json copy = *pick(places, rng).value;
      auto children = places_where([](const Place& p) { return p.parent != nullptr; });
      if (children.empty()) return;
      *pick(children, rng).value = copy;
      return;
    }
    case 6: {  // a value changes its kind
      Json& x = *pick(places, rng).value;
      switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
        case 0: x = nullptr; break;
        case 1: x = true; break;
        case 2: x = Json::array(); break;
        case 3: x = Json::object(); break;
        case 4: x = ""; break;
        default: x = Json::array({x}); break;
      }
      return;
    }
    case 7: {  // two elements trade places
      auto arrays = places_where([](const Place& p) { return p.value->is_array() && p.value->size() > 1; });
      if (arrays.empty()) return;
      Json& a = *pick(arrays, rng).value;
      std::uniform_int_distribution<size_t> index(0, a.size() - 1);
      std::swap(a[index(rng)], a[index(rng)]);
      return;
    }
    default: {  // a value becomes something of the format
      auto children = places_where([](const Place& p) { return p.parent != nullptr; });
      if (children.empty()) return;
      *pick(children, rng).value = some_value(v, names, rng);
      return;
    }
  }
}

std::uint32_t read_u32(const std::string& s, size_t at) {
  std::uint32_t x = 0;
  std::memcpy(&x, s.data() + at, 4);
  return x;
}

void append_u32(std::string& s, std::uint32_t x) {
  char bytes[4];
  std::memcpy(bytes, &x, 4);
  s.append(bytes, 4);
}

bool mutate_text(std::string& text, const Vocabulary& v, std::mt19937& rng) {
  Diagnostics ignored;
  std::optional<Json> root = parse_json(text, "fuzz", ignored, "");
  if (!root) return false;
  const int edits = std::uniform_int_distribution<int>(1, 4)(rng);
  for (int i = 0; i < edits; ++i) edit(*root, v, rng);
  text = root->dump(-1, ' ', false, Json::error_handler_t::replace);
  return true;
}

}  // namespace

Vocabulary material_vocabulary() {
  Vocabulary v;
  v.keys = {"$schema", "format",  "materials", "name", "class", "source", "notes", "clamp_lower_roughness",
            "model",   "surface", "nodes",     "id",   "type"};
  for (const NodeDecl& decl : NodeRegistry::builtin().all()) {
    v.strings.push_back(decl.type);
    for (const ParamDecl& p : decl.params) {
      v.keys.push_back(p.name);
      for (const auto& choice : p.choices) v.strings.push_back(choice);
      for (double bound : {p.lo, p.hi})
        if (std::isfinite(bound)) v.numbers.push_back(bound);
    }
    for (const OutputDecl& o : decl.outputs) v.strings.push_back(o.name);
  }
  for (char c = 'a'; c <= 'h'; ++c) v.strings.push_back(std::string(1, c));
  v.strings.push_back("textures/patina_mask.png");
  for (const char* model : {"weidlich_wilkie", "energy_conserving"}) v.strings.push_back(model);
  add_boundary_numbers(v.numbers);
  finish(v);
  return v;
}

Vocabulary scene_vocabulary() {
  Vocabulary v;
  v.keys = {"$schema", "format", "materials", "cameras", "lights", "objects", "transform"};
  auto add_fields = [&](const std::vector<ParamDecl>& fields) {
    for (const ParamDecl& f : fields) {
      v.keys.push_back(f.name);
      for (double bound : {f.lo, f.hi})
        if (std::isfinite(bound)) v.numbers.push_back(bound);
    }
  };
  add_fields(camera_fields());
  add_fields(transform_fields());
  for (size_t t = 0; t < light_type_names().size(); ++t) add_fields(light_fields(static_cast<LightType>(t)));
  for (size_t s = 0; s < shape_names().size(); ++s) add_fields(object_fields(static_cast<ShapeType>(s)));
  for (const auto& name : light_type_names()) v.strings.push_back(name);
  for (const auto& name : shape_names()) v.strings.push_back(name);
  v.strings.insert(v.strings.end(), {"materials/brass.json", "materials/patina_map_copper.json", "quad.gltf",
                                     "points.gltf", "materials/textures/patina_mask.png"});
  add_boundary_numbers(v.numbers);
  finish(v);
  return v;
}

Vocabulary gltf_vocabulary() {
  Vocabulary v;
  // glTF 2.0's properties (sec. 5) that lamina's reader looks at, and the extensions it imports.
  v.keys = {"asset",
            "version",
            "minVersion",
            "generator",
            "extensionsUsed",
            "extensionsRequired",
            "extensions",
            "extras",
            "scene",
            "scenes",
            "nodes",
            "children",
            "mesh",
            "matrix",
            "translation",
            "rotation",
            "scale",
            "meshes",
            "primitives",
            "attributes",
            "POSITION",
            "NORMAL",
            "TANGENT",
            "TEXCOORD_0",
            "TEXCOORD_1",
            "indices",
            "material",
            "mode",
            "accessors",
            "bufferView",
            "byteOffset",
            "componentType",
            "normalized",
            "count",
            "type",
            "max",
            "min",
            "sparse",
            "bufferViews",
            "buffer",
            "byteLength",
            "byteStride",
            "target",
            "buffers",
            "uri",
            "images",
            "mimeType",
            "textures",
            "sampler",
            "source",
            "samplers",
            "magFilter",
            "minFilter",
            "wrapS",
            "wrapT",
            "materials",
            "name",
            "pbrMetallicRoughness",
            "baseColorFactor",
            "baseColorTexture",
            "metallicFactor",
            "roughnessFactor",
            "metallicRoughnessTexture",
            "normalTexture",
            "occlusionTexture",
            "emissiveTexture",
            "emissiveFactor",
            "alphaMode",
            "alphaCutoff",
            "doubleSided",
            "index",
            "texCoord",
            "strength",
            "ior",
            "specularFactor",
            "specularTexture",
            "specularColorFactor",
            "specularColorTexture",
            "clearcoatFactor",
            "clearcoatTexture",
            "clearcoatRoughnessFactor",
            "clearcoatRoughnessTexture",
            "clearcoatNormalTexture",
            "KHR_materials_ior",
            "KHR_materials_specular",
            "KHR_materials_clearcoat",
            "KHR_texture_transform",
            "LAMINA_materials_layered",
            "graph",
            "material_name"};
  v.strings = {"2.0",
               "SCALAR",
               "VEC2",
               "VEC3",
               "VEC4",
               "MAT4",
               "OPAQUE",
               "BLEND",
               "MASK",
               "image/png",
               "image/jpeg",
               "KHR_materials_ior",
               "KHR_materials_clearcoat",
               "KHR_draco_mesh_compression",
               "LAMINA_materials_layered",
               "data:application/octet-stream;base64,AAAAAA==",
               "data:image/png;base64,",
               "buffer.bin",
               "../outside.bin",
               "/etc/passwd"};
  for (int x : {gltf::kByte,
                gltf::kUnsignedByte,
                gltf::kShort,
                gltf::kUnsignedShort,
                gltf::kUnsignedInt,
                gltf::kFloat,
                gltf::kArrayBuffer,
                gltf::kElementArrayBuffer,
                gltf::kModeTriangles,
                gltf::kModeTriangleStrip,
                gltf::kModeTriangleFan,
                gltf::kLinear,
                gltf::kLinearMipmapLinear,
                gltf::kRepeat,
                gltf::kClampToEdge,
                gltf::kMirroredRepeat,
                3,
                4,
                12,
                16})
    v.numbers.push_back(x);
  add_boundary_numbers(v.numbers);
  finish(v);
  return v;
}

const Vocabulary* vocabulary_for(const std::string& target) {
  static const Vocabulary material = material_vocabulary();
  static const Vocabulary scene = scene_vocabulary();
  static const Vocabulary gltf = gltf_vocabulary();
  if (target == "material" || target == "glsl") return &material;
  if (target == "scene") return &scene;
  if (target == "gltf_import" || target == "mesh") return &gltf;
  return nullptr;
}

std::string dictionary_text(const Vocabulary& vocabulary) {
  std::set<std::string> words(vocabulary.keys.begin(), vocabulary.keys.end());
  words.insert(vocabulary.strings.begin(), vocabulary.strings.end());
  std::string text;
  for (const std::string& w : words) text += Json(w).dump() + "\n";
  return text;
}

bool mutate_json(std::string& text, const Vocabulary& vocabulary, std::mt19937& rng, size_t max_size) {
  std::string result = text;
  if (result.size() >= 20 && read_u32(result, 0) == gltf::kGlbMagic) {
    // GLB: the JSON chunk is mutated; the header and chunk lengths are written to fit it.
    const std::uint32_t json_length = read_u32(result, 12);
    if (read_u32(result, 16) != gltf::kChunkJson || json_length > result.size() - 20) return false;
    std::string json = result.substr(20, json_length);
    if (!mutate_text(json, vocabulary, rng)) return false;
    json.append((4 - json.size() % 4) % 4, ' ');
    const std::string rest = result.substr(20 + json_length);
    result.clear();
    append_u32(result, gltf::kGlbMagic);
    append_u32(result, gltf::kGlbVersion);
    append_u32(result, static_cast<std::uint32_t>(20 + json.size() + rest.size()));
    append_u32(result, static_cast<std::uint32_t>(json.size()));
    append_u32(result, gltf::kChunkJson);
    result += json;
    result += rest;
  } else if (!mutate_text(result, vocabulary, rng)) {
    return false;
  }
  if (result.size() > max_size) return false;
  text = std::move(result);
  return true;
}

}  // namespace lamina::fuzz
