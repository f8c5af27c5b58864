// lamina kernels: the steps of the layered model's composition (Weidlich and Wilkie course,
// sec. 3.1-3.2; Elek 2010, Algorithm 1). The CPU evaluator loops over a stack calling these; the
// GLSL back end unrolls the same calls for each material, so both compute one sequence of float
// operations. Relative indices eta are n_below / n_above; frames and directions as in common.glsl.

// The Beckmann RMS slope of a roughness parameter: m = tan(angle) for roughness_deg (clamped to
// its declared 0..45 deg), the slope itself for alpha (clamped to 0..1).
LAMINA_FN float lamina_slope(float value, bool degrees) {
  if (degrees) return tan(clamp(value, 0.0f, 45.0f) * LAMINA_PI / 180.0f);
  return clamp(value, 0.0f, 1.0f);
}

// The slope a lobe uses: Elek sec. 3 raises it to at least the slope of the interfaces above it
// when clamp_lower is on; never below LAMINA_MIN_SLOPE, where the distributions stay finite.
LAMINA_FN float lamina_effective_slope(float own, float above, bool clamp_lower) {
  return max(clamp_lower ? max(own, above) : own, LAMINA_MIN_SLOPE);
}

// V.H and L.H are equal in exact arithmetic; their mean is bitwise the same when L and V swap, so
// rounding cannot break reciprocity where L + V nearly cancels (grazing, opposite directions).
LAMINA_FN float lamina_symmetric_dot(vec3 l, vec3 v, vec3 h) { return 0.5f * (dot(v, h) + dot(l, h)); }

// One interface of the recursion f(i)(L, V) = f_i(L, V) + T_i f(i+1)(L', V') a_i t_i (course
// sec. 3.1, Elek eq. 2). Returns f_i, the Torrance-Sparrow reflection of the interface with F_i
// at V.H (the Fresnel term `fresnel` selects: lamina_fresnel_dielectric). l_below and v_below
// receive L' and V' (z <= 0 when either cannot refract: then nothing below contributes), carry
// receives T_i a_i t_i with T_i = 1 - F_i, a_i the Beer-Lambert absorption (Elek eq. 3) and
// t_i = (1 - G_i) + T_i G_i (Elek eq. 4).
LAMINA_FN vec3 lamina_interface_eval(vec3 l, vec3 v, float eta, int distribution, int fresnel_mode, float m,
                                     vec3 sigma, float thickness, LAMINA_OUT(vec3) l_below,
                                     LAMINA_OUT(vec3) v_below, LAMINA_OUT(vec3) carry) {
  vec3 h = normalize(l + v);
  float v_dot_h = lamina_symmetric_dot(l, v, h);
  float fresnel = lamina_fresnel_dielectric(fresnel_mode, v_dot_h, eta);
  float d = d_microfacet_h(distribution, h, m);
  float g = g_microfacet(distribution, l.z, v.z, h.z, v_dot_h, m);
  l_below = refract_down(l, eta);
  v_below = refract_down(v, eta);
  carry = vec3(0.0f);
  if (l_below.z > 0.0f && v_below.z > 0.0f) {
    float transmittance = 1.0f - fresnel;
    carry = transmittance * absorption(sigma, thickness, l_below.z, v_below.z) * tir_compensation(transmittance, g);
  }
  return torrance_sparrow(vec3(fresnel), d, g, l.z, v.z);
}

// A rough conductor base: Torrance-Sparrow with the conductor Fresnel term at V.H (the one
// `fresnel_mode` selects: lamina_fresnel_conductor); eta and k are the metal's index relative to
// the medium above it (Elek's shader uses the absolute one).
LAMINA_FN vec3 lamina_conductor_eval(vec3 l, vec3 v, vec3 eta, vec3 k, int distribution, int fresnel_mode, float m) {
  vec3 h = normalize(l + v);
  float v_dot_h = lamina_symmetric_dot(l, v, h);
  vec3 fresnel = lamina_fresnel_conductor(fresnel_mode, v_dot_h, eta, k);
  float d = d_microfacet_h(distribution, h, m);
  float g = g_microfacet(distribution, l.z, v.z, h.z, v_dot_h, m);
  return torrance_sparrow(fresnel, d, g, l.z, v.z);
}

LAMINA_FN vec3 lamina_lambert_eval(vec3 l, vec3 v, vec3 albedo) {
  return (l.z > 0.0f && v.z > 0.0f) ? lambert(albedo) : vec3(0.0f);
}

// --- sampling ------------------------------------------------------------------------------------

// Lobe selection (course sec. 3.2.3) estimates each lobe's share at wo: its Fresnel reflectance
// or albedo times what the layers above let through twice. One layer of that product: returns wo
// refracted below an interface of relative index eta (z <= 0 when it cannot enter) and sets
// factor = (1 - F(cos wo))^2 times the luminance of the absorption along the refracted wo, with the
// interface's Fresnel term (fresnel_mode, as in lamina_interface_eval).
LAMINA_FN vec3 lamina_selection_step(vec3 v, float eta, int fresnel_mode, vec3 sigma, float thickness,
                                     LAMINA_OUT(float) factor) {
  float f0 = lamina_fresnel_dielectric(fresnel_mode, v.z, eta);
  vec3 below = refract_down(v, eta);
  factor = 0.0f;
  if (below.z > 0.0f) factor = lamina_sqr(1.0f - f0) * lamina_luminance(absorption(sigma, thickness, below.z, below.z));
  return below;
}

