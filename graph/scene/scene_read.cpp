#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "graph/json_values.h"
#include "graph/limits.h"
#include "graph/load.h"
#include "graph/number_text.h"
#include "graph/scene/scene.h"

#include "graph/cpu/image.h"
#include "graph/scene/primitives.h"
#include "graph/scene/scene_fields.h"

namespace lamina {

namespace {

// The values of one JSON object that passed their declaration's checks, by key; a key the object
// leaves out has its declared default.
class FieldValues {
 public:
  explicit FieldValues(const std::vector<ParamDecl>& fields) : fields_(fields) {}

  void set_numbers(const std::string& name, std::vector<double> numbers) { numbers_[name] = std::move(numbers); }
  void set_text(const std::string& name, std::string text) { texts_[name] = std::move(text); }

  bool has(const std::string& name) const { return numbers_.count(name) || texts_.count(name); }
  // Whether the object's declarations have the key at all (a point light has no cone).
  bool declares(const std::string& name) const { return find_param(fields_, name) != nullptr; }
  double number(const std::string& name) const { return numbers(name)[0]; }
  // For a key declared optional: none when the object leaves it out.
  std::optional<double> optional_number(const std::string& name) const {
    if (!has(name)) return std::nullopt;
    return number(name);
  }
  glm::dvec2 vec2(const std::string& name) const {
    const auto v = numbers(name);
    return {v[0], v[1]};
  }
  glm::dvec3 vec3(const std::string& name) const {
    const auto v = numbers(name);
    return {v[0], v[1], v[2]};
  }
  glm::dquat quaternion(const std::string& name) const {  // written [x, y, z, w]
    const auto v = numbers(name);
    return {v[3], v[0], v[1], v[2]};
  }
  // "" for a key left out with no default (the error of a required one is already reported).
  std::string text(const std::string& name) const {
    if (auto it = texts_.find(name); it != texts_.end()) return it->second;
    const Value* fallback = declared_default(name);
    return fallback && std::holds_alternative<std::string>(*fallback) ? std::get<std::string>(*fallback) : "";
  }

 private:
  // The reader asks only for keys the object's declarations have: anything else is its own mistake.
  const Value* declared_default(const std::string& name) const {
    const ParamDecl* decl = find_param(fields_, name);
    if (!decl) throw std::logic_error("the scene reader asks for '" + name + "', which is not declared here");
    return decl->fallback ? &*decl->fallback : nullptr;
  }

  std::vector<double> numbers(const std::string& name) const {
    if (auto it = numbers_.find(name); it != numbers_.end()) return it->second;
    const Value* fallback = declared_default(name);
    std::vector<double> numbers = fallback ? value_numbers(*fallback) : std::vector<double>();
    if (numbers.empty())
      throw std::logic_error("the scene reader asks for the number '" + name + "', which has no default");
    return numbers;
  }

  const std::vector<ParamDecl>& fields_;
  std::map<std::string, std::vector<double>> numbers_;
  std::map<std::string, std::string> texts_;
};

std::string single_quoted(const std::string& s) { return quote_excerpt(s, '\''); }

bool has_extension(const std::filesystem::path& path, std::initializer_list<const char*> extensions) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return std::any_of(extensions.begin(), extensions.end(), [&](const char* e) { return ext == e; });
}

class SceneReader {
 public:
  SceneReader(const std::string& file, Diagnostics& diagnostics, const AssetPolicy& policy)
      : file_(file), dir_(std::filesystem::path(file).parent_path()), diag_(diagnostics), policy_(policy) {}

