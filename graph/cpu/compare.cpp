#include "graph/cpu/compare.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <numbers>
#include <thread>

#include "graph/cpu/reference.h"

namespace lamina::cpu {

namespace {

using glm::dvec3;
using glm::vec3;

double luminance(dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

vec3 in_plane(double theta_deg) {
  const double t = theta_deg * std::numbers::pi / 180.0;
  return vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

double relative_error(dvec3 model, dvec3 reference) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(model[c] - reference[c]) / std::max(reference[c], kCompareErrorFloor));
  return worst;
}

// Runs jobs 0..count-1 on every core; each job writes only its own result, so the outcome does not
// depend on the schedule.
void run_jobs(size_t count, const std::function<void(size_t)>& job) {
  std::atomic<size_t> next{0};
  const size_t threads = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 16);
  std::vector<std::thread> pool;
  for (size_t t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (size_t i = next++; i < count; i = next++) job(i);
    });
  for (std::thread& thread : pool) thread.join();
}

}  // namespace

Comparison compare_to_reference(const ShadingPoint& point, const CompareOptions& options) {
  Comparison out;
  for (double theta : kCompareAlbedoAngles) out.albedo.push_back({theta, {}, 0.0});
  for (double theta_o : kCompareViewAngles) {
    SliceComparison s;
    s.theta_o_deg = theta_o;
    for (double t = -kCompareLightLimit; t <= kCompareLightLimit + 1e-9; t += kCompareLightStep) {
      s.theta_i_deg.push_back(t);
      s.f.emplace_back();
    }
    out.slices.push_back(std::move(s));
  }
  // Every reference estimate is a job: the albedo rows first, then the slices' points.
  std::vector<std::pair<size_t, size_t>> points;
  for (size_t s = 0; s < out.slices.size(); ++s)
    for (size_t k = 0; k < out.slices[s].f.size(); ++k) points.emplace_back(s, k);
  run_jobs(out.albedo.size() + points.size(), [&](size_t job) {
    if (job < out.albedo.size()) {
      AlbedoComparison& row = out.albedo[job];
      const vec3 wo = in_plane(row.theta_deg);
      const ReferenceEstimate r = reference_albedo(point, wo, {options.albedo_walks, 1000, options.seed});
      row.albedo = {dvec3(point.albedo(wo)), r.value, r.std_error};
      return;
    }
    const auto [s, k] = points[job - out.albedo.size()];
    SliceComparison& slice = out.slices[s];
    const vec3 wo = in_plane(slice.theta_o_deg);
    const vec3 wi = in_plane(-slice.theta_i_deg[k]);
    const ReferenceEstimate r = reference_eval(point, wi, wo, {options.slice_walks, 1000, options.seed});
    slice.f[k] = {dvec3(point.eval(wi, wo)), r.value, r.std_error};
  });
  for (AlbedoComparison& row : out.albedo) {
    row.relative_error = relative_error(row.albedo.model, row.albedo.reference);
    if (row.relative_error > out.max_albedo_error) {
      out.max_albedo_error = row.relative_error;
      out.max_albedo_error_theta_deg = row.theta_deg;
    }
  }
  for (SliceComparison& slice : out.slices) {
    double sum = 0.0;
    for (const CompareValue& v : slice.f) {
      const double reference = luminance(v.reference);
      sum += std::pow((luminance(v.model) - reference) / std::max(reference, kCompareSliceFloor), 2.0);
    }
    slice.rms_relative_error = slice.f.empty() ? 0.0 : std::sqrt(sum / double(slice.f.size()));
  }
  return out;
}

}  // namespace lamina::cpu
