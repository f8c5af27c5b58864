#include "graph/cpu/compare.h"

#include <algorithm>
#include <cmath>

#include "graph/cpu/frame.h"
#include "graph/cpu/reference.h"
#include "graph/parallel.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace {

using glm::dvec3;
using glm::vec3;

double luminance(dvec3 c) { return kernels::lamina_luminance(vec3(c)); }

double relative_error(dvec3 model, dvec3 reference) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(model[c] - reference[c]) / std::max(reference[c], kCompareErrorFloor));
  return worst;
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
  parallel_for(out.albedo.size() + points.size(), [&](size_t job) {
    if (job < out.albedo.size()) {
      AlbedoComparison& row = out.albedo[job];
      const vec3 wo = direction_in_plane(row.theta_deg);
      const ReferenceEstimate r = reference_albedo(point, wo, {options.albedo_walks, 1000, options.seed});
      row.albedo = {dvec3(point.albedo(wo)), r.value, r.std_error};
      return;
    }
    const auto [s, k] = points[job - out.albedo.size()];
    SliceComparison& slice = out.slices[s];
    const vec3 wo = direction_in_plane(slice.theta_o_deg);
    const vec3 wi = direction_in_plane(-slice.theta_i_deg[k]);
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
