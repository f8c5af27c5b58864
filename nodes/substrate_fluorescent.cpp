// substrate/fluorescent: a Lambertian base whose pigment re-radiates part of the light it absorbs
// at longer wavelengths (Weidlich and Wilkie course, sec. 5.2.2: day-glo card, fluorescent paint
// under a varnish). Its albedo is a matrix (nodes/kernels/diffuse.glsl, lamina_fluorescent_albedo);
// the compositions carry light of a colour through it (stack.glsl, lamina_stack_glows), so a
// layer above it keeps the incident colour in its reflection while the body shifts it.
#include <optional>
#include <string>
#include <vector>

#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/number_text.h"
#include "graph/value.h"
#include "nodes/kernels/kernels.h"
#include "nodes/normal_param.h"

namespace lamina {

// No channel may give back more than it receives: what stays in green (albedo[1]) and what green
// re-radiates as red at most 1; blue likewise with both its shifts.
static void check_fluorescent(const NodeCheckContext& ctx) {
  struct Column {
    const char* name;
    int channel;
    std::vector<const char*> shifts;
  };
  const Column columns[] = {{"green", 1, {"green_to_red"}}, {"blue", 2, {"blue_to_red", "blue_to_green"}}};
  for (const Column& c : columns) {
    std::optional<double> total = ctx.constant_channel("albedo", c.channel, 0.0);
    std::string terms = "albedo[" + std::to_string(c.channel) + "]";
    const char* named = "albedo";  // the error's pointer: the last shift the file gives
    for (const char* s : c.shifts) {
      std::optional<double> shift = ctx.constant_channel(s, 0, 0.0);
      if (!total || !shift) {
        total.reset();
        break;
      }
      *total += *shift;
      terms += std::string(" + ") + s;
      if (ctx.get(s)) named = s;
    }
    if (total && *total > 1.0 + 1e-9)
      ctx.error(named,
                "the " + std::string(c.name) + " light this base returns, " + terms + " = " + number_text(*total) +
                    ", exceeds the light it receives",
                "keep " + terms + " at most 1 (each channel returns at most what it receives)");
  }
}

static void lower_fluorescent(NodeLowering& n) {
  StackEntry& e = n.entry();
  e.kind = kernels::LAMINA_SUBSTRATE;
  e.model = kernels::LAMINA_SUBSTRATE_FLUORESCENT;
  e.colour0 = n.input("albedo");
  e.scalar_x = n.input("green_to_red");
  e.scalar_y = n.input("blue_to_red");
  e.scalar_z = n.input("blue_to_green");
  lower_normal_param(n);
}

NodeDecl declare_substrate_fluorescent() {
  NodeDecl d;
  d.type = "substrate/fluorescent";
  d.kind = NodeKind::Substrate;
  d.doc = "diffuse opaque base whose pigment re-radiates absorbed light at longer wavelengths (fluorescence)";
  d.params.push_back(param("albedo", ValueType::Color)
                         .range(0.0, 1.0)
                         .links()
                         .described("diffuse reflectance per channel without change of colour (linear RGB)"));
  const char* shifts[][2] = {
      {"green_to_red", "share of the green light the base receives that it re-radiates as red"},
      {"blue_to_red", "share of the blue light the base receives that it re-radiates as red"},
      {"blue_to_green", "share of the blue light the base receives that it re-radiates as green"}};
  for (const auto& s : shifts)
    d.params.push_back(param(s[0], ValueType::Float).range(0.0, 1.0).links().or_default(0.0).described(s[1]));
  add_normal_param(d);
  d.outputs.push_back({"stack", ValueType::Stack, "an opaque base, for a layer's base or a material's surface"});
  d.check = check_fluorescent;
  d.lower = lower_fluorescent;
  d.gltf = "baked into the fitted PBR fallback as its colour under white light (glTF has no fluorescence)";
  return d;
}

}  // namespace lamina
