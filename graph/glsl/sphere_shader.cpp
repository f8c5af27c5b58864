#include "graph/glsl/sphere_shader.h"

#include "graph/glsl/glsl_text.h"

namespace lamina::glsl {

namespace {

// NAME stands for the material's prefix.
const char* kSphere = R"(// ================================================================================
// --shader sphere: a unit sphere filling the viewport's shorter side, seen orthographically along
// -z, lit by a directional light and a constant ambient (estimated with the material's own
// importance sampling). Set lamina_viewport; the constants below are free to edit.
// ================================================================================

uniform vec2 lamina_viewport;  // viewport size in pixels
const vec3 lamina_light_direction = vec3(-1.0f, 1.0f, 1.0f);  // towards the light (normalised below)
const vec3 lamina_light_irradiance = vec3(LAMINA_PI);        // at normal incidence
const vec3 lamina_ambient_radiance = vec3(0.08f);
const vec3 lamina_background = vec3(0.12f, 0.12f, 0.13f);
const int lamina_ambient_samples = 16;

layout(location = 0) out vec4 lamina_color;

void main() {
  vec2 q = (2.0f * gl_FragCoord.xy - lamina_viewport) / min(lamina_viewport.x, lamina_viewport.y);
  float r2 = dot(q, q);
  if (r2 >= 1.0f) {
    lamina_color = vec4(srgb_from_linear(lamina_background), 1.0f);
    return;
  }
  vec3 n = vec3(q, sqrt(1.0f - r2));
  // Tangent along the lines of latitude about the y axis; uv = (longitude, latitude from the top).
  vec3 t = vec3(n.z, 0.0f, -n.x);
  t = dot(t, t) > 1.0e-12f ? normalize(t) : vec3(1.0f, 0.0f, 0.0f);
  vec3 b = cross(n, t);
  vec2 uv = vec2(atan(n.x, n.z) / (2.0f * LAMINA_PI) + 0.5f, acos(clamp(n.y, -1.0f, 1.0f)) / LAMINA_PI);
  vec3 view = vec3(0.0f, 0.0f, 1.0f);
  vec3 light = normalize(lamina_light_direction);
  vec3 wo = normalize(vec3(dot(t, view), dot(b, view), dot(n, view)));
  vec3 wi = normalize(vec3(dot(t, light), dot(b, light), dot(n, light)));
  vec3 radiance = vec3(0.0f);
  if (wi.z > 0.0f) {
    radiance += NAME_eval(wi, wo, uv) * wi.z * lamina_light_irradiance;
  }
  // Ambient: the directional albedo at wo by the material's sampling (the same point set in every
  // pixel, so the image is smooth, not noisy).
  vec3 albedo = vec3(0.0f);
  for (int i = 0; i < lamina_ambient_samples; ++i) {
    float x = (float(i) + 0.5f) / float(lamina_ambient_samples);
    vec2 u = vec2(x, fract(float(i) * 0.618034f + 0.5f));
    float u_layer = fract(float(i) * 0.754878f + 0.25f);
    vec3 w;
    float pdf;
    vec3 f = NAME_sample(wo, u, u_layer, uv, w, pdf);
    if (pdf > 0.0f) {
      albedo += f * w.z / pdf;
    }
  }
  radiance += lamina_ambient_radiance * albedo / float(lamina_ambient_samples);
  lamina_color = vec4(srgb_from_linear(radiance), 1.0f);
}
)";

}  // namespace

std::string sphere_shader(const std::string& prefix) { return replace_all(kSphere, "NAME", prefix); }

}  // namespace lamina::glsl
