// lamina render's path tracer against closed forms (a white furnace, a Lambertian plane under a
// point light, a directional light and a uniform sky), against the evaluator's own albedo for
// every example, its three estimators against each other, and its determinism.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <vector>

#include "graph/cpu/pcg32.h"
#include "graph/cpu_test_support.h"
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

// Uniform pairs in [0, 1)^2 from a fixed PCG32 stream.
struct Pcg32Directions {
  cpu::Pcg32 rng{7, 3};
  glm::vec2 next() {
    const float a = rng.uniform();
    return glm::vec2(a, rng.uniform());
  }
};

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
  // Under the sanitisers every second example, and the first whose lobes are wide if that half has
  // none before it: which half holds one changes as examples are added.
  const std::vector<std::filesystem::path> swept = test::swept_example_files(1);
  for (const auto& file : test::example_files()) {
    const cpu::Evaluator material = test::load_evaluator(file);
    const bool wide = peak_density(material) < 64.0f;
    if (std::find(swept.begin(), swept.end(), file) == swept.end() && !(wide && light_sampled == 0)) continue;
    const std::string name = material.program().name;
    CAPTURE(name);
    const Scene scene =
        render_scene_text(example_sphere(file, name, R"({"name": "sky", "type": "environment", "file": "sky.png"})"));
    const render::RenderScene prepared(scene, test::repository_policy());
    const int size = 12;
    const auto inside = interior_pixels(prepared, scene.cameras[0], size);
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

TEST_CASE("a time budget renders passes whose image equals one pass of as many samples, bit for bit") {
  const Scene scene = render_scene_text(
      R"({"format": 1, "materials": ["lambert.json", "../../../examples/materials/aventurine_glass.json"], "cameras": [{"name": "c", "position": [0, 1.5, 4], "look_at": [0, 0.5, 0]}], "lights": [{"name": "sky", "type": "environment", "file": "sky.png"}], "objects": [{"name": "ball", "shape": "sphere", "material": "aventurine_glass", "transform": {"translation": [0, 1, 0]}}, {"name": "floor", "shape": "plane", "size": [6, 6], "material": "grey"}]})");
  const render::RenderScene prepared(scene, test::repository_policy());
  render::RenderOptions options;
  options.width = 24;
  options.height = 16;
  options.seed = 5;
  options.aovs = true;
  auto same = [](const render::RenderResult& a, const render::RenderResult& b) {
    return a.samples == b.samples && a.radiance == b.radiance && a.albedo == b.albedo && a.normal == b.normal;
  };
  // A budget far beyond the cap: passes of 1, 1, 2 and 1 samples.
  options.samples = 5;
  options.time_budget = 600.0;
  const auto passes = render::render(prepared, scene.cameras[0], options);
  CHECK(passes.samples == 5);
  options.time_budget = 0.0;
  CHECK(same(passes, render::render(prepared, scene.cameras[0], options)));

  // A budget that ends the passes before the cap: whatever number of samples fitted.
  options.samples = 1 << 20;
  options.time_budget = 0.2;
  const auto timed = render::render(prepared, scene.cameras[0], options);
  CHECK(timed.samples >= 1);
  options.samples = timed.samples;
  options.time_budget = 0.0;
  CHECK(same(timed, render::render(prepared, scene.cameras[0], options)));
}

// The share of a disk of unit radius left of the line x = u: a straight edge seen through a disk.
double disk_share_left_of(double u) {
  u = std::clamp(u, -1.0, 1.0);
  return 0.5 + (u * std::sqrt(1.0 - u * u) + std::asin(u)) / std::numbers::pi;
}

TEST_CASE("a thin lens keeps the plane in focus sharp and blurs an edge off it into the lens disk's profile") {
  // Looking straight down at the edge x = 0 of a black floor (x < 0) over a uniform sky of radiance 1:
  // the image is black on the left and 1 on the right, the edge between columns 31 and 32.
  auto scene_with = [](const std::string& lens) {
    return render_scene_text(
        R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "down", "position": [0, 4, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "yfov": 10, "aspect": 4, "aperture_radius": 0.2)" +
        lens +
        R"(}], "lights": [{"name": "sky", "type": "environment"}], "objects": [{"name": "floor", "shape": "plane", "size": [40, 40], "material": "black", "transform": {"translation": [-20, 0, 0]}}]})");
  };
  const int width = 64, height = 16;
  render::RenderOptions options;
  options.width = width;
  options.height = height;
  options.samples = 64;
  auto column_means = [&](const Scene& scene) {
    const render::RenderScene prepared(scene, test::repository_policy());
    const auto image = render::render(prepared, scene.cameras[0], options);
    std::vector<double> means(size_t(width), 0.0);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) means[size_t(x)] += average(image.radiance[size_t(y * width + x)]) / height;
    return means;
  };

  SUBCASE("focused on the floor (look_at, by default), every pixel is wholly floor or wholly sky") {
    // Beside the edge, a sample's position rounds to the pixel border now and then (31 + 0.99999994 is
    // 32 in single precision), as a pinhole's would.
    const auto means = column_means(scene_with(""));
    for (int x = 0; x < width; ++x) {
      CAPTURE(x);
      if (x == width / 2 - 1 || x == width / 2)
        CHECK(std::abs(means[size_t(x)] - (x < width / 2 ? 0.0 : 1.0)) < 0.01);
      else
        CHECK(means[size_t(x)] == (x < width / 2 ? 0.0 : 1.0));
    }
  }
  SUBCASE("focused at half the floor's distance, a point of the edge spreads over the lens's disk") {
    // A ray through image coordinate t (the tangent across the view) from lens point x_l meets the floor
    // at x_l (1 - d / f) + t d: it sees the sky where x_l < t d f / (d - f), a disk's share left of a line.
    const double d = 4.0, f = 2.0, r = 0.2;
    const double tan_half = std::tan(5.0 * std::numbers::pi / 180.0), aspect = double(width) / height;
    const auto means = column_means(scene_with(R"(, "focus_distance": 2)"));
    int blurred = 0;
    for (int x = 0; x < width; ++x) {
      double expected = 0.0;
      const int steps = 256;
      for (int k = 0; k < steps; ++k) {
        const double t = (2.0 * (x + (k + 0.5) / steps) / width - 1.0) * tan_half * aspect;
        expected += disk_share_left_of(t * d * f / ((d - f) * r)) / steps;
      }
      const double samples = double(height) * options.samples;
      const double error = std::sqrt(expected * (1.0 - expected) / samples);
      INFO("column " << x << ": " << means[size_t(x)] << ", expected " << expected);
      CHECK(std::abs(means[size_t(x)] - expected) <= 4.0 * error + 1e-6);
      if (expected > 0.02 && expected < 0.98) ++blurred;
    }
    // The circle of confusion's radius, r (d - f) / (d f) = 0.05 in tangent units, is 4.6 pixels.
    CHECK(blurred >= 7);
  }
}

