// substrate/conductor: a rough metal, Torrance-Sparrow with the conductor Fresnel term (exact by
// default; course sec. 2.1). Metals are opaque, so a conductor is always the bottom of a stack.
#include "graph/lowering.h"
#include "graph/number_text.h"
#include "nodes/kernels/kernels.h"
#include "nodes/metals.h"
#include "nodes/microfacet_params.h"
#include "nodes/normal_param.h"

namespace lamina {

// Each named metal with its constants and their source, for `lamina nodes` and schema/nodes.md.
static std::vector<std::pair<std::string, std::string>> described_metals() {
  auto triple = [](const Vec3d& v) { return number_text(v[0]) + ", " + number_text(v[1]) + ", " + number_text(v[2]); };
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& m : metals())
    out.emplace_back(m.name, "n (" + triple(m.n) + "), k (" + triple(m.k) + "); " + std::string(m.source));
  return out;
}

// A named metal's tabulated n and k, as the constants the parameters would have given.
static InputRef metal_constant(NodeLowering& n, const char* parameter, const Vec3d& value) {
  InputRef r;
  r.constant = glm::vec3(float(value[0]), float(value[1]), float(value[2]));
  r.size = 3;
  r.node = n.id();
  r.parameter = parameter;
  return r;
}

static void lower_conductor(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_CONDUCTOR;
  if (n.given("metal")) {
    const Metal* metal = find_metal(n.text("metal"));
    e.colour0 = metal_constant(n, "n", metal->n);
    e.colour1 = metal_constant(n, "k", metal->k);
    e.note = n.text("metal");
  } else {
    e.colour0 = n.input("n");
    e.colour1 = n.input("k");
  }
  lower_microfacet_params(n);
  lower_normal_param(n);
}

NodeDecl declare_substrate_conductor() {
  NodeDecl d;
  d.type = "substrate/conductor";
  d.kind = NodeKind::Substrate;
  d.doc = "rough metal base: a named metal or its complex index of refraction n + ik per channel";
  d.params.push_back(param("metal", ValueType::Enum)
                         .one_of_described(described_metals())
                         .described("a named metal with tabulated n and k; give this or n and k"));
  d.params.push_back(param("n", ValueType::Color)
                         .above(0.0)
                         .at_most(kMaxConductorIndex)
                         .links()
                         .described("real part of the metal's index of refraction per channel"));
  d.params.push_back(param("k", ValueType::Color)
                         .range(0.0, kMaxConductorIndex)
                         .links()
                         .described("extinction coefficient (imaginary part of the index) per channel"));
  add_microfacet_params(d);
  d.alternatives.push_back({{{"metal"}, {"n", "k"}}, false});
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.lower = lower_conductor;
  d.metal = true;
  return d;
}

}  // namespace lamina
