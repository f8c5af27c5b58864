// texture/image: an image file, addressed by a transformed uv.
#include <algorithm>
#include <cmath>

#include "graph/cpu/image.h"
#include "graph/diagnostics.h"
#include "graph/file_access.h"
#include "graph/glsl/op_writer.h"
#include "graph/lowering.h"
#include "graph/node_decl.h"
#include "graph/registers.h"
#include "nodes/kernels/kernels.h"

namespace lamina {

// The file is followed and decoded exactly as compiling the material will (file_access.h, the
// pixel budget), so that what validates also loads.
static void check_image(const NodeCheckContext& ctx) {
  const Value* file = ctx.get("file");
  if (!file || !std::holds_alternative<std::string>(*file)) return;
  const auto& name = std::get<std::string>(*file);
  try {
    const Reference ref = resolve_reference(ctx.file, name, ReferenceScope::AssetRoots, ctx.policy);
    const Value* space = ctx.get("color_space");
    const bool srgb = !space || std::get<std::string>(*space) == "srgb";
    load_image_reference(ref, srgb, ctx.policy);
  } catch (const ReferenceError& e) {
    ctx.error("file", std::string("texture file ") + e.what(), e.hint());
  } catch (const ImageError& e) {
    ctx.error("file", "texture file '" + name + "' is not a readable image: " + e.what(),
              "lamina reads PNG, JPEG, OpenEXR, Radiance HDR and TIFF; convert others, e.g. with oiiotool");
  }
}

// Inputs: uv_rotation_deg, uv_scale, uv_offset. Choices: wrap (repeat 0, clamp 1, mirror 2, as
// lamina_wrap_index numbers them). Outputs: color, value, alpha. The file is decoded here, once.
static void lower_image(NodeLowering& n) {
  TextureOp& op = n.op();
  op.inputs = {n.input("uv_rotation_deg"), n.input("uv_scale"), n.input("uv_offset")};
  op.choices = {n.choice("wrap")};
  op.file = n.text("file");
  try {
    const Reference ref = resolve_reference(n.file(), op.file, ReferenceScope::AssetRoots, n.policy());
    op.image = load_image_reference(ref, n.text("color_space") == "srgb", n.policy());
  } catch (const std::runtime_error& e) {  // ReferenceError, ImageError: the file changed since the check
    n.fail("texture file '" + op.file + "': " + e.what());
  }
}

static void run_image(const TextureOp& op, const ShadingContext& ctx, float* r) {
  const glm::vec2 uv = kernels::lamina_image_uv(ctx.uv, read_float(op.inputs[0], r), read_vec2(op.inputs[1], r),
                                                read_vec2(op.inputs[2], r));
  const glm::vec4 texel = sample_bilinear(*op.image, uv, Wrap(op.choices[0]));
  write_vec3(r, op.outputs[0], glm::vec3(texel));
  write_float(r, op.outputs[1], kernels::lamina_luminance(glm::vec3(texel)));
  write_float(r, op.outputs[2], texel.w);
}

// Bilinear filtering and wrapping done with texelFetch, exactly as the CPU does them, so results
// agree whatever sampler state the host sets.
const char* const kImageLookup =
    R"(// texture/image lookups: bilinear filtering and wrapping done here with texelFetch, exactly as the
// CPU evaluator does them, so results agree whatever sampler state the host sets.
vec4 lamina_image_bilinear(sampler2D image, vec2 uv, int wrap) {
  ivec2 size = textureSize(image, 0);
  ivec4 t;
  vec2 w = lamina_bilinear_texels(uv, size.x, size.y, wrap, t);
  vec4 top = mix(texelFetch(image, t.xy, 0), texelFetch(image, t.zy, 0), w.x);
  vec4 bottom = mix(texelFetch(image, t.xw, 0), texelFetch(image, t.zw, 0), w.x);
  return mix(top, bottom, w.y);
}

)";

static void emit_image(const TextureOp& op, glsl::OpWriter& w) {
  static const char* const kWrap[] = {"repeat", "clamp", "mirror"};
  w.module_code("lamina_image_bilinear", kImageLookup);
  w.comment(op.file + ", wrap " + kWrap[op.choices[0] % 3]);
  const std::string uv = w.local(op, "uv", "vec2",
                                 "lamina_image_uv(" + w.context("uv") + ", " + w.input(op, 0) + ", " + w.input(op, 1) +
                                     ", " + w.input(op, 2) + ")");
  const std::string texel =
      w.local(op, "texel", "vec4",
              "lamina_image_bilinear(" + w.sampler(op) + ", " + uv + ", " + std::to_string(op.choices[0]) + ")");
  w.output(op, 0, texel + ".xyz");
  w.output(op, 1, "lamina_luminance(" + texel + ".xyz)");
  w.output(op, 2, texel + ".w");
}

// Texels per uv unit: the image's larger side times the larger tiling factor.
static float uv_detail_image(const TextureOp& op) {
  if (!op.image) return 0.0f;
  return float(std::max(op.image->width, op.image->height)) * op.inputs[1].largest();
}

NodeDecl declare_texture_image() {
  NodeDecl d;
  d.type = "texture/image";
  d.kind = NodeKind::Texture;
  d.doc = "image file (PNG, JPEG, OpenEXR, Radiance HDR or TIFF) looked up at (rotate(uv) * uv_scale + uv_offset)";
  d.params.push_back(param("file", ValueType::String)
                         .described("image path, relative to the material file and inside the asset roots"));
  d.params.push_back(
      param("uv_scale", ValueType::Vec2).or_default(Vec2d{1.0, 1.0}).described("uv multiplier (tiling)"));
  d.params.push_back(
      param("uv_offset", ValueType::Vec2).or_default(Vec2d{0.0, 0.0}).described("uv shift after scaling"));
  d.params.push_back(param("uv_rotation_deg", ValueType::Float)
                         .range(-360.0, 360.0)
                         .in_unit("degrees")
                         .or_default(0.0)
                         .described("rotation of uv about (0.5, 0.5), counter-clockwise, before scaling"));
  d.params.push_back(param("wrap", ValueType::Enum)
                         .one_of({"repeat", "clamp", "mirror"})
                         .or_default(std::string("repeat"))
                         .described("what uv outside [0, 1] reads"));
  d.params.push_back(param("color_space", ValueType::Enum)
                         .one_of({"srgb", "linear"})
                         .or_default(std::string("srgb"))
                         .described("encoding of the stored values; srgb is decoded to linear"));
  d.outputs.push_back({"color", ValueType::Color, "linear RGB (grey images give r = g = b)"});
  d.outputs.push_back({"value", ValueType::Float, "luminance 0.2126 r + 0.7152 g + 0.0722 b"});
  d.outputs.push_back({"alpha", ValueType::Float, "the alpha channel, 1 when the image has none"});
  d.check = check_image;
  d.lower = lower_image;
  d.run = run_image;
  d.emit_glsl = emit_image;
  d.uv_detail = uv_detail_image;
  d.varies = true;
  d.gltf = "its file becomes a glTF image of the lossless extension; the fallback bakes its effect into textures";
  return d;
}

}  // namespace lamina
