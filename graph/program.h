// A compiled material: the texture operations that fill a register file of floats at a shading
// point, and the layer stack as the array of entries the kernels' composition walks
// (nodes/kernels/stack.glsl). A Program is immutable and valid by construction; back ends only
// read it, from any thread.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace lamina {

struct NodeDecl;
struct LinearImage;

// Everything a material may read at a shading point (DESIGN.md: bound once per hit). Positions,
// normals and tangents are in world space; the shading frame is built from normal and tangent, so
// that directions given in world space are turned into the local frame in one place
// (cpu::ShadingPoint). The defaults make world space the local frame.
struct ShadingContext {
  glm::vec2 uv{0.0f};
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};
  float view_distance = 1.0f;
  float footprint = 0.0f;  // pixel footprint in uv units; 0 = a point sample

  bool operator==(const ShadingContext&) const = default;
};

// A value a node reads: a constant folded at compile time, or `size` registers from `slot` on,
// clamped to the parameter's declared range [lo, hi] (a texture cannot push a parameter outside
// the model's domain). size: 1 a float, 2 a vec2, 3 a colour or a vec3.
struct InputRef {
  glm::vec3 constant{0.0f};
  int slot = -1;  // the first register, or -1 for the constant
  int size = 1;
  float lo = -std::numeric_limits<float>::infinity();
  float hi = std::numeric_limits<float>::infinity();
  std::string node;       // the node and parameter it came from: back ends name uniforms and
  std::string parameter;  // comments after them

  bool linked() const { return slot >= 0; }
  // The largest magnitude any of its `size` components can take: the constant's, or the top of a
  // link's range.
  float largest() const {
    if (linked()) return hi;
    float m = std::abs(constant.x);
    for (int c = 1; c < size && c < 3; ++c) m = std::max(m, std::abs(constant[c]));
    return m;
  }
};

// One texture or math node at a shading point: its behaviour (NodeDecl::run on the CPU,
// NodeDecl::emit_glsl in GLSL) reads `inputs` and writes its outputs' registers.
struct TextureOp {
  const NodeDecl* decl = nullptr;
  std::string node;                          // the node's id
  std::vector<InputRef> inputs;              // in the order the node's lowering adds them
  std::vector<int> outputs;                  // the first register of each declared output, in declaration order
  std::vector<int> choices;                  // enum and flag parameters, as the node's lowering encodes them
  std::shared_ptr<const LinearImage> image;  // texture/image: the decoded file
  std::string file;                          // texture/image: the file as written
};

// A colour or vec3 input (3 components), by default the constant c.
inline InputRef vec3_input(glm::vec3 c = glm::vec3(0.0f)) {
  InputRef r;
  r.constant = c;
  r.size = 3;
  return r;
}

// One entry of the stack as the kernels see it (LaminaEntry and LaminaInputs of
// nodes/kernels/stack.glsl), with where it came from.
struct StackEntry {
  // LaminaEntry: the kernels' constants (LAMINA_LAYER, LAMINA_SUBSTRATE_CONDUCTOR, ...).
  int kind = 0;
  int model = 0;
  int medium = 0;
  int distribution = 0;
  int fresnel = 0;
  bool degrees = false;  // the roughness input is an angle in degrees (else the slope itself)
  int parent = -1;
  int side = 0;
  int first = -1;
  int second = -1;
  // LaminaInputs, member by member; an input a model does not read stays a constant 0.
  InputRef colour0 = vec3_input(), colour1 = vec3_input(), colour2 = vec3_input();
  InputRef scalar_x, scalar_y, scalar_z, scalar_w;
  // The frame slot: a normal input will tilt the entry's frame; the shading normal until then.
  InputRef normal = vec3_input(glm::vec3(0.0f, 0.0f, 1.0f));

  // Where it came from: the layer, mix, select or substrate node, and a layer's interface and medium.
  const NodeDecl* decl = nullptr;
  std::string node;
  const NodeDecl* interface_decl = nullptr;
  std::string interface_node;
  const NodeDecl* medium_decl = nullptr;
  std::string medium_node;
  std::string note;  // for listings: e.g. the named metal a conductor's n and k came from
};

struct Program {
  std::string name;         // the material's name
  std::string source_file;  // the file it came from
  bool clamp_lower_roughness = true;
  int model = 0;  // LAMINA_MODEL_* of nodes/kernels/stack.glsl: 0 Weidlich-Wilkie, 1 energy-conserving
  int slot_count = 0;
  std::vector<TextureOp> ops;     // run in order; each reads only registers written before it
  std::vector<StackEntry> stack;  // depth first from the surface (entry 0): parents before children

  bool textured() const { return !ops.empty(); }
};

}  // namespace lamina
