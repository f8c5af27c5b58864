#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "graph/scene/scene.h"

namespace lamina {

namespace {

constexpr double kSpacing = 2.5;  // centre to centre: unit spheres with half a diameter between them
constexpr double kMargin = 0.5;   // around the outer spheres, in scene units

}  // namespace

Scene sample_sheet(const Document& materials, const std::filesystem::path& material_file, int columns) {
  Scene scene;
  scene.path = material_file.string();
  scene.policy = materials.policy.with_default_root(material_file);
  scene.material_files.push_back(MaterialFileRef{material_file.string(), material_file, materials});
  size_t count = materials.materials.size();
  size_t per_row = static_cast<size_t>(std::max(1, columns));
  size_t used_columns = std::max<size_t>(1, std::min(count, per_row));
  size_t rows = std::max<size_t>(1, (count + per_row - 1) / per_row);
  // The grid is centred on the origin in the xy-plane, first row on top.
  double left = -kSpacing * static_cast<double>(used_columns - 1) / 2.0;
  double top = kSpacing * static_cast<double>(rows - 1) / 2.0;
  for (size_t i = 0; i < count; ++i) {
    SceneObject o;
    o.name = materials.materials[i].name;
    o.material = materials.materials[i].name;
    o.label = materials.materials[i].name;
    o.shape = ShapeType::Sphere;
    o.radius = 1.0;
    o.transform.translation = glm::dvec3(left + kSpacing * static_cast<double>(i % per_row),
                                         top - kSpacing * static_cast<double>(i / per_row), 0.0);
    scene.objects.push_back(std::move(o));
  }

  Camera camera;
  camera.name = "sheet";
  camera.yfov_deg = 35.0;
  camera.aspect = 1.5;
  double half_width = -left + 1.0 + kMargin, half_height = top + 1.0 + kMargin;
  double tan_half = std::tan(glm::radians(camera.yfov_deg) / 2.0);
  // Far enough that the grid's half-height and half-width both fit; the spheres' front is one
  // radius nearer than the plane of their centres.
  double distance = std::max(half_height / tan_half, half_width / (tan_half * camera.aspect)) + 1.0;
  camera.position = glm::dvec3(0.0, 0.0, distance);
  camera.look_at = glm::dvec3(0.0);
  camera.znear = 0.05;
  camera.zfar = distance * 4.0;
  scene.cameras.push_back(camera);

  // Key: a point light above, left and in front. Its intensity [cd] gives about 3 lux at the
  // grid's centre (E = I / d^2), a bright indoor key; the fill is a third of that, from the right.
  Light key;
  key.name = "key";
  key.type = LightType::Point;
  key.position = glm::dvec3(-half_width, half_height + 2.0, distance * 0.75);
  key.intensity = 3.0 * glm::dot(key.position, key.position);
  scene.lights.push_back(key);
  Light fill;
  fill.name = "fill";
  fill.type = LightType::Directional;
  fill.direction = glm::normalize(glm::dvec3(-1.0, -0.5, -1.0));
  fill.intensity = 1.0;
  scene.lights.push_back(fill);
  return scene;
}

}  // namespace lamina