  Scene read(std::string_view text) {
    Scene scene;
    scene.path = file_;
    scene.policy = policy_;
    auto parsed =
        parse_json(text, file_, diag_, "a scene file is a JSON object with \"format\", \"materials\" and \"objects\"");
    if (!parsed) return scene;
    const Json& root = *parsed;
    if (!root.is_object()) {
      error("", "expected an object with \"format\", \"materials\" and \"objects\", found " + json_kind(root));
      return scene;
    }
    check_known_keys(root, file_, "", {"$schema", "format", "materials", "cameras", "lights", "objects"}, diag_);
    if (auto it = root.find("$schema"); it != root.end()) {
      if (it->is_string())
        scene.schema = it->get<std::string>();
      else
        error("/$schema", "expected a string (the schema's path or URI), found " + json_kind(*it));
    }
    read_format(root);
    read_materials(root, scene);
    for_each_element(root, "cameras", "camera", false, [&](const Json& j, const std::string& p) {
      if (auto c = read_camera(j, p)) scene.cameras.push_back(std::move(*c));
    });
    for_each_element(root, "lights", "light", false, [&](const Json& j, const std::string& p) {
      if (auto l = read_light(j, p)) scene.lights.push_back(std::move(*l));
    });
    std::vector<std::string> object_pointers;
    for_each_element(root, "objects", "object", true, [&](const Json& j, const std::string& p) {
      if (auto o = read_object(j, p)) {
        scene.objects.push_back(std::move(*o));
        object_pointers.push_back(p);
      }
    });
    check_material_names(scene, object_pointers);
    check_geometry_budget(scene, object_pointers);
    return scene;
  }

 private:
  void error(const std::string& pointer, std::string message, std::string hint = {}) {
    diag_.error(file_, pointer, std::move(message), std::move(hint));
  }

  std::filesystem::path resolve(const std::string& written) const { return (dir_ / written).lexically_normal(); }

  // `written` followed under the policy; a refused reference is an error at `pointer` that starts
  // with `what` ("material file", ...).
  std::optional<Reference> follow(const std::string& written, const std::string& pointer, const std::string& what) {
    try {
      return resolve_reference(file_, written, ReferenceScope::AssetRoots, policy_);
    } catch (const ReferenceError& e) {
      error(pointer, what + " " + e.what(),
            e.hint().empty() ? "paths are relative to the scene file's directory" : e.hint());
      return std::nullopt;
    }
  }

  void read_format(const Json& root) {
    auto it = root.find("format");
    if (it == root.end()) {
      error("", "missing \"format\"", "add \"format\": " + std::to_string(kSceneFormatVersion));
    } else if (!it->is_number()) {
      error("/format", "expected the format version number, found " + json_kind(*it),
            "write \"format\": " + std::to_string(kSceneFormatVersion));
    } else if (it->get<double>() != kSceneFormatVersion) {
      error("/format", "unsupported format " + number_text(it->get<double>()) + ": this lamina reads scene format " +
                           std::to_string(kSceneFormatVersion));
    }
  }

  // Calls `visit` on each element of the array root[key]; reports a missing (when required),
  // non-array or empty (when required) value, and names used twice within the array.
  template <class Visit>
  void for_each_element(const Json& root, const std::string& key, const std::string& what, bool required, Visit visit) {
    std::string pointer = "/" + key;
    auto it = root.find(key);
    if (it == root.end()) {
      if (required) error("", "missing \"" + key + "\"", "add \"" + key + "\": [ { \"name\": ..., ... } ]");
      return;
    }
    if (!it->is_array()) {
      error(pointer, "expected an array of " + what + "s, found " + json_kind(*it));
      return;
    }
    if (required && it->empty()) error(pointer, "the scene has no " + what, "add at least one " + what);
    std::map<std::string, size_t> seen;
    for (size_t i = 0; i < it->size(); ++i) {
      const Json& element = (*it)[i];
      std::string at = pointer_append(pointer, i);
      if (!element.is_object()) {
        error(at, "expected " + what + " object, found " + json_kind(element));
        continue;
      }
      if (auto name = element.find("name"); name != element.end() && name->is_string()) {
        auto [first, inserted] = seen.emplace(name->get<std::string>(), i);
        if (!inserted)
          error(at + "/name",
                "duplicate " + what + " name " + single_quoted(first->first) + " (also " +
                    pointer_append(pointer, first->second) + ")",
                "names identify " + what + "s: make them unique");
      }
      visit(element, at);
    }
  }

  // The kind a discriminating key names (a light's "type", an object's "shape") as an index into
  // its choices; none after an error.
  std::optional<size_t> read_kind(const Json& j, const std::string& pointer, const ParamDecl& key,
                                  const std::string& owner) {
    auto it = j.find(key.name);
    if (it == j.end()) {
      error(pointer, "missing \"" + key.name + "\" of " + owner,
            "valid " + key.name + "s: " + join_alternatives(key.choices));
      return std::nullopt;
    }
    const std::vector<ParamDecl> only{key};
    FieldValues probe(only);
    read_field(key, *it, pointer_append(pointer, key.name), probe);
    if (!probe.has(key.name)) return std::nullopt;
    return static_cast<size_t>(std::find(key.choices.begin(), key.choices.end(), probe.text(key.name)) -
                               key.choices.begin());
  }

