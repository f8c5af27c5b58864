#include "graph/cpu/energy_table.h"

#include <algorithm>
#include <cmath>

#include "graph/cpu/microsurface.h"
#include "graph/cpu/pcg32.h"
#include "graph/parallel.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace k = lamina::kernels;
using glm::vec2;
using glm::vec3;

namespace {

// The mean over n x n strata of the distribution's normal sampling (sample_microfacet_normal) of
// integrand(l, h, v.h), l the view v mirrored about the drawn normal h (draws whose v.h or l.z is not
// positive add 0): an integral over the upper hemisphere of l, for an integrand that divides by
// the density of l.
template <typename Integrand>
double over_mirrored_directions(int distribution, float m, vec3 v, int n, Integrand integrand) {
  double sum = 0.0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      vec2 u((float(a) + 0.5f) / float(n), (float(b) + 0.5f) / float(n));
      vec3 h = k::sample_microfacet_normal(distribution, m, u);
      float v_dot_h = glm::dot(v, h);
      if (v_dot_h <= 0.0f) continue;
      vec3 l = 2.0f * v_dot_h * h - v;
      if (l.z <= 0.0f) continue;
      sum += integrand(glm::normalize(l), h, v_dot_h);
    }
  }
  return sum / (double(n) * double(n));
}

vec3 view_of_cosine(float mu) { return vec3(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu); }

// The boundary's reflection f(l, v) cos_l over the density of l drawn by over_mirrored_directions
// from v: D(h) cos_h / (4 v.h) (Walter et al. 2007, eq. 14), with D from h's components as the
// evaluation computes it (for narrow lobes cos_h rounds to 1); 0 where the density is not positive.
double reflection_over_density(int distribution, int fresnel, float m, float eta, vec3 l, vec3 v, vec3 h,
                               float v_dot_h) {
  const double pdf = double(k::d_microfacet_h(distribution, h, m)) * double(h.z) / (4.0 * double(v_dot_h));
  if (!(pdf > 0.0)) return 0.0;
  return double(k::lamina_boundary_reflection(l, v, eta, distribution, fresnel, m)) * double(l.z) / pdf;
}

}  // namespace

double dielectric_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n) {
  const vec3 v = view_of_cosine(mu);
  return over_mirrored_directions(distribution, m, v, n, [&](vec3 l, vec3 h, float v_dot_h) {
    return reflection_over_density(distribution, fresnel, m, eta, l, v, h, v_dot_h);
  });
}

double conductor_cone_quadrature(int distribution, float mu, float m, float cone_cosine, int n) {
  const vec3 v = view_of_cosine(mu);
  return over_mirrored_directions(distribution, m, v, n, [&](vec3 l, vec3 h, float v_dot_h) {
    if (l.z <= cone_cosine) return 0.0;
    // D G / (4 mu cos_l) cos_l over the density D cos_h / (4 v.h): G v.h / (mu cos_h).
    const double g = double(k::g_microfacet(distribution, l.z, v.z, h.z, v_dot_h, m));
    return g * double(v_dot_h) / (double(mu) * double(h.z));
  });
}

double height_correlated_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n) {
  const vec3 v = view_of_cosine(mu);
  const double lambda_v = double(k::lamina_smith_lambda(distribution, v, m));
  return over_mirrored_directions(distribution, m, v, n, [&](vec3 l, vec3 h, float v_dot_h) {
    // f cos_l / pdf with pdf = D cos_h / (4 v.h): F G2 v.h / (cos_v cos_h).
    const double g2 = 1.0 / (1.0 + lambda_v + double(k::lamina_smith_lambda(distribution, l, m)));
    const double f = double(k::lamina_fresnel_dielectric(fresnel, v_dot_h, eta));
    return f * g2 * double(v_dot_h) / (double(mu) * double(h.z));
  });
}

double raised_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n) {
  const vec3 v = view_of_cosine(mu);
  const vec2 xy = k::lamina_albedo_grid_xy(m, eta);
  const float boost_v = k::lamina_boundary_boost_at(k::lamina_albedo_point_at(distribution, fresnel, xy, mu, eta));
  return over_mirrored_directions(distribution, m, v, n, [&](vec3 l, vec3 h, float v_dot_h) {
    const float boost_l = k::lamina_boundary_boost_at(k::lamina_albedo_point_at(distribution, fresnel, xy, l.z, eta));
    return reflection_over_density(distribution, fresnel, m, eta, l, v, h, v_dot_h) *
           (1.0 + double(boost_v) * double(boost_l));
  });
}

