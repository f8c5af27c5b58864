#include "tools/render/render_scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <mutex>
#include <numbers>
#include <set>

#include "graph/compile.h"
#include "graph/node_decl.h"
#include "graph/scene/mesh_shading.h"

namespace lamina::render {

// The Embree device, and the first error it reported: Embree reports errors through a callback and
// carries on, so every call that can fail is followed by check().
class Device {
 public:
  Device() {
    device_ = rtcNewDevice("verbose=0");
    if (!device_) throw IoError("Embree: cannot create a device (" + code_text(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceErrorFunction(device_, &Device::on_error, this);
  }
  ~Device() { rtcReleaseDevice(device_); }
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  RTCDevice get() const { return device_; }
  void check(const char* what) {
    std::lock_guard lock(mutex_);
    if (!error_.empty()) throw IoError(std::string("Embree: ") + what + ": " + error_);
  }

 private:
  static std::string code_text(RTCError code) {
    switch (code) {
      case RTC_ERROR_NONE: return "no error";
      case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
      case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
      case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
      case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
      case RTC_ERROR_CANCELLED: return "cancelled";
      default: return "unknown error";
    }
  }
  static void on_error(void* self, RTCError code, const char* text) {
    auto* device = static_cast<Device*>(self);
    std::lock_guard lock(device->mutex_);
    if (device->error_.empty()) device->error_ = code_text(code) + (text ? std::string(": ") + text : "");
  }

  RTCDevice device_ = nullptr;
  std::mutex mutex_;
  std::string error_;
};

namespace {

glm::dmat4 object_to_world(const Transform& t) {
  return glm::translate(glm::dmat4(1.0), t.translation) * glm::mat4_cast(t.rotation) *
         glm::scale(glm::dmat4(1.0), t.scale);
}

// A bottom-level scene of one geometry, whose buffers are filled: committed, and the geometry released
// to it.
RTCScene scene_of(Device& device, RTCGeometry geometry) {
  RTCScene scene = rtcNewScene(device.get());
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  device.check("building a geometry's hierarchy");
  return scene;
}

// A bottom-level scene holding one triangle mesh.
RTCScene mesh_scene(Device& device, const TriangleMesh& mesh) {
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.indices.size() / 3));
  device.check("allocating a mesh");
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) vertices[3 * i + size_t(c)] = mesh.positions[i][c];
  std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
  return scene_of(device, geometry);
}

// Whether a material's textures read uv: one of its texture nodes has detail over uv.
bool reads_uv(const Program& program) {
  return std::any_of(program.ops.begin(), program.ops.end(), [](const TextureOp& op) {
    return op.decl && op.decl->uv_detail && op.decl->uv_detail(op) > 0.0f;
  });
}

// How many of a mesh's triangles (of those with area) have no area in uv: there textures over uv are
// not filtered (the footprint has no uv size) and the tangent is arbitrary (mesh_shading.h).
struct UvCoverage {
  size_t without_uv_area = 0, triangles = 0;
};
UvCoverage uv_coverage(const TriangleMesh& mesh) {
  UvCoverage c;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], k = mesh.indices[t + 2];
    const glm::dvec3 e1(mesh.positions[b] - mesh.positions[a]), e2(mesh.positions[k] - mesh.positions[a]);
    if (!(glm::length(glm::cross(e1, e2)) > 0.0)) continue;
    ++c.triangles;
    const glm::dvec2 d1(mesh.uvs[b] - mesh.uvs[a]), d2(mesh.uvs[k] - mesh.uvs[a]);
    if (std::abs(d1.x * d2.y - d2.x * d1.y) < kLeastUvDeterminant) ++c.without_uv_area;
  }
  return c;
}

// A bottom-level scene holding one exact sphere of `radius` about the origin (Embree's sphere
// point): no facets, and a shading normal that is the geometric one.
RTCScene sphere_scene(Device& device, float radius) {
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* point = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  device.check("allocating a sphere");
  point[0] = point[1] = point[2] = 0.0f;
  point[3] = radius;
  return scene_of(device, geometry);
}

