// texture/image: an image file, addressed by a transformed uv.
#include "graph/cpu/image.h"
#include "graph/diagnostics.h"
#include "graph/file_access.h"
#include "graph/node_decl.h"

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
  return d;
}

}  // namespace lamina
