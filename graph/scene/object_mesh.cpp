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

}  // namespace lamina
