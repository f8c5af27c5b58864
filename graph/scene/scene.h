// A scene as written in a scene file: cameras, lights, objects with transforms and materials
// assigned by name from material files. Read and checked like material files (every problem with
// the file and its JSON pointer); the glTF exporter and, later, the path tracer consume it.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graph/diagnostics.h"
#include "graph/document.h"

namespace lamina {

inline constexpr int kSceneFormatVersion = 1;

// The initialisers below serve scenes built in code (sample_sheet). What a scene file leaves out
// takes the defaults declared in graph/scene/scene_fields.cpp, and
// tests/graph/scene/scene_fields_test.cpp checks that the two agree.

struct Camera {
  std::string name;
  glm::dvec3 position{0.0, 0.0, 5.0};
  glm::dvec3 look_at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double yfov_deg = 40.0;  // vertical field of view
  double aspect = 1.5;     // width / height
  double znear = 0.05;
  std::optional<double> zfar;  // none: infinite projection
  double exposure = 0.0;       // stops: lamina render multiplies the image's radiance by 2^exposure
  // A thin lens (lamina render only): the lens's radius, 0 for a pinhole, and the distance along the
  // view direction of the plane in focus (none: the distance to look_at).
  double aperture_radius = 0.0;
  std::optional<double> focus_distance;
  // The plane in focus: focus_distance, or the distance to look_at.
  double focus() const { return focus_distance ? *focus_distance : glm::length(look_at - position); }
};

enum class LightType { Point, Directional, Spot, Environment };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::dvec3 color{1.0};  // linear RGB
  // Point and spot: luminous intensity in candela; directional: illuminance in lux (as
  // KHR_lights_punctual); environment: a multiplier of the image's radiance.
  double intensity = 1.0;
  glm::dvec3 position{0.0};             // point, spot
  glm::dvec3 direction{0.0, -1.0, 0};   // directional, spot: where the light travels
  double inner_cone_deg = 0.0;          // spot
  double outer_cone_deg = 45.0;         // spot
  double angular_radius_deg = 0.0;      // directional: the source's apparent radius (0: a point at infinity)
  std::optional<double> range;          // point, spot
  double rotation_deg = 0.0;            // environment: the image turned about +y (counter-clockwise from above)
  std::string file;                     // environment: an equirectangular image, as written
  std::filesystem::path resolved_file;  // environment: the file against the scene's folder, lexically normal
  Reference reference;                  // environment: the file as file_access.h follows it
};

// A triangle mesh with what shading needs: per-vertex position, normal, tangent (xyz and the
// bitangent sign in w, glTF's convention) and uv; counter-clockwise front faces.
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;  // three per triangle
};

enum class ShapeType { Sphere, Plane, Box, Torus, Mesh };

struct Transform {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
  glm::dvec3 scale{1.0};
};

struct SceneObject {
  std::string name;
  ShapeType shape = ShapeType::Sphere;
  // Sphere: radius; plane: size (x, z extent, y up); box: size (x, y, z); torus: major and minor
  // radius. The shape's own parameters, already checked.
  double radius = 1.0;
  glm::dvec2 plane_size{1.0};
  glm::dvec3 box_size{1.0};
  double major_radius = 1.0, minor_radius = 0.25;
  int segments = 64;                         // tessellation of curved primitives (around); rings are derived
  std::string mesh_file;                     // mesh: as written
  std::filesystem::path resolved_mesh_file;  // mesh: against the scene's folder, lexically normal
  Reference mesh_reference;                  // mesh: the file as file_access.h follows it
  Transform transform;
  std::string material;      // a material name from one of the scene's material files
  std::string label;         // shown under the object by the glTF export; empty: none
  glm::dvec3 emission{0.0};  // radiance leaving its front faces [cd/m^2], linear RGB; 0: none
};

struct MaterialFileRef {
  std::string path;                // as written, relative to the scene file
  std::filesystem::path resolved;  // against the scene's folder, lexically normal
  Document document;               // loaded and checked
};

struct Scene {
  std::string path;    // where it was read from
  AssetPolicy policy;  // how its files (and its material files' textures) are followed
  std::optional<std::string> schema;
  int format = kSceneFormatVersion;
  std::vector<MaterialFileRef> material_files;
  std::vector<Camera> cameras;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;

  // The material called `name` and the file it came from; nullptr when unknown.
  const Material* find_material(std::string_view name, const MaterialFileRef** file = nullptr) const;
};

// Reads and checks a scene: JSON, keys, types, finite and in-range numbers, transforms (no zero
// scale, unit-length-able rotations), material files (each checked as `lamina validate` would;
// their problems are reported under their own file), material names (unknown: "did you mean"),
// mesh files (loaded) and environment images (decoded), every file followed under `policy`
// (file_access.h; its roots default to the scene's folder). Problems go to `diagnostics`.
Scene read_scene(std::string_view text, const std::string& file, Diagnostics& diagnostics,
                 const AssetPolicy& policy = {});
// As read_scene; throws IoError when the scene file itself cannot be read (one beyond
// kMaxJsonFileBytes is an error in `diagnostics`).
Scene read_scene_file(const std::filesystem::path& path, Diagnostics& diagnostics, const AssetPolicy& policy = {});

// Whether a JSON file is a scene (an object with "objects") rather than a material file.
bool looks_like_scene(std::string_view text);

// A sample sheet for a material file: one unit sphere per material in a grid (rows of up to
// `columns`), named and labelled after the materials, a camera that frames them all and a key light.
Scene sample_sheet(const Document& materials, const std::filesystem::path& material_file, int columns = 4);

// The mesh of an object in its own space (the transform is not applied): a built-in primitive
// with UVs and tangents, or every triangle primitive of a .gltf/.glb file (node transforms of its
// default scene applied, normals and tangents generated where the file has none). Throws IoError
// when a mesh file cannot be read, lamina::Error for one lamina cannot use.
TriangleMesh object_mesh(const SceneObject& object, const AssetPolicy& policy);

// Objects with the same key have the same mesh (shape, size, tessellation or mesh file): the glTF
// export writes it once, and the scene's vertex budget counts it once.
std::string geometry_key(const SceneObject& object);

}  // namespace lamina
