// The dielectric albedo table of nodes/kernels/energy.glsl, computed from the kernels: the
// directional albedo of lamina_boundary_reflection by quadrature over its normals.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lamina::cpu {

// The integral over the upper hemisphere of the boundary's reflection f(l, v) cos_l for a view of
// cosine mu, on n x n strata of the distribution's normal sampling (sample_microfacet_normal).
double dielectric_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n);

// The same integral for the lobe the energy-conserving composition reflects, raised by the table's
// boost: f(l, v) (1 + b(l) b(v)), b read from block B as the kernels read it (energy.glsl).
double raised_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n);

// The same integral for the reflection of one scattering event on the Smith microsurface the
// reference solver walks (graph/cpu/microsurface.h), whose masking and shadowing are height-correlated:
// G2 = 1 / (1 + Lambda(l) + Lambda(v)) (Heitz 2014, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs", eq. 99) in place of the model's G1(l) G1(v).
double height_correlated_albedo_quadrature(int distribution, int fresnel, float mu, float m, float eta, int n);

// What random walks over that microsurface (Heitz, Hanika, d'Eon and Dachsbacher 2016) from a view
// of cosine mu find, deterministic for a seed: `multiple`, the mean weight of the walks that leave
// above after two events or more (what the boundary reflects beyond single scattering); and for
// those that leave below (every event counted), the ratios r of lamina_rough_transmittance
// (energy.glsl), x_s / g with x_s = 1 / mu_below the path per unit thickness of a smooth boundary's
// refracted light: `path_ratio` with g the mean of x = 1 / |cos| (the limit of depth 0),
// `depth_ratio` with g = -ln(mean of exp(-depth x)) / depth at depth LAMINA_ALBEDO_PATH_DEPTH, each
// mean weighted by the walks' weights; at most LAMINA_ALBEDO_PATH_RANGE, and 1 where nothing passes.
// At grazing views most of what passes has scattered more than once, on shorter paths than single
// scattering's (at 89 degrees through a GGX boundary of slope 0.25 and index 1.45, the mean path is
// 1.7 times a smooth boundary's where single scattering's is 2.4 times).
struct MicrosurfaceStatistics {
  double multiple = 0.0;
  double path_ratio = 1.0;
  double depth_ratio = 1.0;
};
MicrosurfaceStatistics microsurface_statistics(int distribution, int fresnel, float mu, float m, float eta, int walks,
                                               uint64_t seed);

// The share of a conductor lobe (lamina_conductor_eval with a Fresnel term of 1: D G / (4 cos_l
// cos_v)) that a view of cosine mu sends into the cone cos_l > cone_cosine, integrated with cos_l, on
// n x n strata of the distribution's normal sampling. cone_cosine 0 gives the lobe's whole albedo.
double conductor_cone_quadrature(int distribution, float mu, float m, float cone_cosine, int n);

// The strata per side dielectric_albedo_table uses.
inline constexpr int kAlbedoTableStrata = 192;

// The walks per node for the multiply scattered part: a standard error of at most sqrt(E_ms / 32768),
// 0.0011 where E_ms reaches 0.04.
inline constexpr int kMultipleScatteringWalks = 32768;

// The whole table in the kernels' order (albedo_grid.glsl: a row per combination and eta, each of
// the blocks E, M, C, P, Q and B): E as round(65535 E) rounded up and then raised to bound E between the nodes
// too (below); M as round(65535 M), at most 65535 - E.
//
// Why E is raised: the energy-conserving composition lets 1 - E - M through a boundary whose lobe
// reflects its true E (times its gain), so wherever the table's E falls short the two add up to more
// than 1. Interpolation falls short between nodes where E curves (grazing views of smooth
// boundaries): for every cell of the grid, the interpolation at its centre is compared with E
// there, and the cell's corners are raised by kAlbedoBoundMargin times the shortfall (each node by
// the most any of its cells asks), except the nodes at eta = 1, which stay 0 (an index-matched
// boundary reflects nothing), and at m = 0, which stay the Fresnel reflectance (a smooth boundary
// reflects exactly that). M is lowered where E + M would exceed 1.
std::vector<int> dielectric_albedo_table();
inline constexpr double kAlbedoBoundMargin = 1.5;

// One entry of the block C (albedo_grid.glsl): the conductor lobe of the combination's distribution
// inside the exit cone of eta node i (the whole hemisphere where eta <= 1), as round(65535 C)
// rounded down.
int conductor_cone_table_entry(int combo, int i, int j, int k);

// One entry of the block P (at_depth false) or Q (true): round(65535 r / LAMINA_ALBEDO_PATH_RANGE) of
// the node's microsurface_statistics (the walks of its M), 1 at the nodes of a smooth boundary.
int transmitted_path_table_entry(int combo, int i, int j, int k, bool at_depth);

// One entry of E as the table holds it: the quadrature's, raised as above.
int dielectric_albedo_bounded_entry(int combo, int i, int j, int k);

// One entry of E as the quadrature gives it, before the raise.
int dielectric_albedo_table_entry(int combo, int i, int j, int k);

// One entry of M before the final cap at 65535 - E, given the node's entry of E before the raise
// (`single`).
int dielectric_multiple_table_entry(int combo, int i, int j, int k, int single);

// One run of block B (albedo_grid.glsl), the boost b of the boundary's lobe at each cosine node of
// (combination, eta node i, slope node j), given the run's final entries of M (`multiple`, after
// the cap at 65535 - E) as the table holds them: the b >= 0 for which the lobe f (1 + b(l) b(v))
// reflects its own E plus M at every node, b(mu) int f(l, v) b(v) cos_v = M(mu) with b
// interpolated along the cosine axis as the kernels read it, by kBoostIterations of the symmetric
// scaling iteration b <- sqrt(b M / (K b)), stored as floor(65535 b / LAMINA_ALBEDO_BOOST_RANGE).
// 0 for a smooth boundary (slope node 0), which scatters once only.
std::vector<int> boundary_boost_run(int combo, int i, int j, const int* multiple);
inline constexpr int kBoostIterations = 200;

// The text of nodes/kernels/dielectric_albedo.inc for a table.
std::string dielectric_albedo_inc(const std::vector<int>& table);

}  // namespace lamina::cpu
