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

struct FallbackOptions {
  int bake_size = 256;  // texels per side of baked textures
  int max_states = 9;   // at most this many fits per textured material; texels between interpolate
};

struct Fallback {
  // Factors; where a texture carries a parameter its factor is 1 (the texture holds the value).
  PbrParams params;
  bool uses_ior = false, uses_specular = false, uses_clearcoat = false;
  std::optional<BakedImage> base_color;          // RGB, sRGB-encoded (glTF's baseColorTexture)
  std::optional<BakedImage> metallic_roughness;  // G roughness, B metallic, linear
  std::optional<BakedImage> clearcoat;           // R clearcoat, G clearcoat roughness, linear
  // One fit per distinct texture state (one for an untextured material); `texels` says how many
  // baked texels had that state exactly (0: a representative others interpolate towards).
  struct State {
    FitResult fit;
    glm::vec2 uv{0.5f};
    int texels = 0;
  };
  std::vector<State> states;
  bool interpolated = false;  // more distinct states than max_states: texels interpolate fits
  FitError worst;             // the worst of each error over the states
};

// Fits the fallback of `program` (deterministic; the same program gives the same bytes).
Fallback fit_fallback(const Program& program, const FallbackOptions& options = {});

}  // namespace lamina::gltf
