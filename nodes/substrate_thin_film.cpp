// substrate/thin_film: a rough base (a metal, or a dielectric that absorbs the light entering it)
// under a thin transparent film, whose two boundaries' reflections interfere: oil on asphalt or
// water, a soap film before a dark ground, the temper colours of heated steel (Granier and Heidrich
// 2003). Torrance-Sparrow with the film's reflectance (nodes/kernels/film.glsl) as its Fresnel term,
// so it composes, samples and conserves energy as substrate/conductor does, at any depth of a stack.
#include "graph/lowering.h"
#include "nodes/film_params.h"
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
  lower_film_params(n, "thickness_nm", &StackEntry::scalar_z);
  lower_microfacet_params(n);
  lower_normal_param(n);
}

NodeDecl declare_substrate_thin_film() {
  NodeDecl d;
  d.type = "substrate/thin_film";
  d.kind = NodeKind::Substrate;
  d.doc = "rough opaque base (a named metal or its index n + ik) under a thin film whose reflections interfere";
  add_metal_params(d);
  add_film_params(d, "thickness_nm", "the film's thickness; 0 is the bare base");
  add_microfacet_params(d, false);
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.lower = lower_thin_film;
  d.metal = true;
  return d;
}

}  // namespace lamina
