// lamina render's path tracer against closed forms (a white furnace, a Lambertian plane under a
// point light, a directional light and a uniform sky), against the evaluator's own albedo for
// every example, its three estimators against each other, and its determinism.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "graph/cpu/pcg32.h"
#include "graph/document.h"
#include "graph/load.h"
#include "test_support.h"
#include "tools/render/path_tracer.h"

namespace lamina {
namespace {

using glm::vec3;

// A scene read from `text` as if it were tests/data/render/scene.json, so that it names the test
// materials (and the examples) by paths relative to that folder.
Scene render_scene_text(const std::string& text) {
  Diagnostics diagnostics;
  const auto file = test::source_dir() / "tests/data/render/scene.json";
  Scene scene = read_scene(text, file.string(), diagnostics, test::repository_policy());
  for (const auto& d : diagnostics.errors()) FAIL_CHECK(format(d));
  REQUIRE(diagnostics.ok());
  return scene;
}

// The mean of `values` and its standard error, treating them as independent draws.
struct MeanError {
  double mean = 0.0, error = 0.0;
};
MeanError mean_error(const std::vector<double>& values) {
  MeanError m;
  for (double v : values) m.mean += v;
  m.mean /= double(values.size());
  double variance = 0.0;
  for (double v : values) variance += (v - m.mean) * (v - m.mean);
  variance /= double(values.size() - 1);
  m.error = std::sqrt(variance / double(values.size()));
  return m;
}

double average(vec3 c) { return (double(c.x) + double(c.y) + double(c.z)) / 3.0; }

// A camera 4 units in front of a unit sphere at the origin, framing it tightly.
const char* kSphereCamera =
    R"({"name": "front", "position": [0, 0, 4], "look_at": [0, 0, 0], "yfov": 20, "aspect": 1})";

std::string sphere_scene(const std::string& material_file, const std::string& material, const std::string& lights) {
  return R"({"format": 1, "materials": [")" + material_file + R"("], "cameras": [)" + kSphereCamera +
         R"(], "lights": [)" + lights +
         R"(], "objects": [{"name": "ball", "shape": "sphere", "radius": 1, "material": ")" + material +
         R"(", "segments": 128}]})";
}

// Pixels whose four corners all see the sphere: inside its outline, away from the background.
std::vector<size_t> interior_pixels(const render::RenderScene& scene, const Camera& camera, int size) {
  std::vector<size_t> inside;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      bool all = true;
      for (int corner = 0; corner < 4 && all; ++corner) {
        const auto ray =
            render::camera_ray(camera, size, size, glm::vec2(float(x + corner % 2), float(y + corner / 2)));
        all = scene.intersect(ray.origin, ray.direction, 100.0f).has_value();
      }
      if (all) inside.push_back(size_t(y) * size_t(size) + size_t(x));
    }
  return inside;
}

TEST_CASE("a white Lambertian sphere under a uniform sky shows the sky's radiance, by every estimator") {
  const Scene scene = render_scene_text(
      sphere_scene("lambert.json", "white", R"({"name": "sky", "type": "environment", "color": [0.7, 0.7, 0.7]})"));
  const render::RenderScene prepared(scene, test::repository_policy());
  const int size = 24;
  const auto inside = interior_pixels(prepared, scene.cameras[0], size);
  REQUIRE(inside.size() > size_t(size * size / 3));
  for (auto estimator : {render::Estimator::Mis, render::Estimator::LightSampling, render::Estimator::BrdfSampling}) {
    render::RenderOptions options;
    options.width = options.height = size;
    options.samples = 16;
    options.estimator = estimator;
    const auto image = render::render(prepared, scene.cameras[0], options);
    std::vector<double> values;
    for (size_t i : inside) values.push_back(average(image.radiance[i]));
    const MeanError m = mean_error(values);
    INFO("estimator " << int(estimator) << ": " << m.mean << " +- " << m.error);
    CHECK(std::abs(m.mean - 0.7) < 5.0 * m.error + 1e-6);
    // Cosine sampling makes each path's weight 1: what varies is where shading and geometric normals differ.
    if (estimator == render::Estimator::BrdfSampling) CHECK(m.error < 1e-3 * m.mean);
  }
}

// The irradiance at floor point p (the plane y = 0, normal +y) from the light of a test case.
using Irradiance = std::function<double(glm::dvec3 p)>;

