// Completing a triangle mesh for shading: normals and tangents where a file has none.
#pragma once

#include "graph/scene/scene.h"

namespace lamina {

// A triangle whose uv edges' determinant (twice its area in uv) is below this has no area in uv: its
// uvs give no tangent direction (generate_tangents), and the renderer warns where textures read them.
constexpr double kLeastUvDeterminant = 1e-20;

// Area-weighted vertex normals: smooth where triangles share vertices, flat where they do not.
void generate_normals(TriangleMesh& mesh);
// Tangents along +u from each triangle's uv derivatives, accumulated per vertex and made
// orthogonal to the normal; w as primitives.h states. Vertices whose uvs give no direction get
// any unit tangent orthogonal to the normal, with w = +1. Needs normals and uvs.
void generate_tangents(TriangleMesh& mesh);

}  // namespace lamina