TEST_CASE("a mesh without uv area under a material whose textures read uv is a warning at the object") {
  auto warnings_for = [](const std::string& objects) {
    const Scene scene = render_scene_text(
        R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "c"}], "lights": [{"name": "sky", "type": "environment"}], "objects": [)" +
        objects + "]}");
    Diagnostics warnings;
    const render::RenderScene prepared(scene, test::repository_policy(), &warnings);
    CHECK(warnings.errors().empty());
    std::vector<std::string> lines;
    for (const auto& d : warnings.warnings()) lines.push_back(d.pointer + ": " + d.message);
    return lines;
  };
  auto mesh = [](const std::string& name, const std::string& file, const std::string& material) {
    return R"({"name": ")" + name + R"(", "shape": "mesh", "file": "../scenes/)" + file + R"(", "material": ")" +
           material + R"("})";
  };
  SUBCASE("no texture coordinates at all: one warning however many objects share the mesh and material") {
    const auto lines = warnings_for(mesh("a", "quad_without_uv.gltf", "checkered") + ", " +
                                    mesh("b", "quad_without_uv.gltf", "checkered"));
    REQUIRE(lines.size() == 1);
    CAPTURE(lines[0]);
    CHECK(lines[0].find(R"(/objects/0/file: object "a": its mesh has no texture coordinates)") == 0);
  }
  SUBCASE("some triangles without uv area: how many, of how many") {
    const auto lines = warnings_for(mesh("a", "quad_half_uv.gltf", "checkered"));
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].find("1 of its mesh's 2 triangles have no area in uv") != std::string::npos);
  }
  SUBCASE("nothing to say where the uvs have area, or where the material does not read uv") {
    CHECK(warnings_for(mesh("a", "quad.gltf", "checkered")).empty());
    CHECK(warnings_for(mesh("a", "quad_without_uv.gltf", "grey") + ", " + mesh("b", "quad_without_uv.gltf", "carved"))
              .empty());
    for (const char* shape : {"sphere", "plane", "box", "torus"})
      CHECK(
          warnings_for(R"({"name": "a", "shape": ")" + std::string(shape) + R"(", "material": "checkered"})").empty());
  }
}