// Renders the grey (0.5) plane from 2 units above, looking straight down, under `lights` (and the
// objects `more`), by `estimator`, and compares each pixel with rho E / pi averaged over 4 x 4 points
// across it: the worst relative error of a pixel, and that of the image's mean.
struct PlaneError {
  double worst = 0.0, mean = 0.0;
};
PlaneError plane_error(const std::string& lights, const std::string& more, const Irradiance& irradiance,
                       render::Estimator estimator, int samples) {
  const Scene scene = render_scene_text(
      R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "down", "position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "yfov": 60, "aspect": 1}], "objects": [{"name": "floor", "shape": "plane", "size": [40, 40], "material": "grey"})" +
      more + R"(], "lights": [)" + lights + "]}");
  const render::RenderScene prepared(scene, test::repository_policy());
  const int size = 16;
  render::RenderOptions options;
  options.width = options.height = size;
  options.samples = samples;
  options.estimator = estimator;
  options.max_depth = 1;  // direct light only: the closed forms know nothing of interreflection
  const auto image = render::render(prepared, scene.cameras[0], options);
  PlaneError error;
  double found_sum = 0.0, expected_sum = 0.0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      double expected = 0.0;
      for (int s = 0; s < 16; ++s) {
        const auto ray = render::camera_ray(
            scene.cameras[0], size, size,
            glm::vec2(float(x) + (float(s % 4) + 0.5f) / 4.0f, float(y) + (float(s / 4) + 0.5f) / 4.0f));
        const glm::dvec3 p = glm::dvec3(ray.origin) + glm::dvec3(ray.direction) * (2.0 / -double(ray.direction.y));
        expected += 0.5 * irradiance(p) / std::numbers::pi / 16.0;
      }
      const double found = average(image.radiance[size_t(y * size + x)]);
      error.worst = std::max(error.worst, std::abs(found / expected - 1.0));
      found_sum += found;
      expected_sum += expected;
    }
  error.mean = std::abs(found_sum / expected_sum - 1.0);
  return error;
}

// A uniform spherical cap of radiance L seen within angle a, entirely above a surface, gives it
// E = pi L sin^2(a) cos(theta) (theta: between the cap's centre and the normal), exactly.
TEST_CASE("a Lambertian plane under a point, a directional, a disk and a spherical light shows rho E cos / pi") {
  const glm::dvec3 bulb(0.5, 3.0, 0.0);
  const Irradiance point = [&](glm::dvec3 p) {
    const glm::dvec3 d = bulb - p;
    const double r = glm::length(d);
    return 90.0 * (d.y / r) / (r * r);
  };
  const Irradiance directional = [](glm::dvec3) { return 4.0 * glm::normalize(glm::dvec3(-1.0, 2.0, -0.5)).y; };
  // The lamp: radius 0.25 at (0.5, 2.6, 0.3), behind the camera, emitting 40 (pi L sin^2 a = pi L r^2 / d^2).
  const glm::dvec3 ball(0.5, 2.6, 0.3);
  const Irradiance sphere = [&](glm::dvec3 p) {
    const glm::dvec3 d = ball - p;
    const double r = glm::length(d);
    return std::numbers::pi * 40.0 * 0.0625 / (r * r) * (d.y / r);
  };
  const std::string bulb_light = R"({"name": "bulb", "type": "point", "position": [0.5, 3, 0], "intensity": 90})";
  const std::string sun = R"({"name": "sun", "type": "directional", "direction": [1, -2, 0.5], "intensity": 4)";
  const std::string ball_object =
      R"(, {"name": "lamp", "shape": "sphere", "radius": 0.25, "segments": 256, "material": "black", "emission": [40, 40, 40], "transform": {"translation": [0.5, 2.6, 0.3]}})";
  CHECK(plane_error(bulb_light, "", point, render::Estimator::Mis, 64).worst < 0.02);
  CHECK(plane_error(sun + "}", "", directional, render::Estimator::Mis, 64).worst < 0.02);
  // A sun of 5 degrees and a lamp: every estimator finds them (light samples on them, BRDF samples
  // that escape into the sun's disk or meet the lamp). Where a pixel's estimate stays noisy (BRDF
  // sampling finds both rarely; light samples land on the lamp's far side half the time and near its
  // outline often), the image's mean is compared instead of every pixel.
  for (auto estimator : {render::Estimator::Mis, render::Estimator::LightSampling, render::Estimator::BrdfSampling}) {
    CAPTURE(int(estimator));
    const bool rare = estimator == render::Estimator::BrdfSampling;
    const PlaneError disk =
        plane_error(sun + R"(, "angular_radius": 5})", "", directional, estimator, rare ? 2048 : 64);
    const PlaneError lamp = plane_error("", ball_object, sphere, estimator, rare ? 2048 : 256);
    INFO("disk: worst pixel " << disk.worst << ", mean " << disk.mean << "; lamp: worst pixel " << lamp.worst
                              << ", mean " << lamp.mean);
    CHECK((rare ? disk.mean < 0.05 : disk.worst < 0.03));
    CHECK(lamp.mean < (rare ? 0.05 : 0.02));
  }
}