  // Checks keys, types, ranges and required fields of `j` against `fields`; returns whether all
  // passed. Nested objects (the transform) are left to the caller.
  bool read_fields(const Json& j, const std::string& pointer, const std::vector<ParamDecl>& fields,
                   const std::string& owner, FieldValues& out) {
    size_t errors_before = diag_.errors().size();
    check_known_keys(j, file_, pointer, param_names(fields), diag_);
    for (const auto& f : fields) {
      auto it = j.find(f.name);
      if (it == j.end()) {
        if (f.required()) error(pointer, "missing \"" + f.name + "\" of " + owner, f.doc);
        continue;
      }
      read_field(f, *it, pointer_append(pointer, f.name), out);
    }
    return diag_.errors().size() == errors_before;
  }

  bool check_number(const ParamDecl& f, double v, const std::string& pointer, const std::string& label) {
    if (!std::isfinite(v)) {
      error(pointer, label + " is not a finite number", "JSON numbers beyond 1.8e308 overflow to infinity");
      return false;
    }
    if (!f.in_range(v)) {
      error(pointer, label + " = " + number_text(v) + " is out of range: expected " + f.range_text(label), f.doc);
      return false;
    }
    return true;
  }

  void read_field(const ParamDecl& f, const Json& j, const std::string& pointer, FieldValues& out) {
    auto expected = [&](const std::string& what) {
      error(pointer, "expected " + what + ", found " + json_describe(j), f.doc);
    };
    switch (f.type) {
      case ValueType::Float:
      case ValueType::Integer: {
        if (!j.is_number()) return expected(f.expected_text());
        double v = j.get<double>();
        if (f.type == ValueType::Integer && v != std::floor(v))
          return error(pointer, f.name + " = " + number_text(v) + " is not a whole number", f.doc);
        if (check_number(f, v, pointer, f.name)) out.set_numbers(f.name, {v});
        return;
      }
      case ValueType::Vec2:
      case ValueType::Vec3:
      case ValueType::Color:
      case ValueType::Quaternion: {
        const size_t size = size_t(value_components(f.type));
        const std::string shape = f.expected_text();
        if (!j.is_array()) return expected(shape);
        if (j.size() != size)
          return error(pointer,
                       "expected " + shape + " of " + std::to_string(size) + " numbers, found " +
                           std::to_string(j.size()) + " elements",
                       f.doc);
        std::vector<double> v(size);
        bool ok = true;
        for (size_t i = 0; i < size; ++i) {
          std::string at = pointer_append(pointer, i);
          if (!j[i].is_number()) {
            error(at, "expected a number, found " + json_describe(j[i]));
            ok = false;
            continue;
          }
          v[i] = j[i].get<double>();
          ok = check_number(f, v[i], at, f.name + "[" + std::to_string(i) + "]") && ok;
        }
        if (ok) out.set_numbers(f.name, std::move(v));
        return;
      }
      case ValueType::String: {
        if (!j.is_string()) return expected(f.expected_text());
        const auto text = j.get<std::string>();
        if (text.empty()) return error(pointer, "expected a non-empty string", f.doc);
        // Code points: every byte but UTF-8's continuation bytes starts one.
        const auto length = static_cast<size_t>(std::count_if(
            text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xc0) != 0x80; }));
        if (f.max_length > 0 && length > f.max_length)
          return error(
              pointer,
              f.name + " has " + std::to_string(length) + " characters, more than " + std::to_string(f.max_length),
              f.doc);
        out.set_text(f.name, text);
        return;
      }
      case ValueType::Enum: {
        if (!j.is_string()) return expected(f.expected_text());
        auto text = j.get<std::string>();
        if (std::find(f.choices.begin(), f.choices.end(), text) == f.choices.end()) {
          std::string suggestion = closest_match(text, f.choices);
          return error(pointer, "unknown " + f.name + " " + quote_excerpt(text),
                       (suggestion.empty() ? std::string() : "did you mean \"" + suggestion + "\"? ") +
                           "valid values: " + join_alternatives(f.choices));
        }
        out.set_text(f.name, text);
        return;
      }
      case ValueType::Object:
        if (!j.is_object()) expected(f.expected_text());
        return;
      case ValueType::Bool:
      case ValueType::Interface:
      case ValueType::Medium:
      case ValueType::Stack: throw std::logic_error("scene key " + f.name + " has a type scene files do not use");
    }
  }

  // A unit vector along `v`, or an error at `pointer` when `v` has no direction.
  std::optional<glm::dvec3> direction(glm::dvec3 v, const std::string& pointer, const std::string& what) {
    double length = glm::length(v);
    if (!(length > 1e-12)) {
      error(pointer,
            what + (length == 0.0 ? " has zero length" : " has length " + number_text(length) + ", below 1e-12") +
                ": it gives no direction",
            "write a vector of length well above 0");
      return std::nullopt;
    }
    return v / length;
  }

  void read_materials(const Json& root, Scene& scene) {
    auto it = root.find("materials");
    if (it == root.end()) {
      error("", "missing \"materials\"", "list the material files, e.g. \"materials\": [\"../materials/brass.json\"]");
      return;
    }
    if (!it->is_array()) {
      error("/materials", "expected an array of material file paths, found " + json_kind(*it));
      return;
    }
    if (it->empty()) error("/materials", "the scene lists no material file", "add at least one material file");
    std::map<std::filesystem::path, size_t> files;
    std::map<std::string, size_t> names;  // material name -> index in scene.material_files
    for (size_t i = 0; i < it->size(); ++i) {
      std::string pointer = pointer_append("/materials", i);
      const Json& entry = (*it)[i];
      if (!entry.is_string() || entry.get<std::string>().empty()) {
        error(pointer, "expected the path of a material file, found " + json_describe(entry));
        continue;
      }
      MaterialFileRef ref;
      ref.path = entry.get<std::string>();
      ref.resolved = resolve(ref.path);
      if (auto [first, inserted] = files.emplace(ref.resolved, i); !inserted) {
        error(pointer,
              "material file " + ref.resolved.string() + " is listed twice (also /materials/" +
                  std::to_string(first->second) + ")",
              "remove one of them");
        continue;
      }
      const auto reference = follow(ref.path, pointer, "material file");
      if (!reference) continue;
      CheckedFile checked;
      try {
        checked = check_text(read_reference(*reference, kMaxJsonFileBytes, policy_), ref.resolved.string(), policy_);
      } catch (const ReferenceError& e) {
        error(pointer, std::string("material file ") + e.what(), e.hint());
        continue;
      }
      diag_.append(checked.diagnostics);
      if (!checked.ok()) materials_incomplete_ = true;
      ref.document = std::move(checked.document);
      for (const auto& m : ref.document.materials) {
        if (m.name.empty()) continue;
        auto [first, inserted] = names.emplace(m.name, scene.material_files.size());
        if (!inserted)
          error(pointer,
                "material " + single_quoted(m.name) + " is defined in both " +
                    scene.material_files[first->second].resolved.string() + " and " + ref.resolved.string(),
                "objects name materials, so each name must be defined once: rename one of them");
      }
      scene.material_files.push_back(std::move(ref));
    }
    if (scene.material_files.size() != it->size()) materials_incomplete_ = true;
  }

  std::optional<Camera> read_camera(const Json& j, const std::string& pointer) {
    FieldValues v(camera_fields());
    if (!read_fields(j, pointer, camera_fields(), "a camera", v)) return std::nullopt;
    Camera c;
    c.name = v.text("name");
    c.position = v.vec3("position");
    c.look_at = v.vec3("look_at");
    c.up = v.vec3("up");
    c.yfov_deg = v.number("yfov");
    c.aspect = v.number("aspect");
    c.znear = v.number("znear");
    c.zfar = v.optional_number("zfar");
    c.exposure = v.number("exposure");
    c.aperture_radius = v.number("aperture_radius");
    c.focus_distance = v.optional_number("focus_distance");
    bool ok = true;
    if (const double distance = glm::length(c.look_at - c.position); !(distance >= 1e-9)) {
      error(pointer + "/look_at",
            (distance == 0.0 ? std::string("look_at equals position")
                             : "look_at is " + number_text(distance) + " from position, closer than 1e-9") +
                ": the camera has no view direction",
            "look at a point away from the camera");
      ok = false;
    } else if (auto up = direction(c.up, pointer + "/up", "up")) {
      glm::dvec3 view = glm::normalize(c.look_at - c.position);
      if (glm::length(glm::cross(view, *up)) < 1e-6) {
        error(pointer + "/up", "up is parallel to the view direction: the camera's roll is undefined",
              "choose an up vector across the view direction, e.g. [0, 1, 0] unless looking straight up or down");
        ok = false;
      }
    } else {
      ok = false;
    }
    if (c.zfar && !(*c.zfar > c.znear)) {
      error(pointer + "/zfar",
            "zfar = " + number_text(*c.zfar) + " must be greater than znear = " + number_text(c.znear));
      ok = false;
    }
    return ok ? std::optional<Camera>(c) : std::nullopt;
  }

  std::optional<Light> read_light(const Json& j, const std::string& pointer) {
    const auto kind = read_kind(j, pointer, light_type_field(), "a light");
    if (!kind) return std::nullopt;
    const auto t = static_cast<LightType>(*kind);
    const auto& fields = light_fields(t);
    FieldValues v(fields);
    if (!read_fields(j, pointer, fields, "a " + light_type_names()[*kind] + " light", v)) return std::nullopt;
    // What the type does not declare keeps the initialisers of Light, unused.
    Light l;
    l.name = v.text("name");
    l.type = t;
    l.color = v.vec3("color");
    l.intensity = v.number("intensity");
    if (v.declares("position")) l.position = v.vec3("position");
    if (v.declares("range")) l.range = v.optional_number("range");
    if (v.declares("inner_cone")) l.inner_cone_deg = v.number("inner_cone");
    if (v.declares("outer_cone")) l.outer_cone_deg = v.number("outer_cone");
    if (v.declares("angular_radius")) l.angular_radius_deg = v.number("angular_radius");
    if (v.declares("rotation")) l.rotation_deg = v.number("rotation");
    if (v.declares("direction")) {
      auto d = direction(v.vec3("direction"), pointer + "/direction", "direction");
      if (!d) return std::nullopt;
      l.direction = *d;
    }
    if (t == LightType::Spot && !(l.inner_cone_deg < l.outer_cone_deg)) {
      // KHR_lights_punctual: innerConeAngle must be less than outerConeAngle.
      error(pointer + "/inner_cone",
            "inner_cone = " + number_text(l.inner_cone_deg) +
                " must be less than outer_cone = " + number_text(l.outer_cone_deg),
            "the falloff runs from inner_cone to outer_cone");
      return std::nullopt;
    }
    if (t == LightType::Environment && v.has("file")) {
      l.file = v.text("file");
      l.resolved_file = resolve(l.file);
      const auto reference = follow(l.file, pointer + "/file", "environment image");
      if (!reference) return std::nullopt;
      l.reference = *reference;
      // Decoded now, as rendering will: what validates also loads.
      try {
        load_image_reference(l.reference, false, policy_);
      } catch (const ReferenceError& e) {
        error(pointer + "/file", std::string("environment image ") + e.what(), e.hint());
        return std::nullopt;
      } catch (const ImageError& e) {
        error(pointer + "/file", "environment image '" + l.file + "' is not a readable image: " + e.what());
        return std::nullopt;
      }
    }
    return l;
  }

  std::optional<Transform> read_transform(const Json& j, const std::string& pointer) {
    FieldValues v(transform_fields());
    if (!read_fields(j, pointer, transform_fields(), "a transform", v)) return std::nullopt;
    Transform t;
    t.translation = v.vec3("translation");
    t.scale = v.vec3("scale");
    const glm::dvec3 magnitude = glm::abs(t.scale);
    const double smallest = glm::min(magnitude.x, glm::min(magnitude.y, magnitude.z));
    const double largest = glm::max(magnitude.x, glm::max(magnitude.y, magnitude.z));
    if (largest > kMaxScaleRatio * smallest) {
      // The scale's magnitudes are the singular values of the linear part (the rotation keeps
      // them), so their ratio is its condition number.
      error(pointer + "/scale",
            "the transform is practically singular: its largest scale is " + number_text(largest / smallest) +
                " times its smallest, more than " + number_text(kMaxScaleRatio) +
                " (single precision cannot invert it, so normals would be lost)",
            "flatten a shape by its own size parameters rather than by the scale");
      return std::nullopt;
    }
    if (v.has("rotation") && v.has("rotation_deg")) {
      error(pointer + "/rotation_deg", "give only one of \"rotation\" or \"rotation_deg\"",
            "they describe the same rotation");
      return std::nullopt;
    }
    if (v.has("rotation_deg")) {
      glm::dvec3 a = glm::radians(v.vec3("rotation_deg"));
      // Fixed axes x, then y, then z: R = Rz Ry Rx.
      t.rotation = glm::angleAxis(a.z, glm::dvec3(0, 0, 1)) * glm::angleAxis(a.y, glm::dvec3(0, 1, 0)) *
                   glm::angleAxis(a.x, glm::dvec3(1, 0, 0));
    } else {
      const glm::dquat rotation = v.quaternion("rotation");
      double length = glm::length(rotation);
      if (!(length > 1e-12)) {
        error(pointer + "/rotation",
              "the quaternion has " +
                  (length == 0.0 ? std::string("zero length") : "length " + number_text(length) + ", below 1e-12") +
                  ": it is no rotation",
              "the identity is [0, 0, 0, 1] (x, y, z, w)");
        return std::nullopt;
      }
      if (std::abs(length - 1.0) > 1e-3)
        diag_.warning(file_, pointer + "/rotation",
                      "the quaternion has length " + number_text(length) + ", not 1: it is normalised",
                      "write a unit quaternion [x, y, z, w]");
      t.rotation = rotation / length;
    }
    return t;
  }

  std::optional<SceneObject> read_object(const Json& j, const std::string& pointer) {
    const auto kind = read_kind(j, pointer, shape_field(), "an object");
    if (!kind) return std::nullopt;
    const auto s = static_cast<ShapeType>(*kind);
    const auto& fields = object_fields(s);
    FieldValues v(fields);
    bool ok = read_fields(j, pointer, fields, "a " + shape_names()[*kind], v);
    // What the shape does not declare keeps the initialisers of SceneObject, unused.
    SceneObject o;
    o.name = v.text("name");
    o.shape = s;
    o.material = v.text("material");
    o.label = v.text("label");
    if (v.has("emission")) o.emission = v.vec3("emission");
    switch (s) {
      case ShapeType::Sphere:
        o.radius = v.number("radius");
        o.segments = static_cast<int>(v.number("segments"));
        break;
      case ShapeType::Plane: o.plane_size = v.vec2("size"); break;
      case ShapeType::Box: o.box_size = v.vec3("size"); break;
      case ShapeType::Torus:
        o.major_radius = v.number("major_radius");
        o.minor_radius = v.number("minor_radius");
        o.segments = static_cast<int>(v.number("segments"));
        break;
      case ShapeType::Mesh: break;  // its file is read below
    }
    // Left out, the transform is read as an empty one: every key at its declared default.
    static const Json kDefaultTransform = Json::object();
    if (auto t = j.find("transform"); t == j.end() || t->is_object()) {
      auto transform = read_transform(t == j.end() ? kDefaultTransform : *t, pointer + "/transform");
      if (transform)
        o.transform = *transform;
      else
        ok = false;
    }
    if (!ok) return std::nullopt;
    if (s == ShapeType::Torus && !(o.minor_radius < o.major_radius)) {
      error(pointer + "/minor_radius",
            "minor_radius = " + number_text(o.minor_radius) +
                " must be less than major_radius = " + number_text(o.major_radius),
            "a thicker tube intersects itself");
      return std::nullopt;
    }
    if (s == ShapeType::Mesh && !read_mesh_file(o, v.text("file"), pointer + "/file")) return std::nullopt;
    return o;
  }

  bool read_mesh_file(SceneObject& o, const std::string& written, const std::string& pointer) {
    o.mesh_file = written;
    o.resolved_mesh_file = resolve(written);
    if (!has_extension(o.resolved_mesh_file, {".gltf", ".glb"})) {
      error(pointer, "expected a .gltf or .glb mesh file, found " + quote_excerpt(written));
      return false;
    }
    const auto reference = follow(written, pointer, "mesh file");
    if (!reference) return false;
    o.mesh_reference = *reference;
    // Loaded now so that a mesh file's problems are reported here, not when exporting; once per
    // file however many objects use it.
    auto [known, first_use] = mesh_files_.emplace(o.resolved_mesh_file, MeshFileUse{true, pointer});
    if (!first_use) {
      if (!known->second.ok)
        error(pointer, "the mesh file " + o.resolved_mesh_file.string() + " has errors",
              "they are reported where the scene first uses it, " + known->second.first_pointer);
      return known->second.ok;
    }
    try {
      known->second.vertices = object_mesh(o, policy_).positions.size();
    } catch (const ReferenceError& e) {
      known->second.ok = false;
      error(pointer, std::string("mesh file ") + e.what(), e.hint());
    } catch (const IoError& e) {
      known->second.ok = false;
      error(pointer, e.what());
    } catch (const Error& e) {
      // Problems of a value in the mesh file are reported at that value, naming the object that
      // uses the file; problems of the file as a whole at the object's "file".
      known->second.ok = false;
      for (const auto& d : e.diagnostics()) {
        if (d.pointer.empty())
          error(pointer, d.file + ": " + d.message, d.hint);
        else
          diag_.error(d.file, d.pointer, d.message,
                      (d.hint.empty() ? "" : d.hint + "; ") + "the mesh of " + file_ + ":" + pointer);
      }
    }
    return known->second.ok;
  }

  // kMaxSceneVertices over the distinct shapes, counted without building them; the first object
  // whose shape takes the scene beyond it is the error.
  void check_geometry_budget(const Scene& scene, const std::vector<std::string>& pointers) {
    std::set<std::string> counted;
    size_t total = 0;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      const SceneObject& o = scene.objects[i];
      if (!counted.insert(geometry_key(o)).second) continue;
      const size_t vertices =
          o.shape == ShapeType::Mesh ? mesh_files_[o.resolved_mesh_file].vertices : shape_vertices(o);
      total += vertices;
      if (total > kMaxSceneVertices) {
        error(pointers[i],
              "with this object the scene's distinct shapes have " + std::to_string(total) +
                  " vertices, more than the " + std::to_string(kMaxSceneVertices) + " lamina builds for one scene",
              "this shape has " + std::to_string(vertices) +
                  "; objects of the same shape, size and tessellation share one mesh: reuse shapes, or use fewer "
                  "segments");
        return;
      }
    }
  }

  void check_material_names(const Scene& scene, const std::vector<std::string>& pointers) {
    // With a material file missing or broken, unknown names would only be knock-on errors.
    if (materials_incomplete_) return;
    std::vector<std::string> known;
    for (const auto& f : scene.material_files)
      for (const auto& m : f.document.materials) known.push_back(m.name);
    const std::set<std::string, std::less<>> defined(known.begin(), known.end());
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      const auto& name = scene.objects[i].material;
      if (defined.count(name)) continue;
      std::string suggestion = diag_.suggest(name, known);
      error(pointers[i] + "/material", "unknown material " + single_quoted(name),
            (suggestion.empty() ? std::string() : "did you mean " + single_quoted(suggestion) + "? ") +
                "the scene's material files define " + join_alternatives(known));
    }
  }

  const std::string& file_;
  std::filesystem::path dir_;
  Diagnostics& diag_;
  const AssetPolicy& policy_;
  bool materials_incomplete_ = false;
  struct MeshFileUse {
    bool ok = true;             // whether it loaded
    std::string first_pointer;  // the first object's "file" that named it
    size_t vertices = 0;        // over every instance of its meshes
  };
  std::map<std::filesystem::path, MeshFileUse> mesh_files_;  // by resolved path
};

}  // namespace

Scene read_scene(std::string_view text, const std::string& file, Diagnostics& diagnostics, const AssetPolicy& policy) {
  const AssetPolicy effective = policy.with_default_root(file);
  return SceneReader(file, diagnostics, effective).read(text);
}

Scene read_scene_file(const std::filesystem::path& path, Diagnostics& diagnostics, const AssetPolicy& policy) {
  std::string text;
  try {
    text = read_input_file(path, kMaxJsonFileBytes);
  } catch (const Error& e) {  // too large: a mistake of the file
    for (const auto& d : e.diagnostics()) diagnostics.error(d.file, d.pointer, d.message, d.hint);
    Scene scene;
    scene.path = path.string();
    scene.policy = policy.with_default_root(path);
    return scene;
  }
  return read_scene(text, path.string(), diagnostics, policy);
}

}  // namespace lamina
