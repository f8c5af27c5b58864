#include "graph/cpu/energy_table.h"

#include <cmath>

#include "graph/parallel.h"
#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace k = lamina::kernels;
using glm::vec2;
using glm::vec3;

double dielectric_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n) {
  const vec3 v(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  double sum = 0.0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      vec2 u((float(a) + 0.5f) / float(n), (float(b) + 0.5f) / float(n));
      vec3 h = k::sample_microfacet_normal(distribution, m, u);
      float v_dot_h = glm::dot(v, h);
      if (v_dot_h <= 0.0f) continue;
      vec3 l = 2.0f * v_dot_h * h - v;
      if (l.z <= 0.0f) continue;
      l = glm::normalize(l);
      // The density of l: D(h) cos_h / (4 v.h) (Walter et al. 2007, eq. 14), with D from h's
      // components as the evaluation computes it (for narrow lobes cos_h rounds to 1).
      double pdf = double(k::d_microfacet_h(distribution, h, m)) * double(h.z) / (4.0 * double(v_dot_h));
      if (!(pdf > 0.0)) continue;
      sum += double(k::lamina_boundary_reflection(l, v, eta, distribution, fresnel, m)) * double(l.z) / pdf;
    }
  }
  return sum / (double(n) * double(n));
}

int dielectric_albedo_table_entry(int combo, int i, int j, int k_) {
  const int distribution = combo / 2;
  const int fresnel = combo % 2;  // 0 exact, 1 Schlick (the same table as Lazanyi)
  const float eta = k::lamina_albedo_node_eta(i);
  double e = dielectric_albedo_quadrature(distribution, fresnel, k::lamina_albedo_node_cosine(k_, eta),
                                          k::lamina_albedo_node_slope(j), eta, kAlbedoTableStrata);
  return int(std::min(65535.0, std::ceil(std::max(0.0, e) * 65535.0)));
}

std::vector<int> dielectric_albedo_table() {
  const int per_eta = k::LAMINA_ALBEDO_SLOPES * k::LAMINA_ALBEDO_COSINES;
  const int etas = k::LAMINA_ALBEDO_COMBOS * k::LAMINA_ALBEDO_ETAS;
  std::vector<int> table(size_t(etas) * size_t(per_eta));
  parallel_for(size_t(etas), [&](size_t row) {
    int combo = int(row) / k::LAMINA_ALBEDO_ETAS;
    int i = int(row) % k::LAMINA_ALBEDO_ETAS;
    for (int j = 0; j < k::LAMINA_ALBEDO_SLOPES; ++j)
      for (int c = 0; c < k::LAMINA_ALBEDO_COSINES; ++c)
        table[row * size_t(per_eta) + size_t(j * k::LAMINA_ALBEDO_COSINES + c)] =
            dielectric_albedo_table_entry(combo, i, j, c);
  });
  return table;
}

std::string dielectric_albedo_inc(const std::vector<int>& table) {
  std::string text =
      "// Generated from the kernels by graph/cpu/energy_table.cpp (LAMINA_UPDATE_TABLES=1 lamina_tests\n"
      "// -tc='the dielectric albedo table*'): round(65535 E) of energy.glsl's grid, a row per cosine run.\n";
  for (size_t at = 0; at < table.size(); ++at) {
    text += std::to_string(table[at]);
    bool row_end = (at + 1) % size_t(k::LAMINA_ALBEDO_COSINES) == 0;
    text += at + 1 == table.size() ? "\n" : row_end ? ",\n" : ", ";
  }
  return text;
}

}  // namespace lamina::cpu