TEST_CASE("a coarsely tessellated torus shows no black rim where its shading normals face away from the camera") {
  // A 6-segment torus's interpolated normals face away from the camera near its outline, on triangles
  // the camera sees from the front. Lit by a uniform sky of radiance 1, a white Lambertian surface there
  // sees at least part of the sky: it is not black (measured: 0.68 and more). (The torus shades itself elsewhere, so
  // other pixels may be dark for a reason of their own.)
  const Scene scene = render_scene_text(
      R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "front", "position": [0, 2, 4], "look_at": [0, 0, 0], "yfov": 40, "aspect": 1}], "lights": [{"name": "sky", "type": "environment"}], "objects": [{"name": "ring", "shape": "torus", "major_radius": 1, "minor_radius": 0.5, "material": "white", "segments": 6}]})");
  const render::RenderScene prepared(scene, test::repository_policy());
  const int size = 128;
  render::RenderOptions options;
  options.width = options.height = size;
  options.samples = 8;
  options.max_depth = 1;
  const auto image = render::render(prepared, scene.cameras[0], options);
  int facing_away = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      bool away = true;  // the torus, with its normal facing away, at every corner of the pixel
      for (int corner = 0; corner < 4 && away; ++corner) {
        const auto ray =
            render::camera_ray(scene.cameras[0], size, size, glm::vec2(float(x + corner % 2), float(y + corner / 2)));
        const auto hit = prepared.intersect(ray.origin, ray.direction, 100.0f);
        away = hit && glm::dot(hit->normal, -ray.direction) < 0.0f;
      }
      if (!away) continue;
      ++facing_away;
      CAPTURE(x);
      CAPTURE(y);
      CHECK(average(image.radiance[size_t(y * size + x)]) > 0.3);
    }
  CHECK(facing_away > 0);  // the case this is about occurs
}

TEST_CASE("a sphere renders exact: its outline is a circle whatever its tessellation, and its normal the radius's") {
  // Seen from 4 units, a unit sphere's outline subtends asin(1/4); a 6-segment mesh would cut corners.
  const Scene scene = render_scene_text(
      R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "front", "position": [0, 0, 4], "look_at": [0, 0, 0], "yfov": 40, "aspect": 1}], "lights": [{"name": "sky", "type": "environment"}], "objects": [{"name": "ball", "shape": "sphere", "radius": 1, "material": "white", "segments": 6, "transform": {"rotation_deg": [20, 30, 0]}}]})");
  const render::RenderScene prepared(scene, test::repository_policy());
  const double outline = std::asin(0.25);
  Pcg32Directions directions;
  for (int i = 0; i < 2000; ++i) {
    // Directions within 1.5 times the outline's angle of the view axis.
    const glm::vec2 u = directions.next();
    const double angle = 1.5 * outline * std::sqrt(double(u.x)), phi = 2.0 * std::numbers::pi * double(u.y);
    const vec3 d(float(std::sin(angle) * std::cos(phi)), float(std::sin(angle) * std::sin(phi)),
                 float(-std::cos(angle)));
    if (std::abs(angle - outline) < 1e-4) continue;  // too close to call in single precision
    const auto hit = prepared.intersect(vec3(0.0f, 0.0f, 4.0f), d, 100.0f);
    CAPTURE(angle);
    REQUIRE(hit.has_value() == (angle < outline));
    if (!hit) continue;
    CHECK(glm::length(hit->position) == doctest::Approx(1.0).epsilon(1e-5));
    CHECK(glm::dot(hit->normal, hit->position) == doctest::Approx(1.0).epsilon(1e-5));
    CHECK(glm::dot(hit->geometric_normal, hit->normal) == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(std::abs(glm::dot(glm::normalize(hit->tangent), hit->normal)) < 1e-5);
  }
}

TEST_CASE("an exact sphere's uv and tangent are those of its mesh, so textures lie where the mesh puts them") {
  // Where a ray meets both the exact sphere and its 256-segment mesh (the glTF export's), uv and tangent
  // agree to within the mesh's facets; the footprint's uv-per-length is that of the mesh's triangles.
  const std::string common =
      R"({"format": 1, "materials": ["lambert.json"], "cameras": [{"name": "c"}], "lights": [{"name": "sky", "type": "environment"}], "objects": [{"name": "ball", "shape": "sphere", "radius": 2, "segments": 256, "material": "white", "transform": {"scale": [1, 1.5, 1], "rotation_deg": [10, 0, 0]})";
  const Scene exact_scene = render_scene_text(common + "}]}");
  const Scene mesh_scene = render_scene_text(common + R"(, "emission": [1, 1, 1]}]})");  // emitters stay meshes
  const render::RenderScene exact(exact_scene, test::repository_policy()), mesh(mesh_scene, test::repository_policy());
  Pcg32Directions directions;
  int compared = 0;
  for (int i = 0; i < 500; ++i) {
    const glm::vec2 u = directions.next();
    const vec3 target(4.0f * u.x - 2.0f, 6.0f * u.y - 3.0f, 0.0f);
    const vec3 origin(0.3f, 0.2f, 8.0f);
    const auto a = exact.intersect(origin, glm::normalize(target - origin), 100.0f);
    const auto b = mesh.intersect(origin, glm::normalize(target - origin), 100.0f);
    REQUIRE(a.has_value() == b.has_value());
    if (!a || std::abs(a->uv.x - b->uv.x) > 0.5f) continue;  // none, or across the seam u = 0
    ++compared;
    CHECK(glm::distance(a->uv, b->uv) < 2e-3);
    CHECK(glm::dot(glm::normalize(a->tangent), glm::normalize(b->tangent)) > 0.999);
    CHECK(a->uv_per_length == doctest::Approx(b->uv_per_length).epsilon(0.05));
  }
  CHECK(compared > 100);
}

