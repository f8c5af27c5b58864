// lamina's path tracer: unidirectional paths from a pinhole camera, next-event estimation towards
// every punctual light and the environment, BRDF sampling by the material's own `sample`, and the
// two combined by multiple importance sampling with the power heuristic (Veach 1997, sec. 9.2.1,
// eq. 9.13), Russian roulette after a few bounces. Every hit binds the material once
// (Evaluator::bind) with the hit's uv, position, frame, view distance and pixel footprint (a ray
// cone), so the image shows exactly what the library evaluates.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "graph/scene/scene.h"
#include "tools/render/render_scene.h"

namespace lamina::render {

// How light is found at a hit. All three are unbiased estimates of the same image; they differ in
// noise, and their agreement is a test of sample() against pdf() and eval().
enum class Estimator {
  Mis,            // light sampling and BRDF sampling, weighted by the power heuristic
  LightSampling,  // the environment through light samples only (rays that escape after a bounce add nothing)
  BrdfSampling,   // the environment through escaping rays only (no light samples towards it)
};

struct RenderOptions {
  int width = 480;
  int height = 320;
  int samples = 16;          // per pixel; with a time budget, the most it may take
  double time_budget = 0.0;  // seconds of path tracing (after the scene's preparation); 0: none
  uint64_t seed = 0;         // the same seed gives the same image, bit for bit, whatever the thread count
  int threads = 0;           // 0: one per core
  int max_depth = 8;         // bounces: surfaces a path is shaded at (1: direct light only, and what one bounce shows)
  int roulette_depth = 3;    // Russian roulette from this many bounces on
  Estimator estimator = Estimator::Mis;
  bool aovs = false;  // also the first hit's albedo and normal, for denoisers
  // Called now and then from the thread that called render, with the share of the work done (of the
  // samples, or of the time budget).
  std::function<void(double)> progress;
};

struct RenderResult {
  int width = 0, height = 0;
  int samples = 0;                  // per pixel: options.samples, or what fitted in the time budget
  std::vector<glm::vec3> radiance;  // linear, rows from the top, the mean over the pixel's samples
  std::vector<glm::vec3> albedo;    // with aovs: the first hit's directional albedo (0 where a ray escapes),
                                    // over the pixel's first 4 samples
  std::vector<glm::vec3> normal;    // with aovs: the first hit's shading normal, world space
  // Counts of what was traced, for throughput reports.
  uint64_t camera_rays = 0, shadow_rays = 0, bounce_rays = 0;
};

// The camera's ray through pixel position `pixel` (in pixels from the top-left corner of a width x
// height image): its origin, its direction (unit), and the angle one pixel subtends (the ray cone's
// spread). A camera with an aperture is a thin lens: the ray starts at a point of the lens drawn
// from `lens` (two uniform numbers; a pinhole ignores them) and passes through the point the
// pinhole ray meets on the plane in focus.
struct CameraRay {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  float spread = 0.0f;
};
CameraRay camera_ray(const Camera& camera, int width, int height, glm::vec2 pixel, glm::vec2 lens = glm::vec2(0.0f));

// Renders `samples` per pixel, or with a time budget, passes of samples until the next would not
// fit: each pixel carries its random stream from pass to pass, so an image of N samples is the
// same, bit for bit, however the passes divided them.
RenderResult render(const RenderScene& scene, const Camera& camera, const RenderOptions& options);

}  // namespace lamina::render
