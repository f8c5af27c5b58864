// Built-in shapes as triangle meshes, in glTF's conventions: y up, counter-clockwise front faces,
// outward normals, uv (0, 0) at the image's top-left with u to the right and v downwards, the
// tangent along +u (dP/du) and its w chosen so that cross(normal, tangent) * w points towards
// decreasing v (up in the image): an unmirrored mapping has w = +1.
#pragma once

#include <glm/glm.hpp>

#include "graph/scene/scene.h"

namespace lamina {

// UV sphere centred on the origin: u = longitude (from +z towards +x), v = 0 at the north pole
// (+y) to 1 at the south pole; `segments` around, segments / 2 rings.
TriangleMesh sphere_mesh(double radius, int segments);
// Square in the xz-plane facing +y: u along +x, v along +z.
TriangleMesh plane_mesh(glm::dvec2 size);
// Axis-aligned box centred on the origin; each face has its own 0..1 uv square.
TriangleMesh box_mesh(glm::dvec3 size);
// Torus around the y axis: u around the axis, v around the tube (starting outside, going down);
// `segments` around the axis, segments / 2 (at least 4) around the tube.
TriangleMesh torus_mesh(double major_radius, double minor_radius, int segments);

// The rings across a sphere or a torus of `segments` around, as the meshes above build them.
int sphere_rings(int segments);
int torus_rings(int segments);
// The vertices the built-in shape of `object` has, without building it (0 for a mesh file).
size_t shape_vertices(const SceneObject& object);

}  // namespace lamina
