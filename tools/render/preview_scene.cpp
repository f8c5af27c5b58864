#include "tools/render/preview_scene.h"

#include <cmath>
#include <numbers>

#include "graph/load.h"
#include "tools/render/environment.h"

namespace lamina::render {

namespace {

// Two greys a stop apart, in squares of half the sphere's radius: scale and tilt read at once.
const char* kFloorMaterial = R"({"format": 1, "materials": [{"name": "lamina_preview_floor",
  "source": "lamina preview: the floor under the sphere", "surface": "@floor", "nodes": [
  {"id": "floor", "type": "substrate/lambert", "albedo": "@squares"},
  {"id": "squares", "type": "texture/checker", "color_a": [0.16, 0.16, 0.16], "color_b": [0.32, 0.32, 0.32],
   "scale": [40, 40]}]}]})";
constexpr double kFloorSize = 20.0;  // scene units: 40 squares of 0.5

const Document& floor_document() {
  static const Document document = [] {
    CheckedFile checked = check_text(kFloorMaterial, "lamina preview floor");
    if (!checked.ok()) throw std::logic_error("the preview's floor material does not check");
    return checked.document;
  }();
  return document;
}

}  // namespace

Scene preview_scene(const Document& materials, const std::filesystem::path& material_file,
                    const std::string& material) {
  Scene scene;
  scene.path = material_file.string();
  scene.policy = materials.policy.with_default_root(material_file);
  scene.material_files.push_back(MaterialFileRef{material_file.string(), material_file, materials});
  scene.material_files.push_back(MaterialFileRef{"lamina preview floor", {}, floor_document()});

  SceneObject ball;
  ball.name = "ball";
  ball.shape = ShapeType::Sphere;
  ball.segments = 128;
  ball.material = material;
  ball.transform.translation = glm::dvec3(0.0, 1.0, 0.0);
  scene.objects.push_back(ball);
  SceneObject floor;
  floor.name = "floor";
  floor.shape = ShapeType::Plane;
  floor.plane_size = glm::dvec2(kFloorSize);
  floor.material = "lamina_preview_floor";
  scene.objects.push_back(floor);

  Camera camera;
  camera.name = "preview";
  camera.position = glm::dvec3(0.0, 1.9, 4.6);
  camera.look_at = glm::dvec3(0.0, 0.85, 0.0);
  camera.yfov_deg = 30.0;
  camera.aspect = 1.0;
  scene.cameras.push_back(camera);
  return scene;
}

std::shared_ptr<const LinearImage> studio_environment(int width) {
  auto image = std::make_shared<LinearImage>();
  image->width = width;
  image->height = width / 2;
  image->texels.resize(size_t(image->width) * size_t(image->height));
  // Where the lights are, as unit directions towards them: the softbox up and to the left of the
  // camera's view, the strip behind the sphere on the right.
  const glm::vec3 softbox = glm::normalize(glm::vec3(-0.55f, 0.65f, 0.55f));
  const glm::vec3 strip = glm::normalize(glm::vec3(0.7f, 0.25f, -0.6f));
  for (int y = 0; y < image->height; ++y)
    for (int x = 0; x < image->width; ++x) {
      const glm::vec3 d = equirect_direction(
          glm::vec2((float(x) + 0.5f) / float(image->width), (float(y) + 0.5f) / float(image->height)));
      glm::vec3 radiance;
      if (d.y >= 0.0f) {  // a sky from 0.35 at the horizon to 0.9 overhead, slightly cool
        const float t = std::sqrt(d.y);
        radiance = glm::mix(glm::vec3(0.35f, 0.35f, 0.37f), glm::vec3(0.8f, 0.85f, 0.95f), t);
      } else {
        radiance = glm::vec3(0.06f, 0.055f, 0.05f);  // a dark ground beyond the floor
      }
      // The softbox: radiance 24 within 11 degrees of its centre (about 2.8 lux at the sphere);
      // the strip: radiance 6 within 6 degrees of its centre.
      if (glm::dot(d, softbox) > std::cos(11.0f * std::numbers::pi_v<float> / 180.0f)) radiance = glm::vec3(24.0f);
      if (glm::dot(d, strip) > std::cos(6.0f * std::numbers::pi_v<float> / 180.0f))
        radiance = glm::vec3(6.0f, 6.0f, 5.6f);
      image->texels[size_t(y) * size_t(image->width) + size_t(x)] = glm::vec4(radiance, 1.0f);
    }
  return image;
}

}  // namespace lamina::render
