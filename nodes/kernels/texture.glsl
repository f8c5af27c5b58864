// lamina kernels: procedural textures and value conversions used by texture and math nodes.

// The shading context a material reads, as the C++ ShadingContext of graph/program.h: texture
// coordinates, world-space position, normal and tangent, the distance to the viewer and the pixel
// footprint in uv units (0: a point sample).
struct LaminaContext {
  vec2 uv;
  vec3 position;
  vec3 normal;
  vec3 tangent;
  float view_distance;
  float footprint;
};

// The context of a texture coordinate alone, every other member at ShadingContext's default.
LAMINA_FN LaminaContext lamina_context(vec2 uv) {
  LaminaContext ctx;
  ctx.uv = uv;
  ctx.position = vec3(0.0f);
  ctx.normal = vec3(0.0f, 0.0f, 1.0f);
  ctx.tangent = vec3(1.0f, 0.0f, 0.0f);
  ctx.view_distance = 1.0f;
  ctx.footprint = 0.0f;
  return ctx;
}

// A checkerboard in uv: 0 on the squares where floor(u sx) + floor(v sy) is even (the one holding
// uv = (0, 0) among them), 1 elsewhere; negative coordinates continue the pattern.
LAMINA_FN float checker_value(vec2 uv, vec2 scale) {
  float cells = floor(uv.x * scale.x) + floor(uv.y * scale.y);
  // cells mod 2, with a result in {0, 1} for negative sums as well.
  return cells - 2.0f * floor(0.5f * cells);
}

// Maps [in_min, in_max] linearly onto [out_min, out_max]:
// out_min + (v - in_min) / (in_max - in_min) (out_max - out_min); with clamp_output the result
// stays between out_min and out_max (either may be the larger). An empty input range, which the
// graph checker rejects, gives out_min. t and the result saturate at LAMINA_MAX_VALUE: with inputs
// of that magnitude at most, a nearly empty range cannot overflow to inf, and no inf - inf or
// 0 * inf makes a NaN that the next operation would pass on.
LAMINA_FN float remap_value(float v, float in_min, float in_max, float out_min, float out_max, bool clamp_output) {
  float span = in_max - in_min;
  float t = span != 0.0f ? clamp((v - in_min) / span, -LAMINA_MAX_VALUE, LAMINA_MAX_VALUE) : 0.0f;
  if (clamp_output) t = clamp(t, 0.0f, 1.0f);
  return clamp(out_min + t * (out_max - out_min), -LAMINA_MAX_VALUE, LAMINA_MAX_VALUE);
}

// Hermite smoothstep of v between edge0 and edge1: t = clamp((v - edge0) / (edge1 - edge0), 0, 1),
// t^2 (3 - 2 t) (the GLSL built-in's formula, written out because GLSL leaves edge0 >= edge1
// undefined). Reversed edges give the falling curve of the same formula; equal edges give the step
// v >= edge0. Inputs of magnitude up to LAMINA_MAX_VALUE give no NaN: only 0 / 0 could, and equal
// edges never divide.
LAMINA_FN float smoothstep_value(float v, float edge0, float edge1) {
  float span = edge1 - edge0;
  float t = span != 0.0f ? clamp((v - edge0) / span, 0.0f, 1.0f) : (v >= edge0 ? 1.0f : 0.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The sRGB EOTF per channel (IEC 61966-2-1:1999, sec. 5.2): c / 12.92 for c <= 0.04045, else
// ((c + 0.055) / 1.055)^2.4. The power's base is clamped at 0 so that negative inputs, which take
// the linear branch, never reach pow with a negative base.
LAMINA_FN vec3 srgb_to_linear(vec3 c) {
  vec3 lo = c / 12.92f;
  vec3 hi = pow(max((c + 0.055f) / 1.055f, vec3(0.0f)), vec3(2.4f));
  // step(c, 0.04045) is 1 exactly where c <= 0.04045.
  return mix(hi, lo, step(c, vec3(0.04045f)));
}

// The sRGB OETF per channel, the inverse of srgb_to_linear (IEC 61966-2-1:1999, sec. 5.3), for
// display: c is clamped to [0, 1], then 12.92 c for c <= 0.0031308, else 1.055 c^(1/2.4) - 0.055.
LAMINA_FN vec3 srgb_from_linear(vec3 c) {
  c = clamp(c, vec3(0.0f), vec3(1.0f));
  vec3 lo = 12.92f * c;
  vec3 hi = 1.055f * pow(c, vec3(1.0f / 2.4f)) - 0.055f;
  // step(c, 0.0031308) is 1 exactly where c <= 0.0031308.
  return mix(hi, lo, step(c, vec3(0.0031308f)));
}

// --- image lookups -------------------------------------------------------------------------------

// texture/image's uv transform: rotate about (0.5, 0.5) by rotation_deg, then scale, then offset.
LAMINA_FN vec2 lamina_image_uv(vec2 uv, float rotation_deg, vec2 scale, vec2 offset) {
  float angle = rotation_deg * LAMINA_PI / 180.0f;
  vec2 c = uv - vec2(0.5f);
  vec2 rotated = vec2(cos(angle) * c.x - sin(angle) * c.y, sin(angle) * c.x + cos(angle) * c.y);
  return (rotated + vec2(0.5f)) * scale + offset;
}

// i modulo period in [0, period) for i >= -2^20 (GLSL leaves % of negative operands undefined).
LAMINA_FN int lamina_positive_mod(int i, int period) {
  int shift = (1048576 / period + 1) * period;
  return (i + shift) % period;
}

// A texel index under a wrap mode: 0 repeat, 1 clamp to edge, 2 mirrored repeat.
LAMINA_FN int lamina_wrap_index(int i, int size, int wrap) {
  if (wrap == 1) return clamp(i, 0, size - 1);
  if (wrap == 2) {
    int j = lamina_positive_mod(i, 2 * size);
    return j < size ? j : 2 * size - 1 - j;
  }
  return lamina_positive_mod(i, size);
}

// Bilinear filtering as OpenGL's GL_LINEAR, texel centres at (i + 0.5) / size, row 0 at v = 0.
// Sets texels to the wrapped (x0, y0, x1, y1) and returns the weights (tx, ty) of x1 and y1.
// A non-finite uv reads texel (0, 0).
LAMINA_FN vec2 lamina_bilinear_texels(vec2 uv, int width, int height, int wrap, LAMINA_OUT(ivec4) texels) {
  float x = uv.x * float(width) - 0.5f;
  float y = uv.y * float(height) - 0.5f;
  // Not finite (NaN fails every comparison): read texel (0, 0).
  if (!(abs(x) <= 3.0e38f) || !(abs(y) <= 3.0e38f)) {
    texels = ivec4(0);
    return vec2(0.0f);
  }
  // Keep the integer part representable; repeat and mirror are periodic anyway.
  x = clamp(x, -1.0e6f, 1.0e6f);
  y = clamp(y, -1.0e6f, 1.0e6f);
  float fx = floor(x);
  float fy = floor(y);
  int x0 = int(fx);
  int y0 = int(fy);
  texels = ivec4(lamina_wrap_index(x0, width, wrap), lamina_wrap_index(y0, height, wrap),
                 lamina_wrap_index(x0 + 1, width, wrap), lamina_wrap_index(y0 + 1, height, wrap));
  return vec2(x - fx, y - fy);
}
