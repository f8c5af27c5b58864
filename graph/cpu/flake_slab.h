// The full model of a paint of flakes, for ground truth: a binder slab of randomly oriented
// specular platelets over a Lambertian substrate, under a smooth binder-air boundary, solved by
// doubling and adding on discretised scattering operators (Ershov, Kolchin and Myszkowski 2001,
// "Rendering pearlescent appearance based on paint-composition modelling", sec. 4-5). Their fast
// two-layer model (sec. 6; nodes/kernels/flakes.glsl) approximates exactly this slab.
//
// Operators are kernels over (cos theta, cos theta', azimuth difference) of directions inside the
// binder: cos theta on Gauss-Legendre nodes split at the critical angle (where the boundary's
// transmission jumps to 0), the azimuth as a cosine series (the slab is isotropic, so each order
// is solved alone: the convolution in azimuth becomes a product). A sublayer thin enough for single
// scattering (2^-doublings of the slab) starts from eq. 9 with the attenuation along both paths
// integrated over its depth, so that grazing directions need no clipping (eq. 11); doubling (eq. 6)
// builds the slab, adding (eqs. 2, 3, 16, 17) puts the substrate under it and the boundary over it.
// The views asked for are extra nodes of weight 0: evaluated exactly, never integrated over.
#pragma once

#include <cstddef>
#include <vector>

namespace lamina::cpu {

// One channel of a flake paint.
struct FlakeSlab {
  double eta = 1.5;                  // the binder's index relative to air (>= 1)
  double coverage = 0.5;             // D <S> h: the flakes' total area per unit area of paint
  double flake_slope = 0.2;          // the slope of the flakes' normals about the paint's (Beckmann's RMS slope)
  int distribution = 0;              // their law, as the kernels number them: 0 Beckmann, 1 Blinn, 2 GGX
  double flake_reflectance = 0.5;    // r_p, from either side at any angle (the paper's mirror flakes)
  double flake_transmittance = 0.0;  // t_p: passes straight through a flake
  double binder_absorption = 0.0;    // kappa h: the binder's absorption depth at normal incidence
  double substrate_albedo = 0.5;     // r_s of the Lambertian substrate
  // Coated flakes (film_ior > 0): each flake a lossless film of index film_ior (absolute) and
  // thickness film_nm in the binder, reflecting Airy's reflectance at wavelength_nm for its angle
  // of incidence and passing the rest; flake_reflectance and flake_transmittance are then unused.
  double film_ior = 0.0;
  double film_nm = 0.0;
  double wavelength_nm = 525.0;
};

// The defaults keep a lossless slab's albedo within 3e-4 of 1 for flakes of slope 0.25 (64 orders
// left +3e-3: a truncated cosine series of a narrow lobe overshoots), in about 2 s.
struct FlakeSlabOptions {
  int nodes = 32;      // Gauss-Legendre nodes of cos theta on each side of the critical angle
  int modes = 128;     // cosine orders in azimuth
  int azimuths = 512;  // azimuths at which each order's coefficient of a kernel is summed
  int doublings = 14;  // the starting sublayer is 2^-doublings of the slab

  // A coarse solve in about 0.05 s: 12 nodes a side, 48 orders, 192 azimuths, 10 doublings; the
  // lossless furnace within 5e-3 of 1 (for quick looks, and the sanitised tests).
  static FlakeSlabOptions coarse() { return {12, 48, 192, 10}; }
};

class FlakeSlabSolution {
 public:
  // Solves `slab` for light from air at the cosines `views` (each in (0, 1]), which are also the
  // directions it is seen from. Throws std::invalid_argument for parameters outside their ranges.
  FlakeSlabSolution(const FlakeSlab& slab, std::vector<double> views, const FlakeSlabOptions& options = {});

  // The BRDF (without the cosine) from view i to view o at azimuth phi (radians) of o from the
  // plane of incidence, 0 on the side the light travels to (the mirror direction's), less the
  // boundary's mirror reflection, which is a delta.
  double brdf(size_t i, size_t o, double phi) const;
  // The share of light from view i that the slab returns through the boundary (brdf's albedo).
  double albedo(size_t i) const;
  // The boundary's mirror reflection of light from view i (the delta brdf leaves out).
  double mirror(size_t i) const;

 private:
  double eta_ = 1.0;
  std::vector<double> views_;
  std::vector<size_t> view_nodes_;      // the views' nodes in the binder
  std::vector<double> mu_, weight_;     // nodes and Gauss-Legendre weights of cos theta in the binder
  std::vector<std::vector<double>> x_;  // per order, the reflection kernel under the boundary (row = out)
};

}  // namespace lamina::cpu
