// The scene `lamina preview` shows a material in: a unit sphere resting on a checkered floor, seen
// from slightly above, in a studio environment (a bright softbox to the upper left, a dimmer strip
// behind on the right, a sky gradient over a dark ground), so that a look-development artist sees
// the material's highlights, its colour in soft light and its Fresnel rim at a glance.
#pragma once

#include <memory>
#include <string>

#include "graph/cpu/image.h"
#include "graph/scene/scene.h"

namespace lamina::render {

// The preview scene of `material` from `materials` (a checked document read from `material_file`).
Scene preview_scene(const Document& materials, const std::filesystem::path& material_file, const std::string& material);

// The studio environment as an equirectangular image (equirect_uv's mapping), `width` x width / 2
// texels of radiance; the softbox gives about 2.8 lux at the sphere from its direction.
std::shared_ptr<const LinearImage> studio_environment(int width = 512);

}  // namespace lamina::render
