// The fallback a plain glTF viewer shows: glTF 2.0's reference BRDF (core metallic-roughness,
// spec appendix B) with KHR_materials_ior, KHR_materials_specular and KHR_materials_clearcoat,
// evaluated on the CPU, and the parameters of it fitted to a lamina material.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "graph/cpu/evaluator.h"

namespace lamina::gltf {

// Parameters of the glTF reference BRDF at one surface point; defaults are glTF's.
struct PbrParams {
  glm::vec3 base_color{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;          // perceptual; alpha = roughness^2
  float ior = 1.5f;                // KHR_materials_ior
  float specular = 1.0f;           // KHR_materials_specular: specularFactor
  glm::vec3 specular_color{1.0f};  // KHR_materials_specular: specularColorFactor
  float clearcoat = 0.0f;          // KHR_materials_clearcoat: clearcoatFactor
  float clearcoat_roughness = 0.0f;
  float iridescence = 0.0f;              // KHR_materials_iridescence: iridescenceFactor
  float iridescence_ior = 1.3f;          // iridescenceIor
  float iridescence_thickness = 400.0f;  // the film's thickness in nm (iridescenceThicknessMaximum)
};

// KHR_materials_iridescence's F_iridescence ("Implementation Notes", as published): the reflectance
// of a film of index film_ior and thickness (nm) between a medium of index outside_ior and a base
// of normal-incidence reflectance base_f0, at the cosine cos1 above the film: Schlick's terms at
// both boundaries, phases 0 or pi, two orders of Belcour and Barla's 2017 series with their
// sensitivity. Its optical path takes the film's cosine (the sample renderer's, and the physics);
// the extension's text writes the cosine above the film.
glm::vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos1, float thickness, glm::vec3 base_f0);

// The reference BRDF f(wi, wo) without the cosine, lamina's conventions (local frame, z up, both
// directions away from the surface, 0 below the horizon), composed from lamina's kernels
// (nodes/kernels/*.glsl). Roughness 0 (a delta lobe, which no BRDF value represents) is floored at
// alpha = kernels::LAMINA_MIN_SLOPE (1e-4). The specular lobe uses the separable Smith G of
// Appendix B sec. B.3.2 as the specification wrote it until January 2026, when KhronosGroup/glTF#2541
// replaced it with the height-correlated form to match glTF-Sample-Viewer; the
// clearcoat Fresnel uses N.V as KHR_materials_clearcoat writes it, so f is reciprocal only when
// clearcoat = 0.
glm::vec3 pbr_eval(const PbrParams& p, glm::vec3 wi, glm::vec3 wo);
// The same BRDF split as f = a + b * base_color (per channel): every other term is independent of
// the base colour, which lets a fit solve for it in closed form. With iridescence, the metal's
// film reflectance depends on the base colour otherwise: that part is in `a`, at p.base_color.
struct PbrAffine {
  glm::vec3 a{0.0f}, b{0.0f};
};
PbrAffine pbr_eval_affine(const PbrParams& p, glm::vec3 wi, glm::vec3 wo);
// Its directional albedo at wo (integral of f cos over the hemisphere), by deterministic quadrature.
glm::vec3 pbr_albedo(const PbrParams& p, glm::vec3 wo, int points = 4096);

// How well a fit matches (all in the material's own terms, over the fit's direction set).
struct FitError {
  float albedo_normal = 0.0f;   // max over channels of |A_fit - A| / max(A, 0.01) at normal incidence
  float albedo_grazing = 0.0f;  // the same at 80 degrees
  float rms = 0.0f;             // RMS of the objective's residuals, relative to the RMS of the target
  // What a person sees (appearance.h): the fallback's mean colour on the preview sphere against
  // the material's own, as CIE 1976 |Delta L*| and the distance of (a*, b*), hue and chroma
  // (chromatic_difference); about 1 is a just visible difference, 100 black against white.
  float lightness = 0.0f;
  float colour = 0.0f;
  // The share of albedo_normal no glTF material can reach: where the lamina material reflects more
  // than it receives (the layered model is not energy conserving, see the white furnace test), the
  // max over channels of (A - 1) / A at normal incidence; 0 for an energy-conserving target.
  float unreachable_normal = 0.0f;
};

struct FitResult {
  PbrParams params;
  FitError error;
  bool uses_ior = false, uses_specular = false, uses_clearcoat = false;  // which extensions help
  bool uses_iridescence = false;  // KHR_materials_iridescence: the material's surface is a thin film
};

// Any BRDF a fit can target: f(wi, wo) without the cosine and its directional albedo A(wo).
struct FitTarget {
  std::function<glm::vec3(glm::vec3 wi, glm::vec3 wo)> eval;
  std::function<glm::vec3(glm::vec3 wo)> albedo;
};

// Fits PbrParams to a target BRDF. Deterministic (fixed directions, grids and iteration counts).
//
// Directions: 6 views at 0, 25, 45, 60, 72 and 80 degrees from the normal; for each, wi from a fixed
// Hammersley set through 6 strategies (cosine-weighted, and GGX half-vectors of alpha 0.0015, 0.008,
// 0.04, 0.15, 0.5), weighted by the balance-heuristic mixture pdf, so that every lobe from a
// near-mirror coat to a diffuse base is represented in proportion to its energy whatever the target.
// Objective: with g = f cos(theta_i) / pdf (a Monte-Carlo term of the albedo; near a peak it is about
// the albedo times the relative error, so sharp peaks do not dominate), over views v and channels c
//   J = sum_v,c [ mean_k (g_fit - g)^2 + 4 (mean_k g_fit - mean_k g)^2 ],
// the second term making the directional albedo (what a viewer shows under even lighting) match.
// Base colour is the clamped closed-form least-squares optimum of J (f is affine in it); the other
// parameters: a coarse grid, then coordinate descent with step halving (fixed sweep count).
// Extensions are tried in the order clearcoat, ior, specular, each on top of those kept, and kept
// only when they lower J by more than 5% and by more than 1e-4 of the target's own J (the value with
// a zero fit), so that plain materials stay plain.
FitResult fit_pbr(const FitTarget& target);
// The fit of a material whose surface is a thin film (substrate/thin_film) with
// KHR_materials_iridescence: `film` holds the film (iridescence 1, its index and thickness), the
// base's reflectance at normal incidence as the base colour, which the extension's film takes for
// its base, and metallic 1; the fit searches the roughness alone.
FitResult fit_pbr_iridescent(const FitTarget& target, const PbrParams& film);

// Fits PbrParams to `material` at shading context `ctx` (textures resolve at ctx.uv), as its flat
// equivalent where a normal input tilts an entry (Evaluator::bind_untilted); with
// fit_pbr_iridescent where its surface is a thin film at that point. Deterministic.
FitResult fit_pbr(const cpu::Evaluator& material, const ShadingContext& ctx);

}  // namespace lamina::gltf