MicrosurfaceStatistics microsurface_statistics(int distribution, int fresnel, float mu, float m, float eta, int walks,
                                               uint64_t seed) {
  const MicrosurfaceBoundary boundary{eta, distribution, fresnel, m};
  const vec3 from = view_of_cosine(mu);
  Pcg32 rng(seed, 0x6d756c7469ull);
  MicrosurfaceStatistics stats;
  double multiple = 0.0, transmitted = 0.0, mean_path = 0.0, at_depth = 0.0;
  for (int w = 0; w < walks; ++w) {
    const MicrosurfaceSample s = microsurface_sample(boundary, from, rng);
    if (s.events >= 2 && s.direction.z > 0.0f) multiple += double(s.weight);
    if (s.direction.z < 0.0f) {
      const double x = 1.0 / double(-s.direction.z);
      transmitted += double(s.weight);
      mean_path += double(s.weight) * x;
      at_depth += double(s.weight) * std::exp(-double(k::LAMINA_ALBEDO_PATH_DEPTH) * x);
    }
  }
  stats.multiple = multiple / double(walks);
  // r = x_s / g: g the mean path, or -ln(mean of exp(-depth x)) / depth; 1 where nothing passes.
  const float mu_below = k::lamina_cosine_below(mu, eta);
  if (transmitted > 0.0 && mu_below > 0.0f) {
    const double range = double(k::LAMINA_ALBEDO_PATH_RANGE);
    const double g_depth = -std::log(at_depth / transmitted) / double(k::LAMINA_ALBEDO_PATH_DEPTH);
    stats.path_ratio = std::min(range, transmitted / (mean_path * double(mu_below)));
    stats.depth_ratio = g_depth > 0.0 ? std::min(range, 1.0 / (g_depth * double(mu_below))) : range;
  }
  return stats;
}

int dielectric_albedo_table_entry(int combo, int i, int j, int k_) {
  const int distribution = combo / 2;
  const int fresnel = combo % 2;  // 0 exact, 1 Schlick (the same table as Lazanyi)
  const float eta = k::lamina_albedo_node_eta(i);
  double e = dielectric_albedo_quadrature(distribution, fresnel, k::lamina_albedo_node_cosine(k_, eta),
                                          k::lamina_albedo_node_slope(j), eta, kAlbedoTableStrata);
  return int(std::min(65535.0, std::ceil(std::max(0.0, e) * 65535.0)));
}

int conductor_cone_table_entry(int combo, int i, int j, int k_) {
  const float eta = k::lamina_albedo_node_eta(i);
  const float cone_cosine = eta > 1.0f ? std::sqrt(1.0f - 1.0f / (eta * eta)) : 0.0f;
  const double c = conductor_cone_quadrature(combo / 2, k::lamina_cone_axis_cosine(float(k_), std::max(eta, 1.0f)),
                                             k::lamina_albedo_node_slope(j), cone_cosine, kAlbedoTableStrata);
  return int(std::clamp(std::floor(c * 65535.0), 0.0, 65535.0));
}

namespace {

// The seed of a node's walks.
uint64_t node_seed(int combo, int i, int j, int k_) {
  return uint64_t(((combo * k::LAMINA_ALBEDO_ETAS + i) * k::LAMINA_ALBEDO_SLOPES + j) * k::LAMINA_ALBEDO_COSINES + k_) +
         1;
}

MicrosurfaceStatistics node_statistics(int combo, int i, int j, int k_) {
  const float eta = k::lamina_albedo_node_eta(i);
  return microsurface_statistics(combo / 2, combo % 2, k::lamina_albedo_node_cosine(k_, eta),
                                 k::lamina_albedo_node_slope(j), eta, kMultipleScatteringWalks,
                                 node_seed(combo, i, j, k_));
}

// M as the table holds it, from the node's single-scattering entry and its walks' multiple share.
int multiple_entry(int combo, int i, int j, int k_, int single, double multiple) {
  const int distribution = combo / 2;
  const int fresnel = combo % 2;
  const float eta = k::lamina_albedo_node_eta(i);
  const float mu = k::lamina_albedo_node_cosine(k_, eta);
  const float m = k::lamina_albedo_node_slope(j);
  const double whole =
      height_correlated_albedo_quadrature(distribution, fresnel, mu, m, eta, kAlbedoTableStrata) + multiple;
  const int surplus = int(std::lround(std::max(0.0, whole - double(single) / 65535.0) * 65535.0));
  return std::clamp(surplus, 0, 65535 - single);
}

// An entry of P or Q from the node's walks. A smooth boundary (slope node 0) refracts every ray to
// mu_below: r = 1 exactly, as the composition's smooth case.
int path_entry(int j, const MicrosurfaceStatistics& stats, bool at_depth) {
  const double r = j == 0 ? 1.0 : at_depth ? stats.depth_ratio : stats.path_ratio;
  return int(std::clamp(std::lround(r / double(k::LAMINA_ALBEDO_PATH_RANGE) * 65535.0), 0l, 65535l));
}

}  // namespace

