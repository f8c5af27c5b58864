// What a person sees of a material: its mean colour on lamina plot's sphere, and the CIE 1976
// L*a*b* differences that compare two such colours. The glTF fallback's fit reports how far the
// fallback's sphere is from the material's own, in lightness and in colour (hue and chroma).
#pragma once

#include <glm/glm.hpp>

#include "graph/gltf/pbr_fit.h"

namespace lamina::gltf {

// CIE 1976 L*a*b* of a linear sRGB colour: IEC 61966-2-1's primaries to XYZ, then CIE 15's
// L*a*b* relative to the D65 white (L* 100 for linear (1, 1, 1)).
glm::vec3 lab_from_linear_srgb(glm::vec3 rgb);

// How far apart two L*a*b* colours are in colour, apart from lightness: the distance of their
// (a*, b*), sqrt(Delta E*ab^2 - Delta L*^2), which counts a change of hue and a loss of chroma alike
// (a fallback turned grey differs by the material's whole chroma C* = sqrt(a*^2 + b*^2)).
float chromatic_difference(glm::vec3 lab_a, glm::vec3 lab_b);

// The mean displayed colour, linear sRGB, of a uniform material on the preview sphere of
// nodes/kernels/preview.glsl: its view, its directional light and a uniform sky of radiance
// LAMINA_PREVIEW_AMBIENT, each point the clipped radiance lamina_preview_display shows: f under the
// light plus the sky times the directional albedo at the view (tabulated over its cosine). Points
// are the centres of a resolution x resolution grid over the sphere's square.
glm::vec3 sphere_colour(const FitTarget& material, int resolution = 64);

}  // namespace lamina::gltf