RTCRayHit make_ray(glm::vec3 origin, glm::vec3 direction, float t_max) {
  RTCRayHit r{};
  r.ray.org_x = origin.x, r.ray.org_y = origin.y, r.ray.org_z = origin.z;
  r.ray.dir_x = direction.x, r.ray.dir_y = direction.y, r.ray.dir_z = direction.z;
  r.ray.tnear = 0.0f;
  r.ray.tfar = t_max;
  r.ray.mask = ~0u;
  r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return r;
}

}  // namespace

const Camera* check_renderable(const Scene& scene, const std::string& camera_name, Diagnostics& diagnostics) {
  const Camera* camera = nullptr;
  if (scene.cameras.empty()) {
    diagnostics.error(scene.path, "/cameras", "the scene has no camera to render from",
                      "add one, e.g. {\"name\": \"main\", \"position\": [0, 1, 5], \"look_at\": [0, 0, 0]}");
  } else if (camera_name.empty()) {
    camera = &scene.cameras.front();
  } else {
    std::vector<std::string> names;
    for (const Camera& c : scene.cameras) {
      names.push_back(c.name);
      if (c.name == camera_name) camera = &c;
    }
    if (!camera) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + quote_excerpt(n);
      const std::string close = diagnostics.suggest(camera_name, names);
      diagnostics.error(scene.path, "/cameras",
                        "no camera called " + quote_excerpt(camera_name) + "; the scene has " + list,
                        close.empty() ? std::string() : "did you mean " + quote_excerpt(close) + "?");
    }
  }
  int environments = 0;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const std::string pointer = "/lights/" + std::to_string(i);
    if (l.type == LightType::Environment && ++environments > 1)
      diagnostics.error(scene.path, pointer, "a second environment light: a scene is lit by at most one",
                        "combine them into one image");
    if (l.intensity == 0.0 || glm::dvec3(l.color) == glm::dvec3(0.0))
      diagnostics.warning(scene.path, pointer + "/intensity", "light " + quote_excerpt(l.name) + " emits nothing");
  }
  const bool emits = std::any_of(scene.objects.begin(), scene.objects.end(),
                                 [](const SceneObject& o) { return o.emission != glm::dvec3(0.0); });
  if (scene.lights.empty() && !emits)
    diagnostics.error(scene.path, "/lights",
                      "the scene has no light, no environment and no emitting object: every image of it would be black",
                      "add a light, or an environment: {\"name\": \"sky\", \"type\": \"environment\"} is a "
                      "uniform white sky");
  return diagnostics.ok() ? camera : nullptr;
}

