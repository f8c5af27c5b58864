#include "graph/glsl/sphere_shader.h"

#include "graph/glsl/glsl_text.h"

namespace lamina::glsl {

namespace {

// NAME stands for the material's prefix. The preview's definition is in the lamina_preview_*
// kernels (nodes/kernels/preview.glsl), which the module embeds because this code calls them; the
// loops here are the ones graph/cpu/preview.cpp runs with the CPU evaluator.
const char* kSphere = R"(// ================================================================================
// --shader sphere: the material preview of lamina plot (nodes/kernels/preview.glsl above): a unit
// sphere filling the viewport's shorter side, seen orthographically along -z, lit by a directional
// light and a uniform sky whose reflection is estimated with the material's own importance
// sampling, from the same points in every pixel. Set lamina_viewport; lamina_ambient_radiance is
// free to edit (0 for the light alone), the rest of the preview is in the kernels.
// ================================================================================

uniform vec2 lamina_viewport;  // viewport size in pixels
const vec3 lamina_ambient_radiance = vec3(LAMINA_PREVIEW_AMBIENT);  // the sky, as lamina plot --ambient

layout(location = 0) out vec4 lamina_color;

void main() {
  vec2 pixel = floor(gl_FragCoord.xy);
  vec3 sum = vec3(0.0f);
  vec3 sky = vec3(0.0f);
  bool have_sky = false;
  for (int s = 0; s < LAMINA_PREVIEW_SUBSAMPLES * LAMINA_PREVIEW_SUBSAMPLES; ++s) {
    vec2 q = lamina_preview_disk(lamina_preview_subsample(pixel, s), lamina_viewport);
    if (!lamina_preview_on_sphere(q)) {
      sum += lamina_preview_background();
      continue;
    }
    vec3 n = lamina_preview_normal(q);
    // resolved once for the light and the sky
    LaminaContext ctx = lamina_preview_context(q, lamina_viewport);
    LaminaPoint point = NAME_point(ctx);
    vec3 wo = lamina_preview_local(LAMINA_PREVIEW_VIEW, n);
    vec3 wi = lamina_preview_local(LAMINA_PREVIEW_LIGHT, n);
    vec3 radiance = vec3(0.0f);
    if (wi.z > 0.0f) {
      radiance = lamina_preview_light(NAME_eval(wi, wo, point), wi);
    }
    // The sky once per pixel, at its first subsample on the sphere.
    if (lamina_ambient_radiance != vec3(0.0f) && !have_sky) {
      vec3 weights = NAME_preview_sky_weights(lamina_preview_sky_view(wo), point);
      sky = lamina_preview_sky(weights, lamina_ambient_radiance);
      have_sky = true;
    }
    sum += lamina_preview_display(radiance + sky);
  }
  lamina_color = vec4(srgb_from_linear(lamina_preview_mean(sum)), 1.0f);
}
)";

const char* kSkyWeights = R"(// The preview's sky estimator for one view at one point (nodes/kernels/preview.glsl).
vec3 NAME_preview_sky_weights(vec3 view, LaminaPoint point) {
  vec3 weights = vec3(0.0f);
  for (int i = 0; i < LAMINA_PREVIEW_SKY_POINTS; ++i) {
    vec3 p = lamina_preview_sky_point(i);
    vec3 w;
    float pdf;
    vec3 f = NAME_sample(view, p.xy, p.z, point, w, pdf);
    weights += lamina_preview_sky_weight(f, w, pdf);
  }
  return weights;
}

)";

}  // namespace

std::string preview_sky_weights(const std::string& prefix) { return replace_all(kSkyWeights, "NAME", prefix); }

std::string sphere_shader(const std::string& prefix) {
  return preview_sky_weights(prefix) + replace_all(kSphere, "NAME", prefix);
}

}  // namespace lamina::glsl