int dielectric_multiple_table_entry(int combo, int i, int j, int k_, int single) {
  return multiple_entry(combo, i, j, k_, single, node_statistics(combo, i, j, k_).multiple);
}

int transmitted_path_table_entry(int combo, int i, int j, int k_, bool at_depth) {
  return path_entry(j, node_statistics(combo, i, j, k_), at_depth);
}

namespace {

constexpr int kCellsI = k::LAMINA_ALBEDO_ETAS - 1;
constexpr int kCellsJ = k::LAMINA_ALBEDO_SLOPES - 1;
constexpr int kCellsK = k::LAMINA_ALBEDO_COSINES - 1;

// Corner n (0..7) of the cell whose first corner is node (i, j, c): bit 0 steps in eta, 1 in slope,
// 2 in cosine.
int corner_i(int i, int n) { return i + (n & 1); }
int corner_j(int j, int n) { return j + ((n >> 1) & 1); }
int corner_c(int c, int n) { return c + (n >> 2); }

// Nodes of an index-matched boundary (reflecting nothing) and of a smooth one (the Fresnel
// reflectance, exactly) are never raised.
bool may_rise(int i, int j) { return k::lamina_albedo_node_eta(i) != 1.0f && j != 0; }

// E at the centre of the cell whose first corner is node (i, j, c).
double cell_centre(int combo, int i, int j, int c) {
  const float eta = k::lamina_albedo_grid_eta(float(i) + 0.5f);
  return dielectric_albedo_quadrature(combo / 2, combo % 2, k::lamina_albedo_grid_cosine(float(c) + 0.5f, eta),
                                      k::lamina_albedo_grid_slope(float(j) + 0.5f), eta, kAlbedoTableStrata);
}

// What a cell asks of each of its corners that may rise: kAlbedoBoundMargin times the shortfall of
// the interpolation of the corners' entries (`corners`, in corner order) at its centre, over the
// share of the centre's interpolation those corners carry; 0 if the interpolation does not fall short.
int cell_lift(int i, int j, const int corners[8], double centre) {
  double interpolated = 0.0, free_weight = 0.0;
  for (int n = 0; n < 8; ++n) {
    interpolated += 0.125 * corners[n];
    if (may_rise(corner_i(i, n), corner_j(j, n))) free_weight += 0.125;
  }
  const double short_by = centre * 65535.0 - interpolated;
  if (short_by <= 0.0 || free_weight <= 0.0) return 0;
  return int(std::ceil(kAlbedoBoundMargin * short_by / free_weight));
}

}  // namespace

