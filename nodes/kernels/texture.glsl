// lamina kernels: procedural textures and value conversions used by texture and math nodes.

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
