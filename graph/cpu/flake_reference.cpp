#include "graph/cpu/flake_reference.h"

#include <algorithm>
#include <stdexcept>

#include "nodes/kernels/kernels.h"

namespace lamina::cpu {

namespace k = kernels;

FlakePaintSlabs flake_paint_slabs(const ShadingPoint& point) {
  const ShadingPoint::Stack stack = point.stack();
  const auto refuse = [](const char* why) { throw std::invalid_argument(why); };
  if (stack.count != 2 || stack.entries[0].kind != k::LAMINA_LAYER ||
      !k::lamina_is_flake_paint(stack.entries[stack.entries[0].first]))
    refuse("the full flake model takes a material whose surface is a layer over a substrate/flake_paint, alone");
  if (stack.entries[0].medium == k::LAMINA_MEDIUM_ABSORBING)
    refuse(
        "the full flake model takes the layer's medium clear (a tinted binder absorbs among the flakes, not "
        "above them)");
  const k::LaminaParams& layer = stack.params[0];
  if (layer.ior < 1.0f) refuse("the full flake model takes a binder of index at least 1");
  const k::LaminaEntry& e = stack.entries[1];
  const k::LaminaParams& p = stack.params[1];
  FlakePaintSlabs slabs;
  slabs.boundary_slope = layer.m;
  slabs.spectral_fold = e.fresnel == k::LAMINA_FRESNEL_FILM_SPECTRAL;
  const double wavelengths[3] = {645.0, 525.0, 445.0};
  for (int c = 0; c < 3; ++c) {
    FlakeSlab& s = slabs.channels[size_t(c)];
    s.eta = double(layer.ior);
    s.coverage = double(p.flake_paint.x);
    s.flake_slope = double(p.m);
    s.distribution = e.distribution;
    s.flake_transmittance = double(p.flake_paint.y);
    // As the kernels take it (lamina_flake_optics): a plain flake reflects at most what it does not pass.
    s.flake_reflectance = std::min(double(p.flake[c]), 1.0 - s.flake_transmittance);
    s.substrate_albedo = double(p.flake_base[c]);
    if (k::lamina_is_film(e.fresnel)) {
      s.film_ior = double(p.film_eta[c] * p.n_above);
      s.film_nm = double(p.film_depth / p.n_above);
      s.wavelength_nm = wavelengths[c];
    }
  }
  return slabs;
}

}  // namespace lamina::cpu