std::vector<int> boundary_boost_run(int combo, int i, int j, const int* multiple) {
  constexpr int n = k::LAMINA_ALBEDO_COSINES;
  std::vector<int> run(size_t(n), 0);
  // A smooth boundary's lobe is a mirror the kernels do not evaluate, and it scatters once only.
  if (j == 0) return run;
  const int distribution = combo / 2;
  const int fresnel = combo % 2;
  const float eta = k::lamina_albedo_node_eta(i);
  const float m = k::lamina_albedo_node_slope(j);
  const double strata = double(kAlbedoTableStrata) * double(kAlbedoTableStrata);
  const vec2 xy = k::lamina_albedo_grid_xy(m, eta);
  // K[c][q]: what the lobe at node c's view reflects, weighted by the hat function of cosine node q
  // on the grid's axis (the composition interpolates b linearly there), so that (K b)_c is exactly
  // the integral of f(l_c, v) b(v) cos_v for the interpolated b.
  std::vector<double> kernel(size_t(n * n), 0.0), target(size_t(n), 0.0), own(size_t(n), 0.0);
  for (int c = 0; c < n; ++c) {
    const vec3 l = view_of_cosine(k::lamina_albedo_node_cosine(c, eta));
    own[size_t(c)] =
        over_mirrored_directions(distribution, m, l, kAlbedoTableStrata, [&](vec3 v, vec3 h, float l_dot_h) {
          const double w = reflection_over_density(distribution, fresnel, m, eta, v, l, h, l_dot_h);
          // v's node on the cosine axis and the fraction beyond, as the kernels find them.
          const k::LaminaAlbedoPoint at = k::lamina_albedo_point_at(distribution, fresnel, xy, v.z, eta);
          kernel[size_t(c * n + at.k)] += w * (1.0 - double(at.fz)) / strata;
          kernel[size_t(c * n + at.k + 1)] += w * double(at.fz) / strata;
          return w;
        });
    target[size_t(c)] = double(multiple[c]) / 65535.0;
  }
  // b_c (K b)_c = target_c, by the symmetric scaling iteration b <- sqrt(b target / (K b)), from
  // b = sqrt(target / E), its solution where the lobe is narrow.
  std::vector<double> b(size_t(n), 0.0), next(size_t(n), 0.0);
  for (int c = 0; c < n; ++c) b[size_t(c)] = own[size_t(c)] > 0.0 ? std::sqrt(target[size_t(c)] / own[size_t(c)]) : 0.0;
  for (int iteration = 0; iteration < kBoostIterations; ++iteration) {
    for (int c = 0; c < n; ++c) {
      double kb = 0.0;
      for (int q = 0; q < n; ++q) kb += kernel[size_t(c * n + q)] * b[size_t(q)];
      next[size_t(c)] = kb > 0.0 ? std::sqrt(b[size_t(c)] * target[size_t(c)] / kb) : 0.0;
    }
    b.swap(next);
  }
  for (int c = 0; c < n; ++c)
    run[size_t(c)] =
        int(std::clamp(std::floor(b[size_t(c)] / double(k::LAMINA_ALBEDO_BOOST_RANGE) * 65535.0), 0.0, 65535.0));
  return run;
}

