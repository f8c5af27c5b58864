// substrate/thin_film: a rough base (a metal, or a dielectric that absorbs the light entering it)
// under a thin transparent film, whose two boundaries' reflections interfere: oil on asphalt or
// water, a soap film before a dark ground, the temper colours of heated steel (Granier and Heidrich
// 2003). Torrance-Sparrow with the film's reflectance (nodes/kernels/film.glsl) as its Fresnel term,
// so it composes, samples and conserves energy as substrate/conductor does, at any depth of a stack.
#include "graph/limits.h"
#include "graph/lowering.h"
#include "nodes/kernels/kernels.h"
#include "nodes/metals.h"
#include "nodes/microfacet_params.h"
#include "nodes/normal_param.h"

namespace lamina {

static void lower_thin_film(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_CONDUCTOR;
  lower_metal_params(n);
  e.colour2 = n.input("film_ior");
  e.scalar_z = n.input("thickness_nm");
  // The choices in the order of the declaration below.
  e.fresnel = n.choice("integration") == 0 ? kernels::LAMINA_FRESNEL_FILM_SPECTRAL : kernels::LAMINA_FRESNEL_FILM_RGB;
  lower_microfacet_params(n);
  lower_normal_param(n);
}

NodeDecl declare_substrate_thin_film() {
  NodeDecl d;
  d.type = "substrate/thin_film";
  d.kind = NodeKind::Substrate;
  d.doc = "rough opaque base (a named metal or its index n + ik) under a thin film whose reflections interfere";
  add_metal_params(d);
  d.params.push_back(param("thickness_nm", ValueType::Float)
                         .range(0.0, kMaxFilmThicknessNm)
                         .in_unit("nm")
                         .links()
                         .described("the film's thickness; 0 is the bare base"));
  d.params.push_back(param("film_ior", ValueType::Color)
                         .range(1.0, kMaxFilmIor)
                         .links()
                         .described("the film's index of refraction per channel (its dispersion), absolute"));
  d.params.push_back(
      param("integration", ValueType::Enum)
          .one_of_described({{"spectral",
                              "the reflectance averaged over each channel's spectral response (Belcour and Barla "
                              "2017): right at any thickness"},
                             {"rgb",
                              "the reflectance at 645, 525 and 445 nm (Granier and Heidrich 2003): aliases where the "
                              "optical path 2 n d exceeds about 1 um"}})
          .or_default(std::string("spectral"))
          .described("how the spectrum is folded into RGB"));
  add_microfacet_params(d, false);
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.lower = lower_thin_film;
  d.metal = true;
  return d;
}

}  // namespace lamina
