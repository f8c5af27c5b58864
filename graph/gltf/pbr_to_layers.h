// The reverse of the fallback fit: a glTF core metallic-roughness material (with
// KHR_materials_ior, _specular and _clearcoat) approximated by a lamina layer stack.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "graph/document.h"

namespace lamina::gltf {

// What the conversion reads from a glTF material, already reduced to numbers (textures other
// than the base colour are averaged or dropped by the caller, which also writes the notes).
struct PbrMaterial {
  std::array<double, 3> base_color{1.0, 1.0, 1.0};  // linear RGB, baseColorFactor
  double metallic = 1.0;                            // glTF defaults (glTF 2.0 sec. 5.22)
  double roughness = 1.0;
  double ior = 1.5;       // KHR_materials_ior
  double specular = 1.0;  // KHR_materials_specular specularFactor
  std::array<double, 3> specular_color{1.0, 1.0, 1.0};
  double clearcoat = 0.0;  // KHR_materials_clearcoat clearcoatFactor
  double clearcoat_roughness = 0.0;
  double iridescence = 0.0;              // KHR_materials_iridescence iridescenceFactor
  double iridescence_ior = 1.3;          // iridescenceIor
  double iridescence_thickness = 400.0;  // nm: iridescenceThicknessMaximum, or the texture's mean
  // A texture/image node feeding the diffuse albedo instead of base_color.
  struct Texture {
    std::string file;
    std::string wrap;  // "repeat", "clamp" or "mirror"
  };
  std::optional<Texture> base_color_texture;
};

// Normal-incidence reflectance of a dielectric boundary: ((ior - 1) / (ior + 1))^2 (Fresnel).
double f0_from_ior(double ior);
// Its inverse, ior = (1 + sqrt(f0)) / (1 - sqrt(f0)), for 0 <= f0 < 1.
double ior_from_f0(double f0);
// Extinction coefficient of a conductor with n = 1 reflecting f0 at normal incidence: from
// f0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) with n = 1, k = 2 sqrt(f0 / (1 - f0)).
double conductor_k_from_f0(double f0);
// The dielectric F0 of KHR_materials_specular (its "dielectric_f0", per channel
// min(f0(ior) * specularColorFactor, 1) * specularFactor), reduced to one number: the mean of the
// channels, since a lamina interface has one ior.
double specular_f0(const PbrMaterial& pbr);

// The stack: a GGX dielectric interface (ior from the specular F0, alpha = roughness^2, glTF 2.0
// Appendix B) over a Lambert base with the base colour, blended by `metallic` (mix node) with a
// GGX conductor (n = 1, k from the base colour as F0); clearcoat > 0 adds a dielectric layer
// (ior 1.5, alpha = clearcoatRoughness^2) on top, blended by the clearcoat factor. Factors of
// exactly 0 or 1 give no mix node. `notes` receives what the stack cannot carry.
Material layered_from_pbr(const std::string& name, const PbrMaterial& pbr, std::vector<std::string>& notes);

}  // namespace lamina::gltf
