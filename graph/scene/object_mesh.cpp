#include "graph/number_text.h"
#include "graph/scene/mesh_file.h"
#include "graph/scene/primitives.h"
#include "graph/scene/scene.h"

namespace lamina {

TriangleMesh object_mesh(const SceneObject& object, const AssetPolicy& policy) {
  switch (object.shape) {
    case ShapeType::Sphere: return sphere_mesh(object.radius, object.segments);
    case ShapeType::Plane: return plane_mesh(object.plane_size);
    case ShapeType::Box: return box_mesh(object.box_size);
    case ShapeType::Torus: return torus_mesh(object.major_radius, object.minor_radius, object.segments);
    case ShapeType::Mesh: return load_mesh_file(object.mesh_reference, policy);
  }
  return {};
}

std::string geometry_key(const SceneObject& o) {
  // Shortest round-trip text: sizes that differ in any bit give different keys.
  auto n = [](double v) { return number_text(v); };
  switch (o.shape) {
    case ShapeType::Sphere: return "sphere " + n(o.radius) + " " + std::to_string(o.segments);
    case ShapeType::Plane: return "plane " + n(o.plane_size.x) + " " + n(o.plane_size.y);
    case ShapeType::Box: return "box " + n(o.box_size.x) + " " + n(o.box_size.y) + " " + n(o.box_size.z);
    case ShapeType::Torus:
      return "torus " + n(o.major_radius) + " " + n(o.minor_radius) + " " + std::to_string(o.segments);
    case ShapeType::Mesh: return "mesh " + o.resolved_mesh_file.string();
  }
  return {};
}

}  // namespace lamina
