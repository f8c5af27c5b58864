// The dielectric albedo table of nodes/kernels/energy.glsl, computed from the kernels: the
// directional albedo of lamina_boundary_reflection by quadrature over its normals.
#pragma once

#include <string>
#include <vector>

namespace lamina::cpu {

// The integral over the upper hemisphere of the boundary's reflection f(l, v) cos_l for a view of
// cosine mu, on n x n strata of the distribution's normal sampling (sample_microfacet_normal).
double dielectric_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n);

// The strata per side dielectric_albedo_table uses.
inline constexpr int kAlbedoTableStrata = 192;

// Every entry of the table, in the kernels' order (combination, eta, slope, cosine): round(65535 E),
// rounded up, so that 1 - E never exceeds what the boundary lets through by rounding.
std::vector<int> dielectric_albedo_table();

// One entry, computed as dielectric_albedo_table computes it.
int dielectric_albedo_table_entry(int combo, int i, int j, int k);

// The text of nodes/kernels/dielectric_albedo.inc for a table.
std::string dielectric_albedo_inc(const std::vector<int>& table);

}  // namespace lamina::cpu