RenderScene::RenderScene(const Scene& scene, const AssetPolicy& policy, Diagnostics* warnings)
    : device_(std::make_unique<Device>()) {
  top_ = rtcNewScene(device_->get());
  std::map<std::string, int> mesh_of_key, material_of_name;
  std::set<std::pair<int, int>> uv_checked;  // (mesh, material) pairs, warned about once
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    // Spheres are exact, except those that emit: light samples land on the triangles of the mesh,
    // so rays must meet the same surface.
    const bool exact_sphere = object.shape == ShapeType::Sphere && object.emission == glm::dvec3(0.0);
    const std::string key = geometry_key(object) + (exact_sphere ? " exact" : "");
    auto [it, added] = mesh_of_key.try_emplace(key, int(meshes_.size()));
    if (added) {
      Mesh m;
      m.mesh = object_mesh(object, policy);
      if (exact_sphere) {
        m.sphere_radius = float(object.radius);
        m.scene = sphere_scene(*device_, m.sphere_radius);
      } else {
        m.scene = mesh_scene(*device_, m.mesh);
      }
      meshes_.push_back(std::move(m));
    }
    Instance instance;
    instance.mesh = it->second;
    const glm::dmat4 to_world = object_to_world(object.transform);
    instance.to_world = glm::mat4(to_world);
    instance.to_object = glm::mat4(glm::inverse(to_world));
    instance.normal_to_world = glm::mat3(glm::transpose(glm::inverse(glm::dmat3(to_world))));
    instance.mirrored = glm::determinant(glm::dmat3(to_world)) < 0.0;
    instances_.push_back(instance);

    RTCGeometry geometry = rtcNewGeometry(device_->get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, meshes_[size_t(instance.mesh)].scene);
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &instance.to_world[0][0]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(top_, geometry, unsigned(i));
    rtcReleaseGeometry(geometry);
    device_->check("instancing an object");

    // The scene's bounds, for ray offsets: every vertex of the instance.
    for (const glm::vec3& p : meshes_[size_t(instance.mesh)].mesh.positions)
      extent_ = std::max(extent_, glm::length(glm::vec3(instance.to_world * glm::vec4(p, 1.0f))));

    auto [material, new_material] = material_of_name.try_emplace(object.material, int(materials_.size()));
    if (new_material) {
      const MaterialFileRef* file = nullptr;
      scene.find_material(object.material, &file);
      materials_.push_back(std::make_unique<cpu::Evaluator>(compile(file->document, object.material)));
    }
    object_material_.push_back(material->second);
    if (warnings && uv_checked.emplace(instance.mesh, material->second).second &&
        reads_uv(materials_[size_t(material->second)]->program())) {
      const UvCoverage c = uv_coverage(meshes_[size_t(instance.mesh)].mesh);
      const std::string pointer =
          "/objects/" + std::to_string(i) + (object.shape == ShapeType::Mesh ? std::string("/file") : std::string());
      const std::string textured = "material " + quote_excerpt(object.material) + " reads textures over uv";
      if (c.without_uv_area > 0 && c.without_uv_area == c.triangles)
        warnings->warning(scene.path, pointer,
                          "object " + quote_excerpt(object.name) +
                              ": its mesh has no texture coordinates (no triangle has an area in uv), and " + textured +
                              ": it shows the textures' value at one point of uv, everywhere",
                          "give the mesh TEXCOORD_0, or read the textures over position (\"space\": \"position\")");
      else if (c.without_uv_area > 0)
        warnings->warning(scene.path, pointer,
                          "object " + quote_excerpt(object.name) + ": " + std::to_string(c.without_uv_area) +
                              " of its mesh's " + std::to_string(c.triangles) + " triangles have no area in uv, and " +
                              textured + ": on those, textures are not filtered and the tangent is arbitrary",
                          "give every triangle distinct texture coordinates at its corners");
    }

    emission_.push_back(glm::vec3(object.emission));
    if (object.emission != glm::dvec3(0.0)) {
      const TriangleMesh& mesh = meshes_[size_t(instance.mesh)].mesh;
      double power = 0.0;
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        auto world = [&](size_t k) {
          return glm::vec3(instance.to_world * glm::vec4(mesh.positions[mesh.indices[t + k]], 1.0f));
        };
        EmitterTriangle e;
        e.p0 = world(0);
        e.edge1 = world(1) - e.p0;
        e.edge2 = world(2) - e.p0;
        const glm::vec3 cross = glm::cross(e.edge1, e.edge2);
        const double area = 0.5 * double(glm::length(cross));
        if (!(area > 0.0)) continue;
        e.normal = glm::normalize(cross) * (instance.mirrored ? -1.0f : 1.0f);
        e.object = int(i);
        power += area * double(luminance(glm::vec3(object.emission)));
        emitters_.push_back(e);
        emitter_cdf_.push_back(emitter_power_ + power);
      }
      if (!(power > 0.0))
        throw Error({Diagnostic{Severity::Error, scene.path, "/objects/" + std::to_string(i) + "/emission",
                                "object " + quote_excerpt(object.name) +
                                    " emits light but has no area to emit it from (its triangles are degenerate)",
                                "give it a mesh with area, or remove its emission"}});
      emitter_power_ += power;
    }
  }
  if (emitter_power_ > 0.0) {
    emitter_cdf_.insert(emitter_cdf_.begin(), 0.0);
    for (double& c : emitter_cdf_) c /= emitter_power_;
    emitter_cdf_.back() = 1.0;
  }
  rtcCommitScene(top_);
  device_->check("building the scene's hierarchy");

  for (const Light& l : scene.lights) {
    const glm::vec3 scaled = glm::vec3(l.color) * float(l.intensity);
    if (l.type == LightType::Environment) {
      environment_ =
          l.file.empty() ? Environment(scaled) : Environment(load_image_reference(l.reference, false, policy), scaled);
      environment_.set_rotation(float(l.rotation_deg));
      continue;
    }
    PunctualLight p;
    p.type = l.type;
    p.intensity = scaled;
    p.position = glm::vec3(l.position);
    p.direction = glm::normalize(glm::vec3(l.direction));
    p.cos_outer = float(std::cos(glm::radians(l.outer_cone_deg)));
    p.cos_inner = float(std::cos(glm::radians(l.inner_cone_deg)));
    p.range = l.range ? float(*l.range) : 0.0f;
    if (l.type == LightType::Directional && l.angular_radius_deg > 0.0) {
      const double radius = glm::radians(l.angular_radius_deg);
      p.cos_radius = float(std::cos(radius));
      p.radiance = scaled / float(std::numbers::pi * std::sin(radius) * std::sin(radius));
    }
    lights_.push_back(p);
  }
}