TEST_CASE("a Lambertian plane under a uniform sky shows rho times the sky") {
  const Scene scene = render_scene_text(
      R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "down", "position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "yfov": 40, "aspect": 1}], "objects": [{"name": "floor", "shape": "plane", "size": [40, 40], "material": "grey"}], "lights": [{"name": "sky", "type": "environment", "intensity": 2}]})");
  const render::RenderScene prepared(scene, test::repository_policy());
  render::RenderOptions options;
  options.width = options.height = 16;
  options.samples = 16;
  const auto image = render::render(prepared, scene.cameras[0], options);
  std::vector<double> values;
  for (const vec3& c : image.radiance) values.push_back(average(c));
  const MeanError m = mean_error(values);
  INFO(m.mean << " +- " << m.error);
  CHECK(std::abs(m.mean - 1.0) < 5.0 * m.error + 1e-6);
}

std::string example_sphere(const std::filesystem::path& file, const std::string& material, const std::string& lights) {
  return sphere_scene("../../../examples/materials/" + file.filename().string(), material, lights);
}

// The image's mean over `pixels`, and its standard error across them.
MeanError image_mean(const std::vector<vec3>& image, const std::vector<size_t>& pixels) {
  std::vector<double> values;
  for (size_t i : pixels) values.push_back(average(image[i]));
  return mean_error(values);
}

TEST_CASE("every example on a sphere under a uniform sky reflects the sky times its albedo") {
  for (const auto& file : test::swept_example_files(0)) {
    const std::string name = test::load_evaluator(file).program().name;
    CAPTURE(name);
    const Scene scene = render_scene_text(example_sphere(file, name, R"({"name": "sky", "type": "environment"})"));
    const render::RenderScene prepared(scene, test::repository_policy());
    const int size = 12;
    const auto inside = interior_pixels(prepared, scene.cameras[0], size);
    render::RenderOptions options;
    options.width = options.height = size;
    options.samples = 16;
    options.aovs = true;  // the first hit's albedo, by the evaluator's quadrature
    const auto image = render::render(prepared, scene.cameras[0], options);
    const MeanError radiance = image_mean(image.radiance, inside), albedo = image_mean(image.albedo, inside);
    INFO("radiance " << radiance.mean << " +- " << radiance.error << ", albedo " << albedo.mean);
    CHECK(std::abs(radiance.mean - albedo.mean) < 5.0 * radiance.error + 0.02 * albedo.mean);
  }
}

// The largest density the material's sampler reaches at its points: above 64 per steradian (a lobe
// narrower than about 8 degrees), a lobe is too narrow for light samples alone to find it within a test's
// budget (their estimate is unbiased, but its rare large values make the error of a short run
// meaningless), so only BRDF sampling and MIS are compared there.
float peak_density(const cpu::Evaluator& material) {
  float peak = 0.0f;
  cpu::Pcg32 rng(7, 0);
  for (int i = 0; i < 256; ++i) {
    ShadingContext ctx;
    ctx.uv = glm::vec2(rng.uniform(), rng.uniform());
    const cpu::ShadingPoint point = material.bind(ctx);
    const float c = rng.uniform();
    const vec3 wo(std::sqrt(1.0f - c * c), 0.0f, c);
    peak = std::max(peak, point.sample(wo, glm::vec2(rng.uniform(), rng.uniform()), rng.uniform()).pdf);
  }
  return peak;
}

