#include "graph/glsl/plane_shader.h"

#include "graph/glsl/glsl_text.h"
#include "graph/glsl/sphere_shader.h"

namespace lamina::glsl {

namespace {

// NAME stands for the material's prefix. The light, the sky estimator and the display are the
// sphere preview's (nodes/kernels/preview.glsl); the camera and the plane are this view's own.
const char* kPlane = R"(// ================================================================================
// --shader plane: the material on the ground plane z = 0, with uv its (x, y) in world units, seen
// from a pinhole camera one unit above the origin that looks along +y, 20 degrees down, with a
// vertical field of view of 60 degrees; above the horizon, the background. One evaluation per
// pixel, at its centre: the texture nodes filter over the pixel's footprint, taken from dFdx and
// dFdy of uv, so that glitter far away converges to its cells' mean instead of flickering. Lit by
// the preview's light (nodes/kernels/preview.glsl), turned to shine from beyond the plane towards
// the camera so that its reflection and the glitter's sparkles face the viewer, and its sky.
// ================================================================================

uniform vec2 lamina_viewport;                // viewport size in pixels
uniform float lamina_footprint_scale;        // 1: textures filter over the pixel; 0: point samples
uniform float lamina_ambient_radiance;       // the sky, as lamina plot --ambient; 0 for the light alone

layout(location = 0) out vec4 lamina_color;

// Towards the light: from beyond the plane, 25 degrees above its horizon.
const vec3 LAMINA_PLANE_LIGHT = vec3(0.0f, 0.906307787f, 0.422618262f);
// The camera: its position, and its forward, right and up axes (20 degrees below the horizon).
const vec3 LAMINA_PLANE_EYE = vec3(0.0f, 0.0f, 1.0f);
const vec3 LAMINA_PLANE_FORWARD = vec3(0.0f, 0.939692621f, -0.342020143f);
const vec3 LAMINA_PLANE_RIGHT = vec3(1.0f, 0.0f, 0.0f);
const vec3 LAMINA_PLANE_UP = vec3(0.0f, 0.342020143f, 0.939692621f);
const float LAMINA_PLANE_TAN_HALF_FOV = 0.577350269f;  // tan(30 degrees)

void main() {
  vec2 ndc = (2.0f * gl_FragCoord.xy - lamina_viewport) / lamina_viewport.y;
  vec3 ray = normalize(LAMINA_PLANE_FORWARD +
                       LAMINA_PLANE_TAN_HALF_FOV * (ndc.x * LAMINA_PLANE_RIGHT + ndc.y * LAMINA_PLANE_UP));
  // The hit is computed for every pixel (rays above the horizon hit far behind the camera, where
  // nothing is drawn), so that dFdx and dFdy are taken in uniform control flow, as GLSL requires.
  float t = LAMINA_PLANE_EYE.z / max(-ray.z, 1.0e-6f);
  vec3 p = LAMINA_PLANE_EYE + t * ray;
  vec2 uv = p.xy;
  float footprint = max(length(dFdx(uv)), length(dFdy(uv)));
  vec3 colour = lamina_preview_background();
  if (ray.z < 0.0f) {
    LaminaContext ctx = lamina_context(uv);
    ctx.position = p;
    ctx.view_distance = t;
    ctx.footprint = lamina_footprint_scale * footprint;
    LaminaPoint point = NAME_point(ctx);
    // The plane's shading frame is the world's: x along u, y along v, z its normal.
    vec3 wo = -ray;
    vec3 radiance = lamina_preview_light(NAME_eval(LAMINA_PLANE_LIGHT, wo, point), LAMINA_PLANE_LIGHT);
    if (lamina_ambient_radiance > 0.0f) {
      // wo itself, not turned to azimuth 0 as the sphere's: no table here, and tilted facets are
      // not isotropic.
      radiance += lamina_preview_sky(NAME_preview_sky_weights(wo, point), vec3(lamina_ambient_radiance));
    }
    colour = lamina_preview_display(radiance);
  }
  lamina_color = vec4(srgb_from_linear(colour), 1.0f);
}
)";

}  // namespace

std::string plane_shader(const std::string& prefix) {
  return preview_sky_weights(prefix) + replace_all(kPlane, "NAME", prefix);
}

}  // namespace lamina::glsl
