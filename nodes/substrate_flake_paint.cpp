// substrate/flake_paint: metallic and pearlescent paint, a binder of randomly oriented mirror flakes
// (aluminium chips, or mica coated with titanium dioxide) over a diffuse base, seen from inside the
// binder: the fast model of Ershov, Kolchin and Myszkowski 2001, sec. 6 (nodes/kernels/flakes.glsl).
// Its glitter is the flakes' reflection (eq. 36), its shade the base seen through them (eq. 32,
// Lambertian without binder absorption). Its flakes are plain (a reflectance and a transmittance)
// or coated with a thin film (interference platelets: colour-shifting paint). The binder's
// boundary above is a layer's interface, whose reflections the composition adds; the full model it
// approximates is graph/cpu/flake_slab.h.
#include <optional>
#include <string>
#include <vector>

#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/number_text.h"
#include "graph/value.h"
#include "nodes/film_params.h"
#include "nodes/kernels/kernels.h"
#include "nodes/microfacet_params.h"
#include "nodes/normal_param.h"

namespace lamina {

// A plain flake reflects at most what it does not pass: r_p + t_p <= 1 per channel, for constant
// values (a texture's are clamped so at shading time, lamina_stack_resolve). A coated flake's
// reflectance and transmittance are its film's: the plain flakes' parameters do not apply to it.
static void check_flake_paint(const NodeCheckContext& ctx) {
  if (ctx.get("film_thickness_nm")) {
    if (ctx.get("flake_transmittance"))
      ctx.error("flake_transmittance", "a coated flake passes what its film does not reflect",
                "leave flake_transmittance out, or the film (film_thickness_nm, film_ior) for plain flakes");
    return;
  }
  if (ctx.get("integration"))
    ctx.error("integration", "only coated flakes have a film whose spectrum is folded into RGB",
              "give film_thickness_nm and film_ior instead of flake_color, or leave integration out");
  const std::optional<double> transmittance = ctx.constant_channel("flake_transmittance", 0, 0.0);
  for (int c = 0; c < 3 && transmittance; ++c) {
    const std::optional<double> reflectance = ctx.constant_channel("flake_color", c, 0.0);
    if (reflectance && *reflectance + *transmittance > 1.0 + 1e-9) {
      ctx.error("flake_transmittance",
                "a flake would reflect " + number_text(*reflectance) + " and pass " + number_text(*transmittance) +
                    " of the light it receives, more than all of it",
                "keep flake_color + flake_transmittance at most 1 in every channel");
      return;
    }
  }
}

static void lower_flake_paint(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_FLAKE_PAINT;
  e.colour0 = n.input("base_color");
  e.scalar_x = n.input("coverage");
  // Coated flakes carry their film in the entry's Fresnel mode (lamina_entry_flakes); plain ones
  // their colour and transmittance.
  if (n.given("film_thickness_nm")) {
    lower_film_params(n, "film_thickness_nm", &StackEntry::scalar_w);
  } else {
    e.colour1 = n.input("flake_color");
    e.scalar_z = n.input("flake_transmittance");
  }
  lower_microfacet_params(n);
  lower_normal_param(n);
}

NodeDecl declare_substrate_flake_paint() {
  NodeDecl d;
  d.type = "substrate/flake_paint";
  d.kind = NodeKind::Substrate;
  d.doc =
      "metallic or pearlescent paint: mirror flakes in a binder over a diffuse base, under a layer's boundary "
      "(Ershov et al. 2001's fast model)";
  d.params.push_back(param("base_color", ValueType::Color)
                         .range(0.0, 1.0)
                         .links()
                         .described("diffuse reflectance of the base under the flakes (linear RGB)"));
  d.params.push_back(param("flake_color", ValueType::Color)
                         .range(0.0, 1.0)
                         .links()
                         .described("a plain flake's reflectance, either face, any angle (aluminium about 0.9); give "
                                    "this or a film"));
  d.params.push_back(param("flake_transmittance", ValueType::Float)
                         .range(0.0, 1.0)
                         .links()
                         .or_default(0.0)
                         .described("share of the light a plain flake passes straight through (mica: most of it)"));
  d.params.push_back(
      param("coverage", ValueType::Float)
          .range(0.0, 20.0)
          .links()
          .described("the flakes' total area per unit area of paint, D <S> h (1: as much flake as paint)"));
  // Coated flakes: a lossless film in the binder, reflecting its colour and passing the rest.
  add_film_params(d, "film_thickness_nm",
                  "coated flakes: the thickness of the film each flake is (titanium dioxide on mica: 40 to 200); "
                  "give this and film_ior or flake_color");
  d.alternatives.push_back({{{"flake_color"}, {"film_thickness_nm", "film_ior"}}, false});
  // The flakes' normals spread about the paint's as microfacets' do: roughness_deg or alpha is their
  // RMS slope, distribution their law.
  add_microfacet_params(d, false);
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  // The course's metallic paint (class e) is flakes under a varnish.
  d.metal = true;
  d.metal_noun = "flake";
  d.check = check_flake_paint;
  d.lower = lower_flake_paint;
  return d;
}

}  // namespace lamina
