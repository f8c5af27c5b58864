#include "nodes/microfacet_params.h"

namespace lamina {

void add_microfacet_params(NodeDecl& decl, bool fresnel) {
  decl.params.push_back(param("roughness_deg", ValueType::Float)
                            .range(0.0, kMaxRoughnessDeg)
                            .in_unit("degrees")
                            .or_default(0.0)
                            .links()
                            .described("RMS microfacet slope angle; 0 is the smooth limit, 26-30 is very rough"));
  decl.params.push_back(param("alpha", ValueType::Float)
                            .range(0.0, kMaxAlpha)
                            .or_default(0.0)
                            .links()
                            .described("RMS microfacet slope m = tan(roughness_deg); give this or roughness_deg"));
  // The choices in the order of the kernels' codes (d_microfacet, lamina_fresnel_dielectric).
  decl.params.push_back(param("distribution", ValueType::Enum)
                            .one_of({"beckmann", "blinn", "ggx"})
                            .or_default(std::string("beckmann"))
                            .described("microfacet distribution: Beckmann, normalised Blinn (e = 2/m^2 - 2) or GGX"));
  if (fresnel)
    decl.params.push_back(
        param("fresnel", ValueType::Enum)
            .one_of({"exact", "schlick", "lazanyi"})
            .or_default(std::string("exact"))
            .described(
                "Fresnel term F: exact (the Fresnel equations), schlick (Schlick 1994, F0 from the exact term at "
                "normal incidence) or lazanyi (Lazanyi and Szirmay-Kalos 2005 as in Elek 2010, App. B)"));
  decl.alternatives.push_back({{{"roughness_deg"}, {"alpha"}}, true});
}

void lower_microfacet_params(NodeLowering& node) {
  StackEntry& e = node.entry();
  e.distribution = node.choice("distribution");
  if (find_param(node.decl().params, "fresnel")) e.fresnel = node.choice("fresnel");
  e.degrees = !node.given("alpha");
  e.scalar_y = node.input(e.degrees ? "roughness_deg" : "alpha");
}

}  // namespace lamina