std::vector<int> dielectric_albedo_table() {
  const int rows = k::LAMINA_ALBEDO_COMBOS * k::LAMINA_ALBEDO_ETAS;
  const int width = k::LAMINA_ALBEDO_TABLE_WIDTH;
  std::vector<int> table(size_t(rows) * size_t(width));
  // One task per (row, slope): the walks dominate and vary with the slope.
  parallel_for(size_t(rows * k::LAMINA_ALBEDO_SLOPES), [&](size_t task) {
    const int row = int(task) / k::LAMINA_ALBEDO_SLOPES;
    const int j = int(task) % k::LAMINA_ALBEDO_SLOPES;
    const int combo = row / k::LAMINA_ALBEDO_ETAS;
    const int i = row % k::LAMINA_ALBEDO_ETAS;
    int* at = table.data() + size_t(row) * size_t(width);
    for (int c = 0; c < k::LAMINA_ALBEDO_COSINES; ++c) {
      const int single = dielectric_albedo_table_entry(combo, i, j, c);
      const MicrosurfaceStatistics stats = node_statistics(combo, i, j, c);
      const int column = j * k::LAMINA_ALBEDO_COSINES + c;
      at[column] = single;
      at[k::LAMINA_ALBEDO_MULTIPLE_COLUMN + column] = multiple_entry(combo, i, j, c, single, stats.multiple);
      at[k::LAMINA_ALBEDO_CONE_COLUMN + column] = conductor_cone_table_entry(combo, i, j, c);
      at[k::LAMINA_ALBEDO_PATH_COLUMN + column] = path_entry(j, stats, false);
      at[k::LAMINA_ALBEDO_DEPTH_COLUMN + column] = path_entry(j, stats, true);
    }
  });
  // Every cell's lift, then every node raised by the most its cells ask.
  auto entry = [&](int combo, int i, int j, int c) -> int& {
    return table[size_t(combo * k::LAMINA_ALBEDO_ETAS + i) * size_t(width) + size_t(j * k::LAMINA_ALBEDO_COSINES + c)];
  };
  std::vector<int> lift(size_t(k::LAMINA_ALBEDO_COMBOS * kCellsI * kCellsJ * kCellsK));
  parallel_for(size_t(k::LAMINA_ALBEDO_COMBOS * kCellsI), [&](size_t task) {
    const int combo = int(task) / kCellsI, i = int(task) % kCellsI;
    for (int j = 0; j < kCellsJ; ++j)
      for (int c = 0; c < kCellsK; ++c) {
        int corners[8];
        for (int n = 0; n < 8; ++n) corners[n] = entry(combo, corner_i(i, n), corner_j(j, n), corner_c(c, n));
        lift[(task * size_t(kCellsJ) + size_t(j)) * size_t(kCellsK) + size_t(c)] =
            cell_lift(i, j, corners, cell_centre(combo, i, j, c));
      }
  });
  std::vector<int> raise(table.size(), 0);
  for (int combo = 0; combo < k::LAMINA_ALBEDO_COMBOS; ++combo)
    for (int i = 0; i < kCellsI; ++i)
      for (int j = 0; j < kCellsJ; ++j)
        for (int c = 0; c < kCellsK; ++c)
          for (int n = 0; n < 8; ++n) {
            if (!may_rise(corner_i(i, n), corner_j(j, n))) continue;
            const size_t node = size_t(combo * k::LAMINA_ALBEDO_ETAS + corner_i(i, n)) * size_t(width) +
                                size_t(corner_j(j, n) * k::LAMINA_ALBEDO_COSINES + corner_c(c, n));
            raise[node] = std::max(
                raise[node],
                lift[((size_t(combo * kCellsI + i) * size_t(kCellsJ)) + size_t(j)) * size_t(kCellsK) + size_t(c)]);
          }
  for (size_t row = 0; row < size_t(rows); ++row)
    for (int e = 0; e < k::LAMINA_ALBEDO_BLOCK; ++e) {
      const size_t at = row * size_t(width) + size_t(e);
      table[at] = std::min(table[at] + raise[at], 65535);
      int& multiple = table[at + size_t(k::LAMINA_ALBEDO_MULTIPLE_COLUMN)];
      multiple = std::min(multiple, 65535 - table[at]);
    }
  // Block B from the final E and M.
  parallel_for(size_t(rows * k::LAMINA_ALBEDO_SLOPES), [&](size_t task) {
    const int row = int(task) / k::LAMINA_ALBEDO_SLOPES;
    const int j = int(task) % k::LAMINA_ALBEDO_SLOPES;
    int* at = table.data() + size_t(row) * size_t(width) + size_t(j * k::LAMINA_ALBEDO_COSINES);
    const std::vector<int> run = boundary_boost_run(row / k::LAMINA_ALBEDO_ETAS, row % k::LAMINA_ALBEDO_ETAS, j,
                                                    at + k::LAMINA_ALBEDO_MULTIPLE_COLUMN);
    std::copy(run.begin(), run.end(), at + k::LAMINA_ALBEDO_BOOST_COLUMN);
  });
  return table;
}

int dielectric_albedo_bounded_entry(int combo, int i, int j, int c) {
  const int own = dielectric_albedo_table_entry(combo, i, j, c);
  if (!may_rise(i, j)) return own;
  int raise = 0;
  // The cells of which the node is a corner: first corners one step below it on each axis, or at it.
  for (int n = 0; n < 8; ++n) {
    const int ci = i - (n & 1), cj = j - ((n >> 1) & 1), cc = c - (n >> 2);
    if (ci < 0 || cj < 0 || cc < 0 || ci >= kCellsI || cj >= kCellsJ || cc >= kCellsK) continue;
    int corners[8];
    for (int m = 0; m < 8; ++m)
      corners[m] = dielectric_albedo_table_entry(combo, corner_i(ci, m), corner_j(cj, m), corner_c(cc, m));
    raise = std::max(raise, cell_lift(ci, cj, corners, cell_centre(combo, ci, cj, cc)));
  }
  return std::min(own + raise, 65535);
}

std::string dielectric_albedo_inc(const std::vector<int>& table) {
  std::string text =
      "// Generated from the kernels by graph/cpu/energy_table.cpp (LAMINA_UPDATE_TABLES=1 lamina_tests\n"
      "// -tc='the dielectric albedo table*'): energy.glsl's table, a row per cosine run, the runs of E,\n"
      "// then those of M, C, P, Q and B for each (combination, eta).\n";
  for (size_t at = 0; at < table.size(); ++at) {
    text += std::to_string(table[at]);
    const bool run_end = (at + 1) % size_t(k::LAMINA_ALBEDO_COSINES) == 0;
    text += at + 1 == table.size() ? "\n" : run_end ? ",\n" : ", ";
  }
  return text;
}

}  // namespace lamina::cpu