TEST_CASE("an environment's rotation turns its radiance, its density and its samples about +y") {
  auto image = std::make_shared<LinearImage>();
  image->width = 16;
  image->height = 8;
  cpu::Pcg32 rng(3, 1);
  for (int i = 0; i < image->width * image->height; ++i) image->texels.emplace_back(rng.uniform3() + 0.01f, 1.0f);
  const render::Environment plain(image, vec3(1.0f));
  render::Environment turned(image, vec3(1.0f));
  turned.set_rotation(90.0f);
  // A right-handed quarter turn about +y: x goes to -z, z to x.
  auto turn = [](vec3 d) { return vec3(d.z, d.y, -d.x); };
  CHECK(glm::distance(turn(vec3(1.0f, 0.0f, 0.0f)), vec3(0.0f, 0.0f, -1.0f)) < 1e-6f);
  for (int y = 0; y < image->height; ++y)
    for (int x = 0; x < image->width; ++x) {
      // Each texel's centre, where rounding cannot move a direction into a neighbour.
      const vec3 d = render::equirect_direction(
          glm::vec2((float(x) + 0.5f) / float(image->width), (float(y) + 0.5f) / float(image->height)));
      CHECK(turned.radiance(turn(d)) == plain.radiance(d));
      CHECK(turned.pdf(turn(d)) == doctest::Approx(plain.pdf(d)).epsilon(1e-5));
      CHECK(turned.radiance(d) != plain.radiance(d));  // the texels are all different
    }
  for (int i = 0; i < 100; ++i) {
    const glm::vec2 u(rng.uniform(), rng.uniform());
    const auto a = plain.sample(u), b = turned.sample(u);
    CHECK(glm::distance(b.wi, turn(a.wi)) < 1e-5f);
    CHECK(b.pdf == a.pdf);
    CHECK(b.radiance == a.radiance);
  }
}

TEST_CASE("under green light a fluorescent sphere glows red as its BRDF's matrix says, a plain one stays green") {
  // A directional green light 30 degrees from the camera's axis: at the sphere's centre pixel the
  // radiance is F(wi, wo) (0, E, 0) cos 30, F the matrix a fluorescent base makes of the BRDF.
  const std::string light =
      R"({"name": "green", "type": "directional", "direction": [-0.5, 0, -0.8660254], "color": [0, 1, 0], "intensity": 3})";
  const int size = 33;
  for (const char* name : {"fluorescent_card", "orange_card"}) {
    CAPTURE(name);
    const std::string file = std::string(name) == "fluorescent_card"
                                 ? "../../../examples/materials/fluorescent_card.json"
                                 : "../../../examples/fluorescence/orange_card.json";
    const Scene scene = render_scene_text(sphere_scene(file, name, light));
    const render::RenderScene prepared(scene, test::repository_policy());
    render::RenderOptions options;
    options.width = options.height = size;
    options.samples = 16;
    const auto image = render::render(prepared, scene.cameras[0], options);
    const vec3 centre = image.radiance[size_t(size / 2) * size_t(size) + size_t(size / 2)];
    const cpu::Evaluator material =
        test::load_evaluator(test::source_dir() / "tests/data/render" / std::filesystem::path(file));
    const vec3 wi(0.5f, 0.0f, 0.8660254f), wo(0.0f, 0.0f, 1.0f);
    const vec3 expected = material.eval(ShadingContext{}, wi, wo, vec3(0.0f, 3.0f, 0.0f)) * wi.z;
    INFO("rendered " << centre.x << " " << centre.y << " " << centre.z << ", expected " << expected.x << " "
                     << expected.y << " " << expected.z);
    for (int c = 0; c < 3; ++c)
      CHECK(std::abs(double(centre[c]) - double(expected[c])) <= 0.02 * double(expected.y) + 1e-6);
    if (std::string(name) == "fluorescent_card")
      CHECK(centre.x > centre.y);  // the body's red outshines the light's own green
    else
      CHECK(centre.x == 0.0f);  // without fluorescence nothing red comes of green light
  }
}

}  // namespace
}  // namespace lamina