// Density of a microfacet reflection lobe over the whole sphere of directions w: the normal
// h = +-normalize(v + w) (the one above the horizon) drawn with density D(h) cos(h), times the
// Jacobian 1 / (4 |v.h|) of reflection (Walter et al. 2007, eq. 14).
LAMINA_FN float lamina_reflection_density(int distribution, float m, vec3 v, vec3 w) {
  vec3 sum = v + w;
  float len = length(sum);
  if (len < 1.0e-7f) return 0.0f;
  vec3 h = sum / len;
  if (h.z < 0.0f) h = -h;
  float v_dot_h = abs(dot(v, h));
  if (v_dot_h <= 0.0f) return 0.0f;
  // pdf_microfacet_normal (D cos_h) with D from h's components, as in the evaluation.
  return d_microfacet_h(distribution, h, m) * h.z / (4.0f * v_dot_h);
}

// Reflections that would leave below the horizon are mirrored back above it, so the lobe's
// density over the upper hemisphere is the sum of both halves and integrates to exactly 1.
LAMINA_FN float lamina_folded_reflection_density(int distribution, float m, vec3 v, vec3 w) {
  return lamina_reflection_density(distribution, m, v, w) +
         lamina_reflection_density(distribution, m, v, mirror_across_horizon(w));
}

// The direction with w's azimuth and the given cosine.
LAMINA_FN vec3 lamina_with_cosine(vec3 w, float cos_theta) {
  float sin_theta = lamina_safe_sqrt(1.0f - cos_theta * cos_theta);
  float planar = sqrt(w.x * w.x + w.y * w.y);
  if (planar <= 0.0f) return vec3(sin_theta, 0.0f, cos_theta);
  return vec3(w.x / planar * sin_theta, w.y / planar * sin_theta, cos_theta);
}

// The cosine of the critical angle in a medium of absolute index n > 1 under air.
LAMINA_FN float lamina_cos_critical(float n) { return sqrt(1.0f - 1.0f / (n * n)); }

// A lobe draws directions in its own frame, below the layers above it (absolute index n_frame).
// Directions inside the exit cone (sin < 1/n_frame) are carried up by Snell's law; a microfacet
// lobe's directions outside the cone, which cannot leave the stack, are spread over the outer
// hemisphere by cos_out = cos_in / cos_critical, so that every lobe's density integrates to 1.
// Diffuse lobes draw cosine-weighted directions inside the cone only.

// Density at the outer direction wi of a microfacet lobe of wo-in-frame v, where w_below is wi
// refracted down into the frame and jacobian = d omega_below / d omega_outside along that path.
LAMINA_FN float lamina_microfacet_lobe_pdf(int distribution, float m, vec3 v, vec3 w_below, float jacobian, vec3 wi,
                                           float n_frame) {
  float density = lamina_folded_reflection_density(distribution, m, v, w_below) * jacobian;
  if (n_frame > 1.0f) {
    float cos_c = lamina_cos_critical(n_frame);
    density += lamina_folded_reflection_density(distribution, m, v, lamina_with_cosine(wi, cos_c * wi.z)) * cos_c;
  }
  return density;
}

LAMINA_FN float lamina_diffuse_lobe_pdf(vec3 w_below, float jacobian, float n_frame) {
  return w_below.z * n_frame * n_frame * LAMINA_INV_PI * jacobian;
}

// Draws a microfacet lobe's direction: plain NDF sampling, reflected about h, mirrored above the
// horizon. Sets inside_cone: true when the result is a direction in the frame still to be carried
// up through the layers, false when it is already the outer direction. vec3(0) if none.
LAMINA_FN vec3 lamina_sample_microfacet_lobe(int distribution, float m, vec3 v, vec2 u, float n_frame,
                                             LAMINA_OUT(bool) inside_cone) {
  vec3 h = sample_microfacet_normal(distribution, m, u);
  vec3 w = 2.0f * dot(v, h) * h - v;
  if (w.z < 0.0f) w = mirror_across_horizon(w);
  inside_cone = true;
  if (w.z <= 0.0f) return vec3(0.0f);
  if ((1.0f - w.z * w.z) * n_frame * n_frame <= 1.0f) return w;
  inside_cone = false;
  return lamina_with_cosine(w, w.z / lamina_cos_critical(n_frame));
}

// Cosine-weighted inside the exit cone of a frame of absolute index n_frame: sin^2 uniform on
// [0, 1/n^2], which the refraction up maps onto the cosine distribution outside.
LAMINA_FN vec3 lamina_sample_diffuse_lobe(vec2 u, float n_frame) {
  float sin2 = u.x / (n_frame * n_frame);
  float phi = 2.0f * LAMINA_PI * u.y;
  float sin_theta = sqrt(sin2);
  return vec3(sin_theta * cos(phi), sin_theta * sin(phi), sqrt(1.0f - sin2));
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
