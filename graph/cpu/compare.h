// The layered model against the reference solver (graph/cpu/reference.h) at one shading point:
// directional albedo from 0 to 89 degrees and in-plane BRDF slices, each reference value with its
// standard error, and summary errors. What `lamina compare` prints.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "graph/cpu/evaluator.h"

namespace lamina::cpu {

struct CompareOptions {
  int64_t albedo_walks = int64_t(1) << 16;  // reference walks per albedo angle
  int64_t slice_walks = int64_t(1) << 14;   // reference walks per BRDF point
  uint64_t seed = 0;
};

// Where the comparison looks: views and lights in the plane of incidence (x, z). theta_i > 0 lies
// on the mirror side of the view, as in lamina plot's slices.
inline constexpr double kCompareAlbedoAngles[] = {0, 10, 20, 30, 40, 50, 60, 70, 75, 80, 85, 89};
inline constexpr double kCompareViewAngles[] = {0, 30, 60, 80};
inline constexpr double kCompareLightStep = 5.0;    // degrees between the points of a slice
inline constexpr double kCompareLightLimit = 85.0;  // the slices run from -85 to 85 degrees

struct CompareValue {
  glm::dvec3 model{0.0};
  glm::dvec3 reference{0.0};
  glm::dvec3 std_error{0.0};  // the reference's
};

struct AlbedoComparison {
  double theta_deg = 0.0;
  CompareValue albedo;
  double relative_error = 0.0;  // the largest over channels of |model - reference| / reference
};

struct SliceComparison {
  double theta_o_deg = 0.0;
  std::vector<double> theta_i_deg;
  std::vector<CompareValue> f;
  // The root mean square over the slice's points of (Y(model) - Y(reference)) / Y(reference), Y the
  // luminance (counted against kCompareSliceFloor where the reference is darker): every direction
  // weighs the same, so a specular peak both agree on cannot hide the rest.
  double rms_relative_error = 0.0;
};

struct Comparison {
  std::vector<AlbedoComparison> albedo;
  std::vector<SliceComparison> slices;
  double max_albedo_error = 0.0;  // the largest relative_error of the albedo rows
  double max_albedo_error_theta_deg = 0.0;
};

// A channel's relative error counts from reference values of this size up (darker channels are
// compared to it instead), so that a nearly black channel cannot dominate.
inline constexpr double kCompareErrorFloor = 0.01;
inline constexpr double kCompareSliceFloor = 1e-3;  // 1/sr

Comparison compare_to_reference(const ShadingPoint& point, const CompareOptions& options = {});

}  // namespace lamina::cpu
