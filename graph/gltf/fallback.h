// The standard-PBR fallback of one lamina material: fitted glTF parameters, constant where the
// material is uniform and baked into textures where its texture nodes make it vary over uv.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "graph/gltf/pbr_fit.h"
#include "graph/program.h"

namespace lamina::gltf {

// An 8-bit image, rows top to bottom (uv (0, 0) is the top-left, as in glTF and lamina).
struct BakedImage {
  int size = 0;  // square
  int channels = 0;
  std::vector<uint8_t> pixels;
};

// The bake resolution a material gets unless told otherwise: twice its finest detail over uv (the
// largest NodeDecl::uv_detail of its texture nodes), rounded up to a power of two, within these.
// At most 512: a 1024 bake took Sunstone's export from 8 to 25 s and 0.5 GB (its 600 Voronoi cells
// per uv unit, a state per cell), where 512 texels already bake the cells' filtered mean.
inline constexpr int kMinAutoBakeSize = 64;
inline constexpr int kMaxAutoBakeSize = 512;

struct FallbackOptions {
  int bake_size = 0;   // texels per side of baked textures; 0: chosen per material (auto_bake_size)
  int max_states = 9;  // at most this many fits per textured material; texels between interpolate
};

// The automatic bake size of `program` (kMinAutoBakeSize for one without detail over uv).
int auto_bake_size(const Program& program);

struct Fallback {
  // Factors; where a texture carries a parameter its factor is 1 (the texture holds the value).
  PbrParams params;
  bool uses_ior = false, uses_specular = false, uses_clearcoat = false, uses_iridescence = false;
  std::optional<BakedImage> base_color;          // RGB, sRGB-encoded (glTF's baseColorTexture)
  std::optional<BakedImage> metallic_roughness;  // G roughness, B metallic, linear
  std::optional<BakedImage> clearcoat;           // R clearcoat, G clearcoat roughness, linear
  // KHR_materials_iridescence's iridescenceThicknessTexture: G, linear, from the thinnest film
  // (iridescence_thickness_min) to the thickest (params.iridescence_thickness); R is 1.
  std::optional<BakedImage> iridescence_thickness;
  float iridescence_thickness_min = 0.0f;
  // RGB, linear: the base's tangent-space normal (glTF's normalTexture), baked where the texture
  // nodes tilt the substrates' normals (flakes, glitter facets) by more than one byte's step.
  // lamina's shading frame is glTF's tangent space when the mesh's tangent has w = 1: x along the
  // tangent (u), y = normal x tangent, z the normal; so a texel stores lamina's (x, y, z) as is.
  std::optional<BakedImage> normal;
  // The same for the coat (KHR_materials_clearcoat's clearcoatNormalTexture) when the fit uses a
  // clearcoat: baked where the texture nodes tilt the top interface of some stack.
  std::optional<BakedImage> clearcoat_normal;
  // One fit per distinct texture state (one for an untextured material); `texels` says how many
  // baked texels had that state exactly (0: a representative others interpolate towards).
  struct State {
    FitResult fit;
    glm::vec2 uv{0.5f};
    int texels = 0;
  };
  std::vector<State> states;
  bool interpolated = false;  // more distinct states than max_states: texels interpolate fits
  int bake_size = 0;          // texels per side of the baked textures (0: nothing baked)
  FitError worst;             // the worst of each error over the states
};

// Fits the fallback of `program` (deterministic; the same program gives the same bytes).
Fallback fit_fallback(const Program& program, const FallbackOptions& options = {});

}  // namespace lamina::gltf