RenderScene::~RenderScene() {
  if (top_) rtcReleaseScene(top_);
  for (Mesh& m : meshes_) rtcReleaseScene(m.scene);
}

std::optional<SurfaceHit> RenderScene::intersect(glm::vec3 origin, glm::vec3 direction, float t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit r = make_ray(origin, direction, t_max);
  rtcIntersect1(top_, &context, &r);
  if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  SurfaceHit hit;
  hit.object = int(r.hit.instID[0]);
  const Instance& instance = instances_[size_t(hit.object)];
  hit.distance = r.ray.tfar;
  if (const float radius = meshes_[size_t(instance.mesh)].sphere_radius; radius > 0.0f) {
    sphere_hit(instance, radius, origin + direction * r.ray.tfar, hit);
    return hit;
  }
  const TriangleMesh& mesh = meshes_[size_t(instance.mesh)].mesh;
  const uint32_t* corner = &mesh.indices[3 * size_t(r.hit.primID)];
  const float b1 = r.hit.u, b2 = r.hit.v, b0 = 1.0f - b1 - b2;
  auto lerp3 = [&](const auto& values) {
    return b0 * values[corner[0]] + b1 * values[corner[1]] + b2 * values[corner[2]];
  };

  const glm::vec3 p0 = glm::vec3(instance.to_world * glm::vec4(mesh.positions[corner[0]], 1.0f));
  const glm::vec3 p1 = glm::vec3(instance.to_world * glm::vec4(mesh.positions[corner[1]], 1.0f));
  const glm::vec3 p2 = glm::vec3(instance.to_world * glm::vec4(mesh.positions[corner[2]], 1.0f));
  const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
  const float twice_area = glm::length(cross);
  hit.position = b0 * p0 + b1 * p1 + b2 * p2;
  hit.geometric_normal =
      twice_area > 0.0f ? cross / twice_area * (instance.mirrored ? -1.0f : 1.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
  const glm::vec3 n = instance.normal_to_world * lerp3(mesh.normals);
  const float n_length = glm::length(n);
  hit.normal = n_length > 0.0f ? n / n_length : hit.geometric_normal;
  if (glm::dot(hit.normal, hit.geometric_normal) < 0.0f) hit.normal = -hit.normal;
  const glm::vec4 t0 = mesh.tangents[corner[0]], t1 = mesh.tangents[corner[1]], t2 = mesh.tangents[corner[2]];
  hit.tangent = glm::mat3(instance.to_world) * (b0 * glm::vec3(t0) + b1 * glm::vec3(t1) + b2 * glm::vec3(t2));
  hit.uv = lerp3(mesh.uvs);
  const glm::vec2 e1 = mesh.uvs[corner[1]] - mesh.uvs[corner[0]], e2 = mesh.uvs[corner[2]] - mesh.uvs[corner[0]];
  const float twice_uv_area = std::abs(e1.x * e2.y - e1.y * e2.x);
  hit.uv_per_length = twice_area > 0.0f ? std::sqrt(twice_uv_area / twice_area) : 0.0f;
  return hit;
}

void RenderScene::sphere_hit(const Instance& instance, float radius, glm::vec3 world_point, SurfaceHit& hit) const {
  // The object-space point's direction gives everything as sphere_mesh defines it (graph/scene/
  // primitives.cpp): n = (sin theta sin phi, cos theta, sin theta cos phi), u = phi / 2 pi, v = theta / pi.
  const glm::vec3 local = glm::vec3(instance.to_object * glm::vec4(world_point, 1.0f));
  const float length = glm::length(local);
  const glm::vec3 n = length > 0.0f ? local / length : glm::vec3(0.0f, 1.0f, 0.0f);
  const float two_pi = 2.0f * std::numbers::pi_v<float>, pi = std::numbers::pi_v<float>;
  float phi = std::atan2(n.x, n.z);
  if (phi < 0.0f) phi += two_pi;
  const float theta = std::acos(std::clamp(n.y, -1.0f, 1.0f));
  const float sin_theta = std::sin(theta);
  hit.uv = glm::vec2(phi / two_pi, theta / pi);
  hit.position = glm::vec3(instance.to_world * glm::vec4(radius * n, 1.0f));
  const glm::vec3 normal = glm::normalize(instance.normal_to_world * n);
  hit.geometric_normal = hit.normal = normal;
  const glm::mat3 linear(instance.to_world);
  const glm::vec3 along_phi(std::cos(phi), 0.0f, -std::sin(phi));  // dP/dphi's direction, defined at the poles too
  hit.tangent = linear * along_phi;
  // uv per length: 1 / sqrt of the world area one unit of uv covers, |dP/du x dP/dv|, with
  // dP/du = 2 pi r sin(theta) along_phi and dP/dv = pi r dn/dtheta (at least 1e-3 of the equator's
  // sin(theta), so that the poles' point has a finite footprint).
  const glm::vec3 along_theta(std::cos(theta) * std::sin(phi), -sin_theta, std::cos(theta) * std::cos(phi));
  const float area = glm::length(glm::cross(hit.tangent, linear * along_theta)) * two_pi * pi * radius * radius *
                     std::max(sin_theta, 1e-3f);
  hit.uv_per_length = area > 0.0f ? 1.0f / std::sqrt(area) : 0.0f;
}

EmitterSample RenderScene::sample_emitter(glm::vec3 from, glm::vec3 u) const {
  EmitterSample s;
  if (emitters_.empty()) return s;
  const auto it = std::upper_bound(emitter_cdf_.begin() + 1, emitter_cdf_.end(), double(u.x));
  const size_t k = std::min(size_t(it - emitter_cdf_.begin()) - 1, emitters_.size() - 1);
  const EmitterTriangle& e = emitters_[k];
  // A uniform point on the triangle: the square-root warp of Turk, "Generating Random Points in
  // Triangles" (Graphics Gems, 1990).
  const float r = std::sqrt(u.y);
  const glm::vec3 q = e.p0 + e.edge1 * (r * (1.0f - u.z)) + e.edge2 * (r * u.z);
  const glm::vec3 d = q - from;
  s.distance = glm::length(d);
  if (!(s.distance > 0.0f)) return {};
  s.wi = d / s.distance;
  s.position = q;
  s.normal = e.normal;
  const float cos_light = -glm::dot(e.normal, s.wi);
  if (!(cos_light > 0.0f)) return {};  // its back face: it emits from the front only
  s.radiance = emission_[size_t(e.object)];
  const float pdf_area = luminance(s.radiance) / float(emitter_power_);
  s.pdf = pdf_area * s.distance * s.distance / cos_light;
  return s;
}

float RenderScene::emitter_pdf(const SurfaceHit& hit, glm::vec3 direction) const {
  const glm::vec3 emitted = emission_[size_t(hit.object)];
  const float cos_light = -glm::dot(hit.geometric_normal, direction);
  if (emitter_power_ <= 0.0 || !(cos_light > 0.0f)) return 0.0f;
  return luminance(emitted) / float(emitter_power_) * hit.distance * hit.distance / cos_light;
}

bool RenderScene::occluded(glm::vec3 origin, glm::vec3 direction, float t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit r = make_ray(origin, direction, t_max);
  rtcOccluded1(top_, &context, &r.ray);
  return r.ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace lamina::render