TEST_CASE(
    "BRDF sampling and MIS give the same image of every example under an environment map, and so does light sampling "
    "where its lobes are wide") {
  int light_sampled = 0;
  for (const auto& file : test::swept_example_files(1)) {
    const cpu::Evaluator material = test::load_evaluator(file);
    const std::string name = material.program().name;
    CAPTURE(name);
    const Scene scene =
        render_scene_text(example_sphere(file, name, R"({"name": "sky", "type": "environment", "file": "sky.png"})"));
    const render::RenderScene prepared(scene, test::repository_policy());
    const int size = 12;
    const auto inside = interior_pixels(prepared, scene.cameras[0], size);
    const bool wide = peak_density(material) < 64.0f;
    light_sampled += wide ? 1 : 0;
    MeanError found[3];
    for (int e = 0; e < 3; ++e) {
      if (e == int(render::Estimator::LightSampling) && !wide) continue;
      render::RenderOptions options;
      options.width = options.height = size;
      options.samples = 32;
      options.seed = uint64_t(e);
      options.estimator = render::Estimator(e);
      found[e] = image_mean(render::render(prepared, scene.cameras[0], options).radiance, inside);
    }
    for (int e = 1; e < 3; ++e) {
      if (e == int(render::Estimator::LightSampling) && !wide) continue;
      INFO("MIS " << found[0].mean << " +- " << found[0].error << ", estimator " << e << ": " << found[e].mean << " +- "
                  << found[e].error);
      CHECK(std::abs(found[e].mean - found[0].mean) < 5.0 * std::hypot(found[0].error, found[e].error));
    }
  }
  MESSAGE(light_sampled << " examples also compared with light sampling alone");
  CHECK(light_sampled > 0);
}

TEST_CASE("a glTF mesh file renders as its triangles, mirrored or not, under its node transforms") {
  // tests/data/scenes/quad.gltf: a 2 x 2 quad centred on x = 1 (its node's scale and translation);
  // quad_mirrored.gltf: a 1 x 1 quad at the origin, mirrored by a negative scale. Seen head on from
  // 1.5 times its width under a uniform sky, each shows rho times the sky in the middle of the image
  // (cosine sampling of a Lambertian surface that sees the whole sky is exact) and the sky around it.
  struct Quad {
    const char* file;
    double centre_x, width;
  };
  for (const Quad& quad : {Quad{"quad.gltf", 1.0, 2.0}, Quad{"quad_mirrored.gltf", 0.0, 1.0}}) {
    CAPTURE(quad.file);
    const std::string x = std::to_string(quad.centre_x), z = std::to_string(1.5 * quad.width);
    const Scene scene = render_scene_text(
        R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "c", "position": [)" + x + ", 0, " + z +
        R"(], "look_at": [)" + x +
        R"(, 0, 0], "yfov": 60, "aspect": 1}], "lights": [{"name": "sky", "type": "environment"}], "objects": [{"name": "quad", "shape": "mesh", "file": "../scenes/)" +
        quad.file + R"(", "material": "grey"}]})");
    const render::RenderScene prepared(scene, test::repository_policy());
    render::RenderOptions options;
    options.width = options.height = 16;
    options.samples = 4;
    options.estimator = render::Estimator::BrdfSampling;
    const auto image = render::render(prepared, scene.cameras[0], options);
    // The image's half-height is tan(30 deg) 1.5 = 0.87 widths: the quad covers its middle 58%.
    for (const size_t pixel : {8 * 16 + 8, 5 * 16 + 10, 10 * 16 + 6})
      CHECK(average(image.radiance[pixel]) == doctest::Approx(0.5).epsilon(1e-3));
    CHECK(average(image.radiance[0]) == doctest::Approx(1.0).epsilon(1e-6));
  }
}

TEST_CASE("the same seed gives the same image bit for bit whatever the thread count, and another seed another") {
  const Scene scene = render_scene_text(
      R"({"format": 1, "materials": ["lambert.json", "../../../examples/materials/aventurine_glass.json"], "cameras": [{"name": "c", "position": [0, 1.5, 4], "look_at": [0, 0.5, 0]}], "lights": [{"name": "sky", "type": "environment", "file": "sky.png"}, {"name": "bulb", "type": "point", "position": [2, 3, 2], "intensity": 20}], "objects": [{"name": "ball", "shape": "sphere", "material": "aventurine_glass", "transform": {"translation": [0, 1, 0]}}, {"name": "floor", "shape": "plane", "size": [6, 6], "material": "grey"}]})");
  const render::RenderScene prepared(scene, test::repository_policy());
  render::RenderOptions options;
  options.width = 24;
  options.height = 16;
  options.samples = 4;
  options.seed = 11;
  std::vector<std::vector<vec3>> images;
  for (int threads : {1, 2, 5}) {
    options.threads = threads;
    images.push_back(render::render(prepared, scene.cameras[0], options).radiance);
  }
  CHECK(images[0] == images[1]);
  CHECK(images[0] == images[2]);
  options.seed = 12;
  CHECK(render::render(prepared, scene.cameras[0], options).radiance != images[0]);
}

}  // namespace
}  // namespace lamina
