// texture/image: an image file read through OpenImageIO, addressed by a transformed uv.
#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "graph/diagnostics.h"
#include "graph/node_decl.h"

namespace lamina {

// The file must exist and be an image OpenImageIO can read; relative paths start at the
// directory of the material file.
static void check_image(const NodeCheckContext& ctx) {
  const Value* file = ctx.get("file");
  if (!file || !std::holds_alternative<std::string>(*file)) return;
  const auto& name = std::get<std::string>(*file);
  std::filesystem::path path(name);
  if (path.is_relative()) path = std::filesystem::path(ctx.file).parent_path() / path;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    ctx.error("file", "texture file '" + name + "' not found (looked for " + path.string() + ")",
              "paths are relative to the material file");
    return;
  }
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    std::string why = OIIO::geterror();
    ctx.error("file", "texture file '" + name + "' is not a readable image" + (why.empty() ? "" : ": " + why),
              "lamina reads what OpenImageIO reads: PNG, JPEG, OpenEXR, TIFF, HDR, ...");
    return;
  }
  input->close();
}

NodeDecl declare_texture_image() {
  NodeDecl d;
  d.type = "texture/image";
  d.kind = NodeKind::Texture;
  d.doc = "image file (any format OpenImageIO reads) looked up at (rotate(uv) * uv_scale + uv_offset)";
  d.params.push_back(param("file", ValueType::String).described("image path, relative to the material file"));
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
