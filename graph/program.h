// A compiled material: the texture operations that fill a register file of floats at a shading
// point, and the layer stack as a small tree whose parameters are constants or registers.
// A Program is immutable and valid by construction; evaluators only read it, from any thread.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace lamina {

// What a texture node reads at a shading point (DESIGN.md: the shading context flows into every
// texture node, so later nodes can filter by footprint or use position and tangents).
struct ShadingContext {
  glm::vec2 uv{0.0f};
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};
  float view_distance = 1.0f;
  float footprint = 0.0f;  // pixel footprint in uv units; 0 = a point sample
};

// A float input: a folded constant, or register `slot` when >= 0.
struct ScalarRef {
  float constant = 0.0f;
  int slot = -1;
};
// A colour input: a folded constant, or registers slot, slot+1, slot+2 when slot >= 0.
struct ColorRef {
  glm::vec3 constant{0.0f};
  int slot = -1;
};

enum class Distribution { Beckmann = 0, Blinn = 1, Ggx = 2 };
// The Fresnel term of a microfacet node; the values are the kernels' fresnel_mode
// (lamina_fresnel_dielectric, lamina_fresnel_conductor in nodes/kernels/fresnel.glsl).
enum class Fresnel { Exact = 0, Schlick = 1, Lazanyi = 2 };

// Roughness as the file gave it: an angle in degrees (m = tan) or the slope alpha itself.
struct RoughnessRef {
  ScalarRef value;
  bool degrees = true;
};

// --- texture operations, run in order ------------------------------------------------------------

struct LinearImage;  // texels decoded to linear floats (graph/cpu/image.h)

// Every operation and stack part keeps the id of the node it came from (`node`), so that back ends
// can name their variables, uniforms and comments after the user's graph.
struct CheckerOp {
  ColorRef color_a, color_b;
  glm::vec2 scale{8.0f};
  int color_slot = -1, value_slot = -1;
  std::string node;
};
struct ImageOp {
  std::shared_ptr<const LinearImage> image;
  std::string file;  // as written in the material (for back ends that bind their own textures)
  glm::vec2 uv_scale{1.0f}, uv_offset{0.0f};
  float uv_rotation_deg = 0.0f;
  int wrap = 0;  // 0 repeat, 1 clamp, 2 mirror
  int color_slot = -1, value_slot = -1, alpha_slot = -1;
  std::string node;
};
struct RemapOp {
  ScalarRef value;
  float in_min = 0.0f, in_max = 1.0f, out_min = 0.0f, out_max = 1.0f;
  bool clamp = true;
  int value_slot = -1;
  std::string node;
};
using TextureOp = std::variant<CheckerOp, ImageOp, RemapOp>;

// --- the stack ------------------------------------------------------------------------------------
// Each kind is its own struct; the evaluators dispatch with std::visit, so a new interface,
// medium or substrate kind adds a struct here and its functions, not a change to the recursion.

struct DielectricInterface {
  ScalarRef ior;  // absolute index of the layer below
  RoughnessRef roughness;
  Distribution distribution = Distribution::Beckmann;
  Fresnel fresnel = Fresnel::Exact;
  std::string node;
};
using LayerInterface = std::variant<DielectricInterface>;

struct ClearMedium {
  std::string node;  // empty when the layer names no medium
};
struct AbsorbingMedium {
  ScalarRef thickness;  // micrometres
  ColorRef absorption;  // per micrometre
  std::string node;
};
using LayerMedium = std::variant<ClearMedium, AbsorbingMedium>;

struct LayerNode {
  LayerInterface interface;
  LayerMedium medium;
  int base = -1;  // index into Program::stack
  std::string node;
};
struct MixNode {
  ScalarRef weight;
  int a = -1, b = -1;
  std::string node;
};
struct LambertNode {
  ColorRef albedo;
  std::string node;
};
struct OrenNayarNode {
  ColorRef albedo;
  ScalarRef sigma;
  std::string node;
};
struct ConductorNode {
  ColorRef n, k;  // absolute complex index
  RoughnessRef roughness;
  Distribution distribution = Distribution::Beckmann;
  Fresnel fresnel = Fresnel::Exact;
  std::string node;
  std::string metal;  // the named metal n and k came from, if any
};
using StackNode = std::variant<LayerNode, MixNode, LambertNode, OrenNayarNode, ConductorNode>;

struct Program {
  std::string name;         // the material's name
  std::string source_file;  // the file it came from
  bool clamp_lower_roughness = true;
  int slot_count = 0;
  std::vector<TextureOp> ops;
  std::vector<StackNode> stack;
  int root = -1;  // index of the surface in `stack`
};

}  // namespace lamina
