#include "tools/render/path_tracer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "graph/cpu/frame.h"
#include "graph/cpu/pcg32.h"
#include "graph/parallel.h"

namespace lamina::render {

namespace {

using glm::vec2;
using glm::vec3;

// The power heuristic with beta = 2 (Veach 1997, eq. 9.13) for one sample of each strategy.
float power_heuristic(float pdf_this, float pdf_other) {
  const float a = pdf_this * pdf_this, b = pdf_other * pdf_other;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

float max_component(vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

// The density of a direction drawn uniformly within a cone of half-angle acos(cos_radius).
float cone_pdf(float cos_radius) { return 1.0f / (2.0f * std::numbers::pi_v<float> * (1.0f - cos_radius)); }

// How far a secondary ray starts off the surface, along the geometric normal: well beyond the
// rounding of the hit's coordinates, so that it does not find its own triangle again.
vec3 offset_origin(vec3 position, vec3 geometric_normal, vec3 direction) {
  const float scale =
      1.0e-4f * (1.0f + std::max(std::abs(position.x), std::max(std::abs(position.y), std::abs(position.z))));
  return position + geometric_normal * (glm::dot(direction, geometric_normal) >= 0.0f ? scale : -scale);
}

// Whether the segment between two surface points is blocked, each end moved off its surface towards
// the other (offset_origin): a segment between the exact points grazes the surfaces it ends on.
bool segment_blocked(const RenderScene& scene, vec3 from, vec3 from_normal, vec3 to, vec3 to_normal) {
  const vec3 a = offset_origin(from, from_normal, to - from), b = offset_origin(to, to_normal, from - to);
  const vec3 d = b - a;
  const float length = glm::length(d);
  return length > 0.0f && scene.occluded(a, d / length, length);
}

// KHR_lights_punctual's recommended attenuation of a point or spot light at `distance` (the range's
// smooth window, and the spot's cone with a squared linear falloff), without the 1 / d^2.
float punctual_attenuation(const PunctualLight& light, float distance, vec3 towards_point) {
  float a = 1.0f;
  if (light.range > 0.0f) {
    const float r = distance / light.range;
    a = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
    a *= a;
  }
  if (light.type == LightType::Spot) {
    const float scale = 1.0f / std::max(0.001f, light.cos_inner - light.cos_outer);
    const float t = std::clamp((glm::dot(towards_point, light.direction) - light.cos_outer) * scale, 0.0f, 1.0f);
    a *= t * t;
  }
  return a;
}

// A pixel's footprint in uv: the ray cone's width where it meets the surface, stretched by the
// obliquity of the hit (a cone meeting a surface at angle theta covers 1 / cos theta more of it, up to
// 20 times), in uv units through the triangle's uv-per-length.
float uv_footprint(float cone_width, float cos_view, float uv_per_length) {
  return cone_width / std::max(std::abs(cos_view), 0.05f) * uv_per_length;
}

// Near the silhouette of a coarse mesh the interpolated normal can face away from a viewer who sees the
// triangle's front: the material, seen from below its horizon, would be black there. Such a normal is
// turned towards the viewer, in the plane of the two, until it sees them at kLeastShadingCos.
constexpr float kLeastShadingCos = 0.01f;
vec3 facing_normal(vec3 n, vec3 wo) {
  const float c = glm::dot(n, wo);
  if (c >= kLeastShadingCos) return n;
  const vec3 across = n - c * wo;  // n's part orthogonal to wo; not 0: wo sees the triangle's front
  const float length = glm::length(across);
  if (!(length > 0.0f)) return wo;
  return kLeastShadingCos * wo + std::sqrt(1.0f - kLeastShadingCos * kLeastShadingCos) * (across / length);
}

struct Counters {
  uint64_t camera = 0, shadow = 0, bounce = 0;
};

struct PathResult {
  vec3 radiance{0.0f};
  vec3 albedo{0.0f};
  vec3 normal{0.0f};
};

// The albedo AOV is the evaluator's quadrature at the first hit: costly, so only the first few samples of a
// pixel compute it, enough to average it over the pixel's area.
constexpr int kAovSamples = 4;

PathResult trace(const RenderScene& scene, const RenderOptions& options, const CameraRay& camera, bool aovs,
                 cpu::Pcg32& rng, Counters& counters) {
  PathResult result;
  const Environment& environment = scene.environment();
  const bool sample_lights = options.estimator != Estimator::BrdfSampling;
  const bool count_escapes = options.estimator != Estimator::LightSampling;
  vec3 origin = camera.origin, direction = camera.direction;
  vec3 throughput(1.0f);
  float travelled = 0.0f;     // the path's length so far, for the ray cone and the view distance
  float previous_pdf = 0.0f;  // the BRDF density of the direction just drawn
  ++counters.camera;
  for (int depth = 0;; ++depth) {
    const auto hit = scene.intersect(origin, direction, std::numeric_limits<float>::infinity());
    // What a ray meets that emits: counted at the camera, and after a bounce as the BRDF-sampling half
    // of the estimate (its MIS weight against the light sample that could have drawn it).
    auto add_emitted = [&](vec3 radiance, float light_pdf) {
      if (depth == 0)
        result.radiance += throughput * radiance;
      else if (count_escapes)
        result.radiance += throughput * radiance * (sample_lights ? power_heuristic(previous_pdf, light_pdf) : 1.0f);
    };
    if (!hit) {
      if (environment.present()) add_emitted(environment.radiance(direction), environment.pdf(direction));
      for (const PunctualLight& light : scene.lights())
        if (!light.delta() && -glm::dot(direction, light.direction) >= light.cos_radius)
          add_emitted(light.radiance, cone_pdf(light.cos_radius));
      break;
    }
    if (const vec3 emitted = scene.emission(hit->object);
        max_component(emitted) > 0.0f && glm::dot(hit->geometric_normal, direction) < 0.0f)
      add_emitted(emitted, scene.emitter_pdf(*hit, direction));
    if (depth >= options.max_depth) break;  // light arriving at this surface was counted; none leaves it
    travelled += hit->distance;
    const vec3 wo = -direction;
    // Surfaces are two-sided: the side the ray arrives on is the front.
    vec3 ng = hit->geometric_normal, n = hit->normal;
    if (glm::dot(ng, wo) < 0.0f) {
      ng = -ng;
      n = -n;
    }
    n = facing_normal(n, wo);
    ShadingContext ctx;
    ctx.uv = hit->uv;
    ctx.position = hit->position;
    ctx.normal = n;
    ctx.tangent = hit->tangent;
    ctx.view_distance = travelled;
    ctx.footprint = uv_footprint(camera.spread * travelled, glm::dot(n, wo), hit->uv_per_length);
    const cpu::Evaluator& material = scene.material(hit->object);
    const cpu::ShadingPoint point = material.bind(ctx);
    if (depth == 0 && aovs) {
      result.normal = n;
      result.albedo = point.albedo(wo, 16);
    }

    // A fluorescent base moves light between channels: what a light of radiance L gives is F L, not
    // f * L, and the path's throughput is carried on by the transposed F (ShadingPoint::eval_adjoint).
    const bool glowing = point.fluorescent();
    auto reflected = [&](vec3 wi, vec3 f, vec3 radiance) {
      return glowing ? point.eval(wi, wo, radiance) : f * radiance;
    };

    // A light sample that is not a delta: its MIS weight against BRDF sampling, which could have drawn
    // the same direction.
    // `emitter`: the point drawn on an emitting surface; none for light from infinitely far away.
    auto add_light_sample = [&](vec3 wi, vec3 radiance, float light_pdf, const EmitterSample* emitter) {
      if (!(light_pdf > 0.0f) || glm::dot(wi, ng) <= 0.0f) return;
      const cpu::EvalPdf brdf = point.eval_pdf(wi, wo);
      if (max_component(brdf.f) <= 0.0f) return;
      ++counters.shadow;
      if (emitter ? segment_blocked(scene, hit->position, ng, emitter->position, emitter->normal)
                  : scene.occluded(offset_origin(hit->position, ng, wi), wi, std::numeric_limits<float>::infinity()))
        return;
      const float weight = count_escapes ? power_heuristic(light_pdf, brdf.pdf) : 1.0f;
      result.radiance +=
          throughput * reflected(wi, brdf.f, radiance) * (std::max(glm::dot(n, wi), 0.0f) * weight / light_pdf);
    };

    if (sample_lights) {
      for (const PunctualLight& light : scene.lights()) {
        if (!light.delta()) {  // a disk at infinity: a direction within its cone
          const vec3 axis = -light.direction;
          const Frame frame = Frame::from_normal_tangent(axis, vec3(0.0f));
          const float cos_theta = 1.0f - rng.uniform() * (1.0f - light.cos_radius);
          const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
          const float phi = 2.0f * std::numbers::pi_v<float> * rng.uniform();
          const vec3 wi = frame.to_world(vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
          add_light_sample(glm::normalize(wi), light.radiance, cone_pdf(light.cos_radius), nullptr);
          continue;
        }
        vec3 wi, incident;
        float distance = std::numeric_limits<float>::infinity();
        if (light.type == LightType::Directional) {
          wi = -light.direction;
          incident = light.intensity;
        } else {
          const vec3 d = light.position - hit->position;
          distance = glm::length(d);
          if (!(distance > 0.0f)) continue;
          wi = d / distance;
          incident = light.intensity * punctual_attenuation(light, distance, -wi) / (distance * distance);
        }
        if (glm::dot(wi, ng) <= 0.0f || max_component(incident) <= 0.0f) continue;
        const vec3 f = point.eval(wi, wo);
        if (max_component(f) <= 0.0f) continue;
        ++counters.shadow;
        const vec3 from = offset_origin(hit->position, ng, wi);
        if (scene.occluded(from, wi, std::isinf(distance) ? distance : distance * (1.0f - 1.0e-4f))) continue;
        result.radiance += throughput * reflected(wi, f, incident) * std::max(glm::dot(n, wi), 0.0f);
      }
      if (environment.present()) {
        const vec2 u(rng.uniform(), rng.uniform());
        const EnvironmentSample s = environment.sample(u);
        add_light_sample(s.wi, s.radiance, s.pdf, nullptr);
      }
      if (scene.has_emitters()) {
        const vec3 u = rng.uniform3();
        const EmitterSample s = scene.sample_emitter(hit->position, u);
        add_light_sample(s.wi, s.radiance, s.pdf, &s);
      }
    }

    const vec2 u(rng.uniform(), rng.uniform());
    const cpu::Sample s = point.sample(wo, u, rng.uniform());
    const float cos_i = glm::dot(n, s.wi);
    if (!(s.pdf > 0.0f) || cos_i <= 0.0f || glm::dot(s.wi, ng) <= 0.0f) break;
    throughput = (glowing ? point.eval_adjoint(s.wi, wo, throughput) : throughput * s.f) * (cos_i / s.pdf);
    previous_pdf = s.pdf;
    if (depth + 1 >= options.roulette_depth) {
      // Continue with the probability of the path's throughput (at most 0.95: every path ends).
      const float q = std::min(0.95f, max_component(throughput));
      if (!(rng.uniform() < q)) break;
      throughput /= q;
    }
    origin = offset_origin(hit->position, ng, s.wi);
    direction = s.wi;
    ++counters.bounce;
  }
  return result;
}

}  // namespace

CameraRay camera_ray(const Camera& camera, int width, int height, vec2 pixel, vec2 lens) {
  const vec3 position(camera.position), forward = glm::normalize(vec3(camera.look_at) - position);
  const vec3 right = glm::normalize(glm::cross(forward, vec3(camera.up)));
  const vec3 up = glm::cross(right, forward);
  const float tan_half = float(std::tan(glm::radians(camera.yfov_deg) / 2.0));
  const float aspect = float(width) / float(height);
  const float sx = (2.0f * pixel.x / float(width) - 1.0f) * tan_half * aspect;
  const float sy = (1.0f - 2.0f * pixel.y / float(height)) * tan_half;
  CameraRay ray;
  ray.origin = position;
  const vec3 through = forward + sx * right + sy * up;  // reaches the plane at distance 1 in front
  ray.direction = glm::normalize(through);
  ray.spread = 2.0f * tan_half / float(height);
  if (camera.aperture_radius > 0.0) {
    // The pinhole ray's point on the plane in focus (perpendicular to the view direction), seen from a
    // point of the lens drawn uniformly over its disk.
    const vec3 focus = position + through * float(camera.focus());
    const float r = float(camera.aperture_radius) * std::sqrt(lens.x);
    const float phi = 2.0f * std::numbers::pi_v<float> * lens.y;
    ray.origin = position + right * (r * std::cos(phi)) + up * (r * std::sin(phi));
    ray.direction = glm::normalize(focus - ray.origin);
  }
  return ray;
}

RenderResult render(const RenderScene& scene, const Camera& camera, const RenderOptions& options) {
  RenderResult result;
  result.width = options.width;
  result.height = options.height;
  const size_t pixels = size_t(options.width) * size_t(options.height);
  // Sums over the samples until the end, then means.
  result.radiance.assign(pixels, vec3(0.0f));
  if (options.aovs) {
    result.albedo.assign(pixels, vec3(0.0f));
    result.normal.assign(pixels, vec3(0.0f));
  }
  const bool budgeted = options.time_budget > 0.0;
  // With a budget, every pixel's random stream, carried from pass to pass; in one pass, each row makes
  // its pixels' streams as it goes.
  std::vector<cpu::Pcg32> streams;
  if (budgeted) {
    streams.reserve(pixels);
    for (size_t i = 0; i < pixels; ++i) streams.emplace_back(options.seed, uint64_t(i));
  }
  const bool lens = camera.aperture_radius > 0.0;
  std::vector<Counters> row_counters(size_t(options.height));
  const std::thread::id caller = std::this_thread::get_id();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };

  auto run_pass = [&](int first, int count) {
    std::atomic<int> rows_done{0};
    auto render_row = [&](size_t row) {
      Counters& counters = row_counters[row];
      for (int x = 0; x < options.width; ++x) {
        const size_t index = row * size_t(options.width) + size_t(x);
        // One stream per pixel: what a pixel draws does not depend on which thread renders it.
        cpu::Pcg32 own(options.seed, uint64_t(index));
        cpu::Pcg32& rng = budgeted ? streams[index] : own;
        for (int s = first; s < first + count; ++s) {
          const vec2 jitter(rng.uniform(), rng.uniform());
          vec2 lens_u(0.0f);
          if (lens) lens_u = vec2(rng.uniform(), rng.uniform());
          const CameraRay ray =
              camera_ray(camera, options.width, options.height, vec2(float(x), float(row)) + jitter, lens_u);
          const PathResult path = trace(scene, options, ray, options.aovs && s < kAovSamples, rng, counters);
          result.radiance[index] += path.radiance;
          if (options.aovs) {
            result.albedo[index] += path.albedo;
            result.normal[index] += path.normal;
          }
        }
      }
      const int done = ++rows_done;
      if (options.progress && std::this_thread::get_id() == caller)
        options.progress(budgeted ? std::min(1.0, elapsed() / options.time_budget)
                                  : (first + count * double(done) / double(options.height)) / options.samples);
    };
    parallel_for(size_t(options.height), render_row, size_t(std::max(options.threads, 0)));
  };

  if (!budgeted) {
    run_pass(0, options.samples);
    result.samples = options.samples;
  } else {
    // Passes that double the samples so far, each as large as the time left holds at the rate measured
    // so far; the first is one sample, whatever the budget (an image is never empty).
    int done = 0;
    while (done < options.samples) {
      int count = 1;
      if (done > 0) {
        const double per_sample = elapsed() / done, left = options.time_budget - elapsed();
        count = int(std::min({left / per_sample, double(done), double(options.samples - done)}));
        if (count < 1) break;
      }
      run_pass(done, count);
      done += count;
    }
    result.samples = done;
  }

  const float inverse = 1.0f / float(result.samples);
  for (size_t i = 0; i < pixels; ++i) {
    result.radiance[i] *= inverse;
    if (options.aovs) {
      result.albedo[i] /= float(std::min(result.samples, kAovSamples));
      const float length = glm::length(result.normal[i]);
      result.normal[i] = length > 0.0f ? result.normal[i] / length : vec3(0.0f);
    }
  }
  for (const Counters& c : row_counters) {
    result.camera_rays += c.camera;
    result.shadow_rays += c.shadow;
    result.bounce_rays += c.bounce;
  }
  if (options.progress) options.progress(1.0);
  return result;
}

}  // namespace lamina::render
