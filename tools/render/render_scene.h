// A scene made ready for path tracing: its meshes in Embree 3 (one bottom-level scene per distinct
// geometry, instanced once per object with the object's transform), its materials compiled for
// the CPU evaluator, its lights and its environment. Embree is held through one small RAII layer:
// the device, the scenes and every error Embree reports (raised as IoError: an error of Embree is
// never a user's mistake once the scene has been read).
#pragma once

#include <embree3/rtcore.h>

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graph/cpu/evaluator.h"
#include "graph/scene/scene.h"
#include "tools/render/environment.h"

namespace lamina::render {

// What a ray meets: the point, its frames and what its material reads, in world space.
struct SurfaceHit {
  float distance = 0.0f;
  glm::vec3 position{0.0f};
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};  // unit, the triangle's front side (counter-clockwise)
  glm::vec3 normal{0.0f, 0.0f, 1.0f};            // unit, interpolated, on the geometric normal's side
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};           // interpolated, along +u
  glm::vec2 uv{0.0f};
  float uv_per_length = 0.0f;  // how fast uv changes across the triangle: sqrt(uv area / world area)
  int object = -1;
};

// A punctual light as KHR_lights_punctual defines it, in world space.
struct PunctualLight {
  LightType type = LightType::Point;
  glm::vec3 intensity{0.0f};  // colour times intensity: candela (point, spot) or lux (directional)
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};     // where the light travels (unit)
  float cos_outer = -1.0f, cos_inner = 1.0f;  // spot cone
  float range = 0.0f;                         // 0: infinite
  // Directional lights with an angular radius: a uniform disk of `radiance` seen within cos_radius of
  // -direction, whose illuminance at normal incidence is `intensity` (E = pi L sin^2 radius).
  float cos_radius = 1.0f;  // 1: a point at infinity
  glm::vec3 radiance{0.0f};
  bool delta() const { return type != LightType::Directional || cos_radius >= 1.0f; }
};

// A point drawn on the scene's emitting surfaces, towards a shading point.
struct EmitterSample {
  glm::vec3 wi{0.0f};  // unit, from the shading point towards the emitter
  float distance = 0.0f;
  glm::vec3 position{0.0f};  // the point drawn on the emitter, and its front face's normal
  glm::vec3 normal{0.0f};
  glm::vec3 radiance{0.0f};  // what the emitter sends back along -wi
  float pdf = 0.0f;          // solid-angle density at the shading point; 0: nothing drawn
};

class Device;

// What rendering needs of a read scene beyond what read_scene checks, each problem an error with the
// scene file and its pointer: the camera called `camera_name` ("" for the first; a scene without
// one, or without that one, is an error naming those it has), some light or an environment, at
// most one environment. A light of zero intensity is a warning. Returns the camera, or nullptr.
const Camera* check_renderable(const Scene& scene, const std::string& camera_name, Diagnostics& diagnostics);

class RenderScene {
 public:
  // Builds everything `scene` (read and checked by read_scene) needs for rendering. Meshes and
  // images are loaded under `policy`. Throws IoError when a file can no longer be read or Embree
  // fails. What renders but not as its author may expect goes to `warnings`, with the object's
  // pointer: a mesh whose triangles have no uv area under a material whose textures read uv.
  RenderScene(const Scene& scene, const AssetPolicy& policy, Diagnostics* warnings = nullptr);
  ~RenderScene();
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;

  // The closest surface along origin + t direction for t in (0, t_max); direction need not be unit.
  std::optional<SurfaceHit> intersect(glm::vec3 origin, glm::vec3 direction, float t_max) const;
  // Whether anything lies along origin + t direction for t in (0, t_max).
  bool occluded(glm::vec3 origin, glm::vec3 direction, float t_max) const;

  const cpu::Evaluator& material(int object) const { return *materials_[size_t(object_material_[size_t(object)])]; }
  const std::vector<PunctualLight>& lights() const { return lights_; }
  // The radiance an object emits from its front faces (0 for most).
  glm::vec3 emission(int object) const { return emission_[size_t(object)]; }
  bool has_emitters() const { return emitter_power_ > 0.0; }
  // A point on the emitting triangles, drawn in proportion to their area times their emission's
  // luminance, seen from `from`; u: three uniform numbers.
  EmitterSample sample_emitter(glm::vec3 from, glm::vec3 u) const;
  // The solid-angle density sample_emitter gives a ray from a point that meets the emitting `hit`
  // (its front face) at `distance`, arriving along `direction` (unit).
  float emitter_pdf(const SurfaceHit& hit, glm::vec3 direction) const;
  const Environment& environment() const { return environment_; }
  // Lights the scene with `environment` instead of the scene's own (a preview's studio).
  void set_environment(Environment environment) { environment_ = std::move(environment); }
  // The scene's bounding sphere radius about the origin (for offsets and far planes).
  float extent() const { return extent_; }

 private:
  struct Mesh {
    TriangleMesh mesh;  // for a sphere too: its bounds, and the uv check
    RTCScene scene = nullptr;
    float sphere_radius = 0.0f;  // > 0: Embree's exact sphere of this radius about the origin
  };
  struct Instance {
    int mesh = 0;
    glm::mat4 to_world{1.0f};
    glm::mat4 to_object{1.0f};        // the inverse of to_world
    glm::mat3 normal_to_world{1.0f};  // inverse transpose of the linear part
    bool mirrored = false;            // a negative determinant turns the winding
  };

  // The hit of an exact sphere of `radius` (object space) at `world_point`: all but object and distance.
  void sphere_hit(const Instance& instance, float radius, glm::vec3 world_point, SurfaceHit& hit) const;

  std::unique_ptr<Device> device_;
  RTCScene top_ = nullptr;
  std::vector<Mesh> meshes_;
  std::vector<Instance> instances_;  // one per object, in the scene's order
  std::vector<std::unique_ptr<cpu::Evaluator>> materials_;
  std::vector<int> object_material_;
  std::vector<PunctualLight> lights_;
  Environment environment_;
  struct EmitterTriangle {
    glm::vec3 p0, edge1, edge2, normal;  // world space; normal: unit, the front face's
    int object = 0;
  };
  std::vector<glm::vec3> emission_;  // per object
  std::vector<EmitterTriangle> emitters_;
  std::vector<double> emitter_cdf_;  // emitters_.size() + 1, from 0 to 1
  double emitter_power_ = 0.0;       // sum of area times emission luminance
  float extent_ = 1.0f;
};

}  // namespace lamina::render
