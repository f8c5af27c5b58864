#include "graph/gltf/pbr_to_layers.h"

#include <algorithm>
#include <cmath>

#include "graph/limits.h"
#include "graph/number_text.h"

namespace lamina::gltf {

namespace {

// lamina's interface/dielectric accepts 1 <= ior <= 4.
constexpr double kMaxIor = 4.0;
// A conductor reflecting everything needs k = infinity; 0.999 keeps k finite (k = 63.2).
constexpr double kMaxMetalF0 = 0.999;
// KHR_materials_clearcoat: the coat is a fixed ior 1.5 dielectric.
constexpr double kClearcoatIor = 1.5;

Param param(std::string name, Value value) { return Param{std::move(name), std::move(value)}; }
Value link(const std::string& node) { return Link{node, {}}; }

// glTF 2.0 Appendix B: alpha = roughness^2 for the GGX distribution (Walter et al. 2007), which
// is lamina's GGX alpha (its "m").
Node microfacet_node(std::string id, std::string type, std::vector<Param> before, double roughness) {
  Node node{std::move(id), std::move(type), std::move(before)};
  double r = std::clamp(roughness, 0.0, 1.0);
  node.params.push_back(param("alpha", r * r));
  node.params.push_back(param("distribution", std::string("ggx")));
  return node;
}

std::string text(double value) { return number_text(value); }

}  // namespace

double f0_from_ior(double ior) {
  double r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}

double ior_from_f0(double f0) {
  double s = std::sqrt(std::clamp(f0, 0.0, 1.0));
  return (1.0 + s) / (1.0 - s);
}

double conductor_k_from_f0(double f0) { return 2.0 * std::sqrt(f0 / (1.0 - f0)); }

double specular_f0(const PbrMaterial& pbr) {
  double f0 = f0_from_ior(pbr.ior);
  double sum = 0.0;
  for (double c : pbr.specular_color) sum += std::min(f0 * c, 1.0) * pbr.specular;
  return sum / 3.0;
}

Material layered_from_pbr(const std::string& name, const PbrMaterial& pbr, std::vector<std::string>& notes) {
  Material m;
  m.name = name;
  const double metallic = std::clamp(pbr.metallic, 0.0, 1.0);
  const double clearcoat = std::clamp(pbr.clearcoat, 0.0, 1.0);
  const double iridescence = std::clamp(pbr.iridescence, 0.0, 1.0);
  if (iridescence > 0.0 && metallic < 1.0)
    notes.push_back(name +
                    ": iridescence over the non-metallic part is not imported (lamina's films lie on opaque bases)");
  std::string top;

  std::string dielectric;
  if (metallic < 1.0) {
    if (pbr.base_color_texture) {
      m.nodes.push_back(Node{"base_color",
                             "texture/image",
                             {param("file", pbr.base_color_texture->file), param("wrap", pbr.base_color_texture->wrap),
                              param("color_space", std::string("srgb"))}});
      m.nodes.push_back(Node{"diffuse", "substrate/lambert", {param("albedo", Link{"base_color", "color"})}});
    } else {
      m.nodes.push_back(Node{"diffuse",
                             "substrate/lambert",
                             {param("albedo", Vec3d{pbr.base_color[0], pbr.base_color[1], pbr.base_color[2]})}});
    }
    // Without KHR_materials_specular's scaling the ior is used as given (no round trip through F0).
    const bool plain = pbr.specular == 1.0 && pbr.specular_color == std::array<double, 3>{1.0, 1.0, 1.0};
    double f0 = specular_f0(pbr);
    double ior = plain ? pbr.ior : ior_from_f0(f0);
    if (!(ior <= kMaxIor)) {
      notes.push_back(name + ": dielectric reflectance " + text(f0) + " needs ior " + text(ior) +
                      ", clamped to lamina's maximum " + text(kMaxIor));
      ior = kMaxIor;
    }
    m.nodes.push_back(microfacet_node("specular", "interface/dielectric", {param("ior", ior)}, pbr.roughness));
    m.nodes.push_back(
        Node{"dielectric", "layer", {param("interface", link("specular")), param("base", link("diffuse"))}});
    dielectric = top = "dielectric";
  }

  if (metallic > 0.0) {
    Vec3d n{}, k{};
    bool clamped = false;
    for (size_t c = 0; c < 3; ++c) {
      double f0 = std::clamp(pbr.base_color[c], 0.0, 1.0);
      if (f0 > kMaxMetalF0) {
        f0 = kMaxMetalF0;
        clamped = true;
      }
      n[c] = 1.0;
      k[c] = conductor_k_from_f0(f0);
    }
    if (clamped)
      notes.push_back(name + ": a metal base colour of 1 reflects everything; clamped to " + text(kMaxMetalF0) +
                      " for a finite extinction coefficient");
    if (pbr.base_color_texture)
      notes.push_back(name +
                      ": the metal's colour comes from baseColorFactor; lamina cannot derive n and k from a "
                      "texture, so baseColorTexture only tints the non-metallic part");
    if (iridescence < 1.0)
      m.nodes.push_back(microfacet_node("metal", "substrate/conductor", {param("n", n), param("k", k)}, pbr.roughness));
    top = "metal";
    if (iridescence > 0.0) {
      // KHR_materials_iridescence: the metal's Fresnel term is mix(F, F_iridescence, factor), a mix
      // of the bare metal and the same metal under the film (lamina's film is exact where the
      // extension's takes Schlick's terms and phases of 0 or pi).
      const double film_ior = std::clamp(pbr.iridescence_ior, 1.0, kMaxFilmIor);
      if (film_ior != pbr.iridescence_ior)
        notes.push_back(name + ": iridescenceIor " + text(pbr.iridescence_ior) + " is clamped to " + text(film_ior));
      m.nodes.push_back(
          microfacet_node("film", "substrate/thin_film",
                          {param("n", n), param("k", k),
                           param("thickness_nm", std::clamp(pbr.iridescence_thickness, 0.0, kMaxFilmThicknessNm)),
                           param("film_ior", Vec3d{film_ior, film_ior, film_ior})},
                          pbr.roughness));
      top = "film";
      if (iridescence < 1.0) {
        m.nodes.push_back(Node{"iridescence_mix",
                               "mix",
                               {param("weight", iridescence), param("a", link("metal")), param("b", link("film"))}});
        top = "iridescence_mix";
      }
    }
    if (metallic < 1.0) {
      // glTF 2.0 Appendix B: material = mix(dielectric_brdf, metal_brdf, metallic).
      m.nodes.push_back(Node{
          "metallic_mix", "mix", {param("weight", metallic), param("a", link(dielectric)), param("b", link(top))}});
      top = "metallic_mix";
    }
  }

  if (clearcoat > 0.0) {
    m.nodes.push_back(
        microfacet_node("clearcoat", "interface/dielectric", {param("ior", kClearcoatIor)}, pbr.clearcoat_roughness));
    m.nodes.push_back(Node{"coated", "layer", {param("interface", link("clearcoat")), param("base", link(top))}});
    std::string under = top;
    top = "coated";
    if (clearcoat < 1.0) {
      // KHR_materials_clearcoat: coated = mix(material, layered, clearcoat) (its fresnel_coat).
      m.nodes.push_back(Node{
          "clearcoat_mix", "mix", {param("weight", clearcoat), param("a", link(under)), param("b", link("coated"))}});
      top = "clearcoat_mix";
    }
  }
  m.surface = Link{top, {}};
  return m;
}

}  // namespace lamina::gltf
