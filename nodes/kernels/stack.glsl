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

// One interface of the recursion f(i)(L, V) = f_i(L, V) + T_i f(i+1)(L', V') a_i t_i (course
// sec. 3.1, Elek eq. 2). Returns f_i, the Torrance-Sparrow reflection of the interface with F_i
// at V.H (the Fresnel term `fresnel` selects: lamina_fresnel_dielectric). l_below and v_below
// receive L' and V' (z <= 0 when either cannot refract: then nothing below contributes), passed
// receives T_i t_i with T_i = 1 - F_i and t_i = (1 - G_i) + T_i G_i (Elek eq. 4), 0 where nothing
// below contributes; the caller applies the layer's Beer-Lambert absorption a_i (Elek eq. 3) along
// L' and V', together or one way each (a glowing stack's light changes colour in between). F_i and
// T_i are RGB: a dielectric's are grey, a coated boundary's need not be.
LAMINA_FN vec3 lamina_interface_eval(vec3 l, vec3 v, float eta, int distribution, int fresnel_mode, float m,
                                     LAMINA_OUT(vec3) l_below, LAMINA_OUT(vec3) v_below, LAMINA_OUT(vec3) passed) {
  vec3 h = normalize(l + v);
  float v_dot_h = lamina_symmetric_dot(l, v, h);
  vec3 fresnel = vec3(lamina_fresnel_dielectric(fresnel_mode, v_dot_h, eta));
  float d = d_microfacet_h(distribution, h, m);
  float g = g_microfacet(distribution, l.z, v.z, h.z, v_dot_h, m);
  l_below = refract_down(l, eta);
  v_below = refract_down(v, eta);
  passed = vec3(0.0f);
  if (l_below.z > 0.0f && v_below.z > 0.0f) {
    vec3 transmittance = vec3(1.0f) - fresnel;
    passed = transmittance * tir_compensation(transmittance, g);
  }
  return torrance_sparrow(fresnel, d, g, l.z, v.z);
}

// A rough conductor base: Torrance-Sparrow with the base's Fresnel term at V.H (the one
// `fresnel_mode` selects: lamina_fresnel_base, a conductor's or a thin film's over it); eta and k are
// the metal's index relative to the medium above it (Elek's shader uses the absolute one), film_eta
// and depth the film's (film.glsl).
LAMINA_FN vec3 lamina_conductor_eval(vec3 l, vec3 v, vec3 eta, vec3 k, vec3 film_eta, float depth, int distribution,
                                     int fresnel_mode, float m) {
  vec3 h = normalize(l + v);
  float v_dot_h = lamina_symmetric_dot(l, v, h);
  vec3 fresnel = lamina_fresnel_base(fresnel_mode, v_dot_h, eta, k, film_eta, depth);
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
  // |v.h| = (1 + v.w) / |v + w| = |v + w| / 2 for unit v and w. The dot product would cancel where
  // w nears -v (the folded half's integrable singularity at the mirror direction): there 1 + v.w is
  // the difference of nearly equal numbers, and the density came out with 0.5% noise.
  float v_dot_h = 0.5f * len;
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
// All three in the lobe's frame: w_below the outer direction refracted down (read where jacobian >
// 0), spread the direction the lobe's spread outside the cone maps onto the outer direction
// (lamina_spread_source; none where its z <= 0).
LAMINA_FN float lamina_microfacet_lobe_pdf(int distribution, float m, vec3 v, vec3 w_below, float jacobian,
                                           vec3 spread, float n_frame) {
  float density = 0.0f;
  if (jacobian > 0.0f) density = lamina_folded_reflection_density(distribution, m, v, w_below) * jacobian;
  if (n_frame > 1.0f && spread.z > 0.0f)
    density += lamina_folded_reflection_density(distribution, m, v, spread) * lamina_cos_critical(n_frame);
  return density;
}

// The inverse of lamina_leave_or_spread's spread: the direction below that it maps onto the outer
// direction w (both in the frame of the layers above the lobe).
LAMINA_FN vec3 lamina_spread_source(vec3 w, float n_frame) {
  return lamina_with_cosine(w, lamina_cos_critical(n_frame) * w.z);
}

LAMINA_FN float lamina_diffuse_lobe_pdf(vec3 w_below, float jacobian, float n_frame) {
  return w_below.z * n_frame * n_frame * LAMINA_INV_PI * jacobian;
}

// A lobe's draw w in the frame of the layers above it (absolute index n_frame): itself when inside
// their exit cone (inside_cone true: still to be carried up), else spread over the outer hemisphere
// by cos_out = cos_in / cos_critical (inside_cone false: already the outer direction). vec3(0)
// when w is not above the horizon.
LAMINA_FN vec3 lamina_leave_or_spread(vec3 w, float n_frame, LAMINA_OUT(bool) inside_cone) {
  inside_cone = true;
  if (w.z <= 0.0f) return vec3(0.0f);
  if ((1.0f - w.z * w.z) * n_frame * n_frame <= 1.0f) return w;
  inside_cone = false;
  return lamina_with_cosine(w, w.z / lamina_cos_critical(n_frame));
}

// Draws a microfacet lobe's direction: plain NDF sampling, reflected about h, mirrored above the
// horizon. Sets inside_cone: true when the result is a direction in the frame still to be carried
// up through the layers, false when it is already the outer direction. vec3(0) if none.
LAMINA_FN vec3 lamina_sample_microfacet_lobe(int distribution, float m, vec3 v, vec2 u, float n_frame,
                                             LAMINA_OUT(bool) inside_cone) {
  vec3 h = sample_microfacet_normal(distribution, m, u);
  vec3 w = 2.0f * dot(v, h) * h - v;
  if (w.z < 0.0f) w = mirror_across_horizon(w);
  return lamina_leave_or_spread(w, n_frame, inside_cone);
}

// Cosine-weighted inside the exit cone of a frame of absolute index n_frame: sin^2 uniform on
// [0, 1/n^2], which the refraction up maps onto the cosine distribution outside.
LAMINA_FN vec3 lamina_sample_diffuse_lobe(vec2 u, float n_frame) {
  float sin2 = u.x / (n_frame * n_frame);
  float phi = 2.0f * LAMINA_PI * u.y;
  float sin_theta = sqrt(sin2);
  return vec3(sin_theta * cos(phi), sin_theta * sin(phi), sqrt(1.0f - sin2));
}

// --- the composition --------------------------------------------------------------------------------
// lamina compiles a material's stack into an array of entries, one per stack node as reached along
// one path from the surface (a stack both sides of a mix share appears once per side), depth first:
// a layer before its base, a mix's first stack before its second, so a parent always comes before
// its children. The loops below walk that array. The CPU evaluator calls them; the GLSL back end
// emits the array as a constant and calls the same functions, whose constant loops its compilers
// unroll. Nothing else composes a stack. The loops have a constant trip count and neither
// `continue` nor `break` (a skipped entry is an if, a walk up the parents a counted loop): Mesa
// leaves a loop with either rolled, and then every entry runs every entry kind's code (car_paint's
// eval was 8x slower on llvmpipe so). The same form suits SIMD lanes.

// What an entry is.
const int LAMINA_LAYER = 0;      // an interface over a medium over the entry `first`
const int LAMINA_MIX = 1;        // (1 - weight) first + weight second
const int LAMINA_SUBSTRATE = 2;  // an opaque base

// A mix's model: where its weight comes from.
const int LAMINA_MIX_LINEAR = 0;  // the weight input, scalars.x
// One step of a select's chain (nodes/select.cpp): its weight is lamina_select_weight of the index
// scalars.x, the step's run of stacks [colour0.x, scalars.y), the coverage scalars.z and the
// select's stack count scalars.w, so that the chain shows one of its stacks, or all of them in
// proportion where the pixel covers many cells.
const int LAMINA_MIX_SELECT = 1;

// A layer's interface model.
const int LAMINA_INTERFACE_DIELECTRIC = 0;  // lamina_interface_eval

// A layer's medium model.
const int LAMINA_MEDIUM_CLEAR = 0;
const int LAMINA_MEDIUM_ABSORBING = 1;  // Beer-Lambert: absorption

// A substrate's model.
const int LAMINA_SUBSTRATE_LAMBERT = 0;     // lamina_lambert_eval
const int LAMINA_SUBSTRATE_OREN_NAYAR = 1;  // oren_nayar
const int LAMINA_SUBSTRATE_CONDUCTOR = 2;   // lamina_conductor_eval
const int LAMINA_SUBSTRATE_FLUORESCENT = 3; // lamina_fluorescent_albedo: Lambert re-radiating across channels
const int LAMINA_SUBSTRATE_FLAKE_PAINT = 4; // lamina_flake_paint_eval: flakes in a binder over a diffuse base

// One entry of a compiled stack: what it is, where it is. Constant for a material.
struct LaminaEntry {
  int kind;          // LAMINA_LAYER, LAMINA_MIX or LAMINA_SUBSTRATE
  int model;         // a layer's interface model or a substrate's model
  int medium;        // a layer's medium model
  int distribution;  // a microfacet lobe's d_microfacet distribution
  int fresnel;       // a microfacet lobe's fresnel_mode
  int degrees;       // 1: the roughness input is an angle in degrees; 0: the slope itself
  int parent;        // the entry above; -1 for the surface
  int side;          // under a mix: 0 in its first stack, 1 in its second
  int first;         // a layer's base, a mix's first stack; -1 for a substrate
  int second;        // a mix's second stack; -1 otherwise
};

// An entry's inputs at one shading point, clamped to their declared ranges (a texture cannot push a
// parameter outside the model's domain). What each member holds:
//   colour0  lambert, oren_nayar, fluorescent: albedo; conductor: n (absolute); flake paint: the base's
//            albedo
//   colour1  conductor: k (absolute); flake paint: the flakes' reflectance
//   colour2  layer: the medium's absorption per micrometre; thin film, coated flakes: the film's
//            index (absolute)
//   scalars  x: a layer's ior (absolute, below its interface), a mix's weight, a select's index,
//               oren_nayar's sigma;
//            y: roughness (layer, conductor; an angle or a slope, per `degrees`); a select step's
//               threshold;
//            z: a layer's medium thickness in micrometres; a thin film's thickness in nm; a select's
//               coverage;
//            x, y, z, w of a flake paint: its flakes' coverage D <S> h, roughness, transmittance,
//               their film's thickness in nm (coated flakes);
//            xyz: a fluorescent base's re-radiated shares green to red, blue to red, blue to green;
//            w: a select's stack count
//   normal   the normal the entry's interface or substrate is tilted to, in the shading frame
//            (tangent space, +z the surface's own normal; a mix's stays (0, 0, 1)); not unit:
//            lamina_stack_resolve normalises it (lamina_entry_normal), and a length below 1
//            widens the entry's lobe (lamina_widened_slope)
struct LaminaInputs {
  vec3 colour0;
  vec3 colour1;
  vec3 colour2;
  vec4 scalars;
  vec3 normal;
};

// How a material composes its stack (its "model").
const int LAMINA_MODEL_WEIDLICH_WILKIE = 0;    // lamina_stack_eval, as the seeds give it
const int LAMINA_MODEL_ENERGY_CONSERVING = 1;  // lamina_stack_eval_conserving

// An entry's parameters at one shading point, with what the entries above it pass down.
struct LaminaParams {
  float n_above;    // absolute index of the medium above the entry (1 at the top)
  float m_above;    // the slope the layer above passes down (Elek sec. 3), 0 at the top
  float ior;        // layer: absolute index below its interface
  float eta;        // layer: the relative index ior / n_above
  float m;          // layer, conductor, flake paint: the slope after Elek's clamp to the layers above
  float thickness;  // layer
  float weight;     // mix
  float share;      // the product of the mix weights on the path from the surface (1 without mixes): 0 where
                    // a mix (a select's chain over one cell) shows none of the entry, which is then skipped
  float sigma;      // oren_nayar
  vec3 absorption;  // layer
  vec3 albedo;      // lambert, oren_nayar; flake paint: its albedo as lobe selection estimates it
  vec3 flake;       // flake paint: the flakes' reflectance
  vec2 flake_paint; // and their coverage D <S> h and transmittance
  vec3 flake_depth; // and the flake layer's optical depth at normal incidence, both ways
  vec3 flake_base;  // and the albedo of the base under the flakes
  vec3 n;           // conductor: the complex index relative to the medium above
  vec3 k;
  vec3 film_eta;    // thin film, coated flakes: the film's index relative to the medium above, per channel
  float film_depth; // and its thickness in nm times the medium above's index (film.glsl)
  vec3 normal;      // the entry's frame in the shading frame (lamina_entry_normal): its normal
  vec3 frame_x;     // and its tangents (lamina_to_entry)
  vec3 frame_y;
  vec3 diffuse;     // energy-conserving model: the coefficient c of the entry's diffuse part
  bool glowing;     // the entry's diffuse part crosses channels: a fluorescent base, or a layer over one
  mat3 glow;        // and then its diffuse coefficient as a matrix, column j what light absorbed in channel
                    // j leaves as (the Weidlich-Wilkie model reads the base's only); diffuse stays what
                    // white light sees, which lobe selection reads
  vec3 forward;     // and the coefficient 1 / N of its forward part (lamina_forward_part)
  vec2 grid;        // energy-conserving model, a layer: its boundary's table coordinates (lamina_albedo_grid_xy)
  vec2 cone_grid;   // and over a conductor, the metal's in block C (lamina_conductor_cone_share)
  vec3 cone_etas;   // with the indices it reads there (lamina_cone_etas)
  vec2 exit_cut;    // and where its lobe leaves the exit cone (lamina_exit_cut)
  vec3 trap_ramp;   // and what its boundary lets out beyond the edge (lamina_trap_ramp)
  vec2 trap_angles; // and the trapped stream's angles, resting and deepest (lamina_trap_angles)
  vec3 trap_near;   // and Gamma_0 there (lamina_trap_series)
  vec3 trap_far;
  float spread_own; // and the metal's slope on block C's grid if the boundary spreads wider (lamina_spread_own)
  float arrival_y;  // and its lobe widened by the arrivals' spread there (lamina_arrival_y)
};

// The Fresnel term of a metal-like base at cosine mu: a conductor's or a thin film's over one.
LAMINA_FN vec3 lamina_metal_fresnel(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p, float mu) {
  return lamina_fresnel_base(e.fresnel, mu, p.n, p.k, p.film_eta, p.film_depth);
}

// --- the energy-conserving composition ---------------------------------------------------------
// Each entry's BRDF is split in two parts: f(l, v) = s(l, v) + c u(l) u(v), where the second, the
// diffuse part, is light that has lost its direction in a diffuse substrate, and c is a constant of
// the entry (LaminaParams.diffuse). A diffuse substrate has u = 1 and c = albedo / pi (Oren-Nayar:
// its mean value, oren_nayar_mean) and s = f - c; a conductor only s; a mix only s (both its stacks
// whole). A layer of relative index eta over a base B, with T(mu) = 1 - E(mu) - M(mu) the energy its
// boundary lets through (energy.glsl: E its single-scattering lobe's albedo, M what its microsurface
// reflects beyond it) and t(mu) what the medium lets through one way of the light the boundary lets
// in from mu (exp(-sigma d / mu') under a smooth boundary, less under a rough one, whose paths are
// longer: lamina_rough_transmittance) and b the boost that makes the boundary's lobe reflect E + M
// (energy.glsl):
//   s(l, v) = f_boundary(l, v) (1 + b(l) b(v)) + T(l) t(l) T(v) t(v) / eta^2 s_B(l', v'),
// f_boundary being lamina_boundary_reflection, raised so that it reflects what the microsurface does,
//   u(w) = T(w) t(w) S(w') u_B(w'),   c = c_B / (eta^2 (1 - K)),
// S the series of the light bouncing between the boundary and a layer base's boundary below it
// (lamina_gap_series; 1 over any other base).
// The 1 / eta^2 is the radiance a ray loses crossing out of the denser medium (Veach 1997, sec.
// 5.2): with it the base's light leaves the layer with exactly the energy it had below. K is the
// share of the diffuse light the base sends up that comes back to it after reflecting off the
// boundary from below (totally outside the exit cone, E(mu_out) + M(mu_out) inside), so c sums every round
// trip, 1 + K + K^2 + ...: a Lambert base's light bounces under the boundary until it leaves or is
// absorbed, which is most of the energy of a white base under a clear coat. Over a conductor, the
// light the metal sends back into the boundary is followed too (lamina_trapped_light): its echo
// inside the exit cone raises the carry by g (g(l, v) = min(g(l'), g(v')), times the share a rough
// boundary's spread leaves inside the cone, lamina_spread_kept), and what total internal
// reflection traps outside the cone leaves by the layer's forward part (lamina_forward_part), added
// to s:
//   s(l, v) = ... T(l) t(l) T(v) t(v) / eta^2 s_B(l', v') g(l, v) + c_f u_f(l) u_f(v) a(l, v).
// Light the specular part of any other base sends into the boundary from below is not followed
// (it is lost, never created). An Oren-Nayar base's s has mean 0 (c is its mean value), so the
// light its direction-dependent terms send there averages out instead of being lost; c as its
// direction-free C1 share alone lost 8.6% of a white base's light under a clear coat (sugar).
// Every factor is symmetric in l and v, so the sum is reciprocal; each step passes on at most the
// energy it received (the boundary reflects at most E + M = 1 - T, t <= 1, a base's diffuse
// reflectance is at most 1 (Oren-Nayar's mean up to 1.0003, the course's model's own excess), and
// a metal's echo, trapped light and first exit add up to at most a_all, what it reflects with its
// Fresnel term at the arriving direction's cosine: an estimate, not a bound, which the strict
// furnace test checks), so no stack reflects more than it receives.

// Gauss-Legendre nodes and weights on [0, 1], five points (exact for polynomials of degree 9).
LAMINA_FN float lamina_gauss5_node(int i) {
  float x = i == 0 ? -0.906179845938664f
          : i == 1 ? -0.538469310105683f
          : i == 2 ? 0.0f
          : i == 3 ? 0.538469310105683f
                   : 0.906179845938664f;
  return 0.5f + 0.5f * x;
}
LAMINA_FN float lamina_gauss5_weight(int i) {
  float w = (i == 0 || i == 4) ? 0.236926885056189f : (i == 1 || i == 3) ? 0.478628670499366f : 0.568888888888889f;
  return 0.5f * w;
}

// What a rough boundary lets through beyond its critical angle, seen from its denser side: eta =
// n_other / n_dense < 1, xy its grid coordinates at eta and xy_other at 1 / eta (the other side).
// The table holds a boundary's cosines beyond its critical angle as the edge's, so the light that
// crosses there comes from reciprocity: light of radiance L on the dense side leaves into a direction
// of cosine mu on the other with radiance L T_o(mu) / eta^2 (T_o = 1 - E - M of the other side), and
// what it sends through the cone is 2 pi L int_cone T(mu) mu dmu (T this side's), so the share
//   g = 1 - int_cone T mu dmu / (eta^2 int T_o mu dmu)
// of what crosses leaves from beyond the edge mu_e. There T falls from T(mu_e) to 0: as a ramp with
// g's flux G = eta^2 int T_o mu dmu - int_cone T mu dmu, of width w = 2 G / (T(mu_e) mu_e) in the
// cosine (GGX's heavier tails fall more like exp(-2 x / w), x the cosine's distance past the edge,
// which has the same integral). Against the boundary's own random walks (the reference's
// interfaces), from a 14-degree Beckmann boundary of 1.45 under 1.7 g is 0.080 for 0.074, and
// beyond a 17-degree Beckmann one of 1.35 the ramp is within 0.01 of the walks' T for 12 degrees
// past the edge. Returned: (T(mu_e), w, g).
LAMINA_FN vec3 lamina_edge_ramp(int distribution, int fresnel, vec2 xy, vec2 xy_other, float eta) {
  float mu_edge = lamina_safe_sqrt(1.0f - eta * eta);
  float multiple = 0.0f;
  float cone = 0.0f;
  float whole = 0.0f;
  for (int q = 0; q < 5; ++q) {
    float weight = lamina_gauss5_weight(q);
    float x = lamina_gauss5_node(q);
    float mu = mix(mu_edge, 1.0f, x);
    cone += weight * (1.0f - mu_edge) * mu *
            (1.0f - lamina_boundary_energy(distribution, fresnel, xy, mu, eta, multiple));
    whole += weight * x * (1.0f - lamina_boundary_energy(distribution, fresnel, xy_other, x, 1.0f / eta, multiple));
  }
  float guided = max(eta * eta * whole - cone, 0.0f);
  float g = whole > 0.0f ? guided / (eta * eta * whole) : 0.0f;
  float t_edge = 1.0f - lamina_boundary_energy(distribution, fresnel, xy, mu_edge, eta, multiple);
  float width = min(2.0f * guided / max(t_edge * mu_edge, 1.0e-6f), mu_edge);
  return vec3(t_edge, width, g);
}

// The mean of lamina_edge_ramp's T, relative to T(mu_e), over angles X past the edge drawn from a
// normal of mean mu and deviation sigma and kept beyond it (X > 0); w the ramp's width in angle. For
// the ramp T_e (1 - X / w)+: (P - (mu P + sigma (phi(a) - phi(b))) / w) / Phi(-a), P = Phi(b) -
// Phi(a), a = -mu / sigma, b = (w - mu) / sigma (the first two moments of a cut normal). For
// GGX's exp(-2 X / w): exp(2 sigma^2 / w^2 - 2 mu / w) Phi(mu / sigma - 2 sigma / w) / Phi(-a),
// written with y = (2 sigma / w - mu / sigma) / sqrt 2 as exp(-a^2 / 2) exp(y^2) erfc(y) / 2 so that
// no factor overflows (lamina_erfc_poly is exp(y^2) erfc(y) for y >= 0). At mu = 0 the kept part
// is the half-normal.
LAMINA_FN float lamina_ramp_mean(int distribution, float w, float mu, float sigma) {
  float a = -mu / sigma;
  float b = (w - mu) / sigma;
  float beyond = max(lamina_normal_cdf(-a), 1.0e-6f);
  float within = lamina_normal_cdf(b) - lamina_normal_cdf(a);
  float ramp = within - (mu * within + sigma * (lamina_normal_pdf(a) - lamina_normal_pdf(b))) / w;
  float y = (2.0f * sigma / w - mu / sigma) * 0.70710678f;
  float gauss = exp(-0.5f * a * a);
  float scaled = y >= 0.0f ? lamina_erfc_poly(y) * gauss
                           : 2.0f * exp(min(2.0f * sigma * sigma / (w * w) - 2.0f * mu / w, 80.0f)) -
                                 lamina_erfc_poly(-y) * gauss;
  return max(distribution == 2 ? 0.5f * scaled : ramp, 0.0f) / beyond;
}

// The cosine of a direction of cosine mu refracted below a boundary of relative index eta, as
// refract_down computes it; 0 when it cannot enter.
LAMINA_FN float lamina_cosine_below(float mu, float eta) {
  float inv_eta = 1.0f / eta;
  float sin2_below = (1.0f - mu * mu) * inv_eta * inv_eta;
  if (mu <= 0.0f || sin2_below > 1.0f) return 0.0f;
  return sqrt(1.0f - sin2_below);
}

// What passes one way through a layer for a direction of cosine mu above it whose refracted cosine
// is mu_below (<= 0: it cannot enter): T(mu) t, T = 1 - E - M what the boundary lets through
// (energy.glsl) and t the medium's transmittance along the paths the boundary's transmission lobe
// gives the light (lamina_rough_transmittance; a smooth boundary's is t(mu_below)). gain receives
// b(mu), the boost by which the boundary's multiple scattering raises its single-scattering lobe
// (f (1 + b(l) b(v)), energy.glsl); reflected receives E(mu) + M(mu), which is also what the
// boundary reflects back down of light reaching it from below at mu_below.
LAMINA_FN vec3 lamina_layer_passage(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p, float mu, float mu_below,
                                    LAMINA_OUT(float) gain, LAMINA_OUT(float) reflected) {
  // One point on the table's grid serves E, M, the boost and the path ratios.
  LaminaAlbedoPoint at = lamina_albedo_point_at(e.distribution, e.fresnel, p.grid, mu, p.eta);
  float multiple = 0.0f;
  reflected = lamina_boundary_energy_at(at, multiple);
  gain = lamina_boundary_boost_at(at);
  if (mu_below <= 0.0f) return vec3(0.0f);
  // A clear medium lets everything through: its ratios are not read.
  vec2 ratios = p.thickness > 0.0f ? lamina_path_ratios_at(at) : vec2(1.0f);
  return (1.0f - reflected) * lamina_rough_transmittance(p.absorption, p.thickness, mu_below, ratios);
}

// The slope of the lobe that spreads a conductor's light under layer i: the metal's own, or, when
// it is smoother, the rough boundary's spread (1 - 1 / eta) m_boundary. Crossing a microfacet
// tilted by theta turns a ray by (1 - cos_i / (eta cos_t)) theta, (1 - 1 / eta) theta at normal
// incidence and more at oblique ones, and the metal's mirror keeps the turn; taken as a metal lobe's
// slope it puts outside the exit cone the light that a rough varnish over a smooth metal traps. The
// factor is chosen against the reference solver (unclamped_metal, 18 degrees over 3): with half of
// it the model stayed 12.0% high at 60 degrees, with it 5.6%, with twice 8.4% low at 85 (tools/
// compare_table.sh). With Elek's clamp the metal is never the smoother, and nothing changes.
LAMINA_FN float lamina_trap_slope(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                  LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  float boundary = max(1.0f - 1.0f / params[i].eta, 0.0f) * params[i].m;
  return max(params[entries[i].first].m, boundary);
}

// Of a conductor's light under layer i, the share inside the exit cone where it really goes,
// relative to the metal's own lobe's at the smooth refraction's cosine mu, at most 1: what of the
// specular part's carry, whose shape is the metal's own lobe at mu, really leaves at once; the rest
// is trapped (lamina_trapped_light counts it there). Really: where the boundary spreads it
// (lamina_trap_slope), from where it arrives (lamina_arrival_cosine); that share is `inside`, which
// lamina_trapped_light has read already. The metal's own lobe is read on block C's grid at the same
// index (cone_grid.x, cone_etas), at its own slope's coordinate: LaminaParams.spread_own where the
// spread is the wider (lamina_spread_own), else the grid's own. For a smooth boundary over a metal
// wider than its spread, both reads are the same and the share is 1.
LAMINA_FN float lamina_spread_kept(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                   LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float mu, float inside) {
  float own_y = params[i].spread_own < 0.0f ? params[i].cone_grid.y : params[i].spread_own;
  int distribution = entries[max(entries[i].first, 0)].distribution;
  float whole_own = 0.0f;
  float own_inside = lamina_conductor_cone_share(distribution, vec2(params[i].cone_grid.x, own_y),
                                                 params[i].cone_etas, mu, whole_own);
  return own_inside > 0.0f ? min(inside / own_inside, 1.0f) : 1.0f;
}

// The metal's own slope on block C's grid under layer i where the boundary spreads its light wider
// than its lobe (lamina_trap_slope), once per shading point (LaminaParams.spread_own); -1 where the
// metal's lobe is the wider, where block C's grid is at the metal's own slope already.
LAMINA_FN float lamina_spread_own(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                  LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  float m = params[max(entries[i].first, 0)].m;
  if (lamina_trap_slope(entries, params, i) <= m) return -1.0f;
  return lamina_albedo_grid_xy(m, max(params[i].eta, 1.0f)).y;
}

// Whether layer i lies on a conductor (the light its base traps: lamina_trapped_light).
LAMINA_FN bool lamina_on_conductor(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK], int i) {
  LaminaEntry base = entries[max(entries[i].first, 0)];
  return entries[i].kind == LAMINA_LAYER && base.kind == LAMINA_SUBSTRATE && base.model == LAMINA_SUBSTRATE_CONDUCTOR;
}

// Whether layer i's conductor base traps light as lamina_trapped_light follows it: a conductor right
// under the layer, in the layer's own frame. Its echo, trapped light and forward part are worked
// out for a metal parallel to the boundary; a metal tilted against it (a flake) sends its light
// elsewhere, and with them it reflected up to 1.18 times the light it received (a 15-degree flake
// of silver under a clear coat, seen from 70 degrees). Under a tilted metal the layer keeps only
// its boundary and the carry, which never reflect more than they receive (lamina_tilt_weight);
// what such a metal sends outside the exit cone is lost.
LAMINA_FN bool lamina_traps_light(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                  LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  vec3 base = params[max(entries[i].first, 0)].normal;
  vec3 own = params[i].normal;
  return lamina_on_conductor(entries, i) && base.x == own.x && base.y == own.y && base.z == own.z;
}

// What a conductor base reflects of light arriving at cosine mu under layer i: a_in, inside the
// boundary's exit cone, and a_all, over the whole hemisphere: F(mu) times the shares of its lobe
// (lamina_conductor_cone_share), whose share inside the cone is `inside`.
LAMINA_FN vec3 lamina_conductor_reflected(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                          LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float mu,
                                          LAMINA_OUT(vec3) a_all, LAMINA_OUT(float) inside) {
  int b = max(entries[i].first, 0);
  vec3 f = lamina_metal_fresnel(entries[b], params[b], mu);
  float whole = 0.0f;
  inside = lamina_conductor_cone_share(entries[b].distribution, params[i].cone_grid, params[i].cone_etas, mu, whole);
  a_all = f * whole;
  return f * inside;
}

// What the boundary of layer i over a conductor reflects back down (E + M) of the light the metal
// sends into the exit cone from an arriving angle theta under it: read at the mean angle of the
// lobe's part inside the cone, not at theta. The in-plane angle of the lobe's reflected directions
// is taken as normal about theta, of deviation sigma = sqrt(2) atan(m) (LaminaParams.exit_cut.y: twice
// the RMS tilt of one slope component), cut at the cone's edge theta_e; the part inside has mean
// theta - sigma phi(z) / Phi(z), z = (theta_e - theta) / sigma (the mean of a normal cut from above).
// Light arriving near the edge, as a grazing view's does, sends its in-cone part well inside it,
// where the boundary lets most of it out; read at theta itself, the echo took back what the carry
// had already let out at each exit direction, and a rough varnish over a near-perfect mirror
// reflected 1.05 at 89 degrees (and silver_paint was 9.6% too bright there against the reference,
// 3.1% now). Arriving well inside the cone, z is large and this is E + M at theta itself, so a
// smooth layer over a smooth metal keeps the closed form of two parallel mirrors.
// Returned with it, as y, the share `keep` of the carry's transmittance T(v) (read from above, at
// the direction the light leaves into) that the boundary really lets out of the metal's light: a
// rough boundary read from below, at the in-cone part's mean angle, lets less through than from
// above wherever the light under it is the metal's own lobe and not the boundary's own spread (by
// reciprocity the reading from above is exact for the latter). Measured with the boundary's own
// walks from below (the test "a boundary's table read from below gives what it lets out of a
// metal's lobe"): under 8-degree GGX of 1.45 a 15-degree metal's in-cone light leaves 0.871, the
// table from below says 0.866, the reading from above 0.947. The two readings are weighted by the
// metal's share of the spread's variance, m_metal^2 / (m_metal^2 + ((1 - 1 / eta) m)^2), and R =
// 1 - T keeps what is not let out in the echo and Gamma, so nothing is created. Without it
// ggx_lacquer_metal was 4.5% to 6.4% too bright at every angle.
LAMINA_FN vec2 lamina_exit_reflected(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                     LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float theta) {
  vec2 edge = params[i].exit_cut;
  float z = (edge.x - theta) / edge.y;
  float cut = max(lamina_normal_cdf(z), 1.0e-6f);
  float mean = max(theta - edge.y * lamina_normal_pdf(z) / cut, 0.0f);
  float eta = params[i].eta;
  float sin_mean = sin(mean);
  float mu_out = lamina_safe_sqrt(1.0f - eta * eta * sin_mean * sin_mean);
  float multiple = 0.0f;
  int distribution = entries[i].distribution;
  float above = lamina_boundary_energy(distribution, entries[i].fresnel, params[i].grid, mu_out, eta, multiple);
  float below = lamina_boundary_energy(distribution, entries[i].fresnel,
                                       lamina_albedo_grid_xy(params[i].m, 1.0f / eta), cos(mean), 1.0f / eta, multiple);
  float m_metal = params[max(entries[i].first, 0)].m;
  float spread = max(1.0f - 1.0f / eta, 0.0f) * params[i].m;
  float own = m_metal * m_metal / max(m_metal * m_metal + spread * spread, 1.0e-12f);
  float passes = mix(1.0f - above, min(1.0f - below, 1.0f - above), own);
  return vec2(1.0f - passes, passes / max(1.0f - above, 1.0e-6f));
}

// Gamma of layer i over a conductor: the share of the light trapped outside its exit cone that
// leaves, followed as one stream at one cosine mu_o (its angle theta_o, below). Each time it crosses
// the medium and comes back (t(mu_o)^2) the metal reflects a_in(mu_o) of it into the cone, where it
// leaves with the boundary's transmittance T = 1 - R, R what it reflects of that part
// (lamina_exit_reflected), or comes back; a_out(mu_o) stays trapped. Gamma_0 = t_o^2 p / (1 - q),
// the series of every return, p = a_in t_c T and q = a_out t_o^2 + a_in t_c^2 R, t_c the medium's
// transmittance in the middle of the cone;
// p + q <= a_all <= 1, so it never exceeds 1. A rough boundary also lets a share d of the stream
// out at its first return, just beyond the edge (see below): Gamma = t_o d + (1 - d) Gamma_0, at
// most 1 too; and at every later return a share d_r of the part a_out that stays beyond the edge
// (p gains a_out t_o d_r, q's a_out term keeps 1 - d_r of it, so p + q <= a_all still): with the
// first return alone, conserving_silver and gold_paint were 5.8% and 5.3% too dark once the carry
// let out only what the boundary passes from below (lamina_exit_reflected). 0 where the boundary
// has no total reflection (eta <= 1).
// Where the trapped light lies: a metal lobe of slope m tilts its normals by about atan(m) / sqrt(2)
// in the plane of reflection (the RMS of one slope component), and turns the reflected direction by
// twice that, so the part beyond the cone's edge lies on average sqrt(2 / pi) * 2 / sqrt(2) atan(m)
// = 1.13 atan(m) beyond the edge (a half-normal's mean) when the light arrives at the edge: the
// stream's resting angle theta_r, never more grazing than the mean cosine 2 mu_c / 3 of light spread
// evenly outside the edge mu_c, which a wide lobe approaches. (That mean alone, for every lobe, left
// the light a lobe traps just beyond the edge, which soon returns into the cone, largely lost:
// gold_metallic_paint 5.6% to 8.3% low between 40 and 70 degrees, within 2% with the trap's own
// angle.) A rough boundary sends grazing light deeper than the edge (lamina_arrival_cosine), and
// there the metal traps it farther out, at its arrival angle theta_a: the first return's d is read
// there, and the stream keeps half the depth beyond theta_r, theta_o = theta_r + (theta_a -
// theta_r)+ / 2, as the boundary's rough reflections spread it back towards the edge. Against the
// reference (unclamped_metal, an 18-degree coat over a 3-degree metal, tools/compare_table.sh):
// theta_o = theta_r left it 5.4% too bright at 85 degrees, theta_o = theta_a 5.6% too dark at 89,
// the half 2.6% and 0.4%. Needs LaminaParams.cone_grid, cone_etas, exit_cut and the trap_ fields.
const float LAMINA_TRAP_SPREAD = 1.13f;
// The angle where a lobe of slope m puts the light it sends beyond an edge at angle theta_edge
// (cosine mu_edge): LAMINA_TRAP_SPREAD atan(m) beyond it, never more grazing than the mean cosine
// 2 mu_edge / 3 of light spread evenly beyond the edge. The trapped stream's (lamina_trap_gain) and
// the guide's (lamina_guide).
LAMINA_FN float lamina_beyond_edge_angle(float theta_edge, float mu_edge, float m) {
  return min(theta_edge + LAMINA_TRAP_SPREAD * atan(m), lamina_acos(2.0f * mu_edge / 3.0f));
}
// Gamma_0 of layer i over a conductor for the stream at angle theta_o (above), once per shading
// point at each end of its range (LaminaParams.trap_near and trap_far).
LAMINA_FN vec3 lamina_trap_series(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                  LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float theta_o) {
  float eta = params[i].eta;
  if (eta <= 1.0f) return vec3(0.0f);
  float mu_edge = sqrt(1.0f - 1.0f / (eta * eta));
  float mu_o = cos(theta_o);
  vec3 a_all = vec3(0.0f);
  float inside = 0.0f;
  vec3 a_in = lamina_conductor_reflected(entries, params, i, mu_o, a_all, inside);
  vec3 a_out = max(a_all - a_in, vec3(0.0f));
  vec3 t_o = one_way_absorption(params[i].absorption, params[i].thickness, mu_o);
  vec3 t_c = one_way_absorption(params[i].absorption, params[i].thickness, 0.5f * (1.0f + mu_edge));
  float back = lamina_exit_reflected(entries, params, i, theta_o).x;
  // A rough boundary lets part of the trapped light out where it lies beyond the edge
  // (lamina_edge_ramp, LaminaParams.trap_ramp: T at the edge, the ramp's width in angle and sigma):
  // d_r, the ramp's T averaged over where the metal's lobe puts it, a normal of deviation sigma about
  // theta_o kept beyond the edge (lamina_ramp_mean). What it does not let out goes on.
  vec3 ramp = params[i].trap_ramp;
  float d_return = ramp.x * lamina_ramp_mean(entries[i].distribution, ramp.y, theta_o - params[i].exit_cut.x, ramp.z);
  vec3 p = a_in * t_c * (1.0f - back) + a_out * t_o * d_return;
  vec3 q = a_out * t_o * t_o * (1.0f - d_return) + a_in * t_c * t_c * back;
  return t_o * t_o * p / max(vec3(1.0f) - q, vec3(1.0e-6f));
}

// The range of the trapped stream's angle theta_o under layer i, once per shading point
// (LaminaParams.trap_angles): the resting angle theta_r and the deepest, half way from it to where
// light from the horizon arrives (lamina_arrival_cosine at mu = 0).
LAMINA_FN vec2 lamina_trap_angles(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                  LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  float eta = params[i].eta;
  if (eta <= 1.0f) return vec2(0.0f, 1.0f);
  float mu_edge = sqrt(1.0f - 1.0f / (eta * eta));
  float rest = lamina_beyond_edge_angle(params[i].exit_cut.x, mu_edge, lamina_trap_slope(entries, params, i));
  float deepest = lamina_acos(lamina_arrival_cosine(0.0f, mu_edge, eta, params[i].m));
  return vec2(rest, rest + 0.5f * max(deepest - rest, 0.0f));
}

// Gamma for light that reaches the metal at angle theta_arrive: the first return's d read about
// the arrival, and Gamma_0 at theta_o, interpolated linearly in the angle between the two ends
// lamina_trap_series computed: every material's largest error against the reference stayed the same
// to 0.1% (tools/compare_table.sh) as with Gamma_0 computed at theta_o for each direction, and
// car_paint's eval took 12668 instructions instead of 16926.
LAMINA_FN vec3 lamina_trap_gain(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float theta_arrive) {
  if (params[i].eta <= 1.0f) return vec3(0.0f);
  vec2 range = params[i].trap_angles;
  float theta_o = range.x + 0.5f * max(theta_arrive - range.x, 0.0f);
  float s = clamp((theta_o - range.x) / max(range.y - range.x, 1.0e-6f), 0.0f, 1.0f);
  vec3 series = mix(params[i].trap_near, params[i].trap_far, s);
  vec3 t_o = one_way_absorption(params[i].absorption, params[i].thickness, cos(theta_o));
  vec3 ramp = params[i].trap_ramp;
  float beyond = max(theta_arrive - params[i].exit_cut.x, 0.0f);
  float d = ramp.x * lamina_ramp_mean(entries[i].distribution, ramp.y, beyond, ramp.z);
  return t_o * d + (1.0f - d) * series;
}

// What the boundary of layer i over a conductor lets out of trapped light just beyond its edge,
// once per shading point (LaminaParams.trap_ramp): lamina_edge_ramp's T at the edge, its width
// turned into an angle, and the deviation sigma = 1.416 atan(m) in angle of where the metal's lobe
// puts the trapped light (m the trap's slope, lamina_trap_slope); T 0 for a smooth boundary (or
// eta <= 1), which lets nothing out there.
LAMINA_FN vec3 lamina_trap_ramp(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  float eta = params[i].eta;
  float sigma = max(1.41614f * atan(lamina_trap_slope(entries, params, i)), 1.0e-4f);
  if (eta <= 1.0f || params[i].m <= 0.0f) return vec3(0.0f, 1.0f, sigma);
  vec2 below = lamina_albedo_grid_xy(params[i].m, 1.0f / eta);
  vec3 ramp = lamina_edge_ramp(entries[i].distribution, entries[i].fresnel, below, params[i].grid, 1.0f / eta);
  return vec3(ramp.x, max(ramp.y / max(sin(params[i].exit_cut.x), 1.0e-3f), 1.0e-6f), sigma);
}

// The slope on block C's grid, once per shading point (LaminaParams.arrival_y), of the metal's own
// lobe under layer i widened by the spread of the arrivals a rough boundary sends down: in angle,
// the arrivals are about normal of deviation (1 - 1 / eta) atan(m) about their mean (the
// boundary's transmitted tilt; its walks give 0.8 to 1.1 times that under Beckmann boundaries at
// every angle, GGX's heavier tails spread grazing light more, which this leaves out), and the
// metal turns each by its own lobe, of deviation sqrt(2) atan(m_metal) in the plane; the two add in
// quadrature, sqrt(2) atan(m_wide) = sqrt(2 atan(m_metal)^2 + ((1 - 1 / eta) atan(m))^2). Read at
// the mean arrival with a lobe of the trap's slope instead, light from 85 degrees under an
// 18-degree coat of 1.5 over a 3-degree metal put 0.116 of what the metal reflects inside the cone
// where the walks put 0.041 (0.063 now; a normal about the walks' own mean and deviation puts
// 0.039 there, 0.107 from 80 and 0.336 from 70 degrees, as the walks do: 0.041, 0.107, 0.336).
LAMINA_FN float lamina_arrival_y(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                 LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  float deviation = max(1.0f - 1.0f / params[i].eta, 0.0f) * atan(params[i].m);
  float own = atan(params[max(entries[i].first, 0)].m);
  float wide = tan(min(sqrt(own * own + 0.5f * deviation * deviation), 1.5f));
  return lamina_albedo_grid_xy(wide, max(params[i].eta, 1.0f)).y;
}

// What a conductor base reflects of the light a rough boundary of layer i sends down to arrive at
// cosine mu: as lamina_conductor_reflected, but with the metal's lobe widened by the arrivals'
// spread (lamina_arrival_y).
LAMINA_FN vec3 lamina_arrival_reflected(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                        LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float mu,
                                        LAMINA_OUT(vec3) a_all, LAMINA_OUT(float) inside) {
  int b = max(entries[i].first, 0);
  float whole = 0.0f;
  inside = lamina_conductor_cone_share(entries[b].distribution, vec2(params[i].cone_grid.x, params[i].arrival_y),
                                       params[i].cone_etas, mu, whole);
  vec3 f = lamina_metal_fresnel(entries[b], params[b], mu);
  a_all = f * whole;
  return f * inside;
}

// Where lamina_exit_reflected cuts a conductor's lobe under layer i, once per shading point
// (LaminaParams.exit_cut): the angle of the exit cone's edge and the deviation sqrt(2) atan(m) of
// the metal's own lobe (at least 1e-4, so that a smooth metal cuts sharply). The edge is 0 for eta
// <= 1, where there is no cone (and no caller reads it); the deviation stays positive, so that a
// back end evaluating both sides of a select never divides by 0.
LAMINA_FN vec2 lamina_exit_cut(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                               LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  float eta = params[i].eta;
  float deviation = max(1.41421356f * atan(params[max(entries[i].first, 0)].m), 1.0e-4f);
  float edge = eta > 1.0f ? lamina_acos(sqrt(1.0f - 1.0f / (eta * eta))) : 0.0f;
  return vec2(edge, deviation);
}

// The light a conductor traps under layer i, for light from outer cosine mu (mu_below under the
// boundary by Snell's law), whose reflection back down there (E + M at mu) is `reflected`; 0 for
// any other base, and echo 1. A rough boundary sends the light on deeper than mu_below: it reaches
// the metal at lamina_arrival_cosine, where what the metal reflects is split. Of it, a_in stays
// inside the exit cone, and what of that leaves at once is the specular part's carry, whose shape
// is the metal's lobe at mu_below. What the boundary reflects back down of it, R
// (lamina_exit_reflected, read for that lobe), returns to the metal, which sends a_in t^2 R of it
// into the cone again each time: an echo near the specular direction that multiplies the carry by
// echo = 1 / (1 - a_in t^2 R) (for smooth layers exactly the series of two parallel mirrors). (Read
// where the light arrives instead, R is that of a lobe nearer the edge than the carry's, and a
// 15-degree coat of 2.0 over a near-perfect 1-degree mirror reflected 1.012 at 80 degrees.) The
// rest, a_out = a_all - a_in of every return, goes outside the cone, where the boundary reflects
// nearly all of it back; of that light a share Gamma (lamina_trap_gain) leaves in the end, after
// travelling on between metal and boundary. Returned: X = a_out echo Gamma.
LAMINA_FN vec3 lamina_trapped_light(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                    LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float mu,
                                    float mu_below, float reflected, LAMINA_OUT(vec3) echo, LAMINA_OUT(float) inside,
                                    LAMINA_OUT(float) keep) {
  echo = vec3(1.0f);
  inside = 1.0f;
  keep = 1.0f;
  if (!lamina_on_conductor(entries, i) || mu_below <= 0.0f) return vec3(0.0f);
  float arrive = lamina_arrival_cosine(mu, mu_below, params[i].eta, params[i].m);
  vec3 a_all = vec3(0.0f);
  vec3 a_in = lamina_arrival_reflected(entries, params, i, arrive, a_all, inside);
  vec3 t = one_way_absorption(params[i].absorption, params[i].thickness, mu_below);
  // Under total internal reflection the echo is what the boundary sends back of the part inside the
  // cone (lamina_exit_reflected); with no cone (eta <= 1), of all of it, at mu_below itself.
  float theta = lamina_acos(mu_below);
  vec2 exit = params[i].eta > 1.0f ? lamina_exit_reflected(entries, params, i, theta) : vec2(reflected, 1.0f);
  float back = exit.x;
  keep = exit.y;
  echo = 1.0f / max(vec3(1.0f) - a_in * t * t * back, vec3(1.0e-6f));
  return max(a_all - a_in, vec3(0.0f)) * echo * lamina_trap_gain(entries, params, i, lamina_acos(arrive));
}

// The trapped light's way out, the forward part of layer i over a conductor:
//   c u(l) u(v) a(l, v),   u(w) = T(w) t(w) X(w'),   c = 1 / N,
// N the integral of u cos over the hemisphere (lamina_forward_coefficient). Trapped light travels on
// between metal and boundary away from the light, keeping its azimuth, and leaves where the metal's
// lobe spreads it into the cone, near the cone's edge: the reference solver shows it forward and
// almost none on the side of the light (a separable lobe c u(l) u(v), tried first, put 30 times the
// reference's light there). So a(l, v) = 1 - cos(phi_l - phi_v) s(l) s(v), s(w) = min(sin w /
// LAMINA_FORWARD_SINE, 1): 0 toward the light and 2 away from it for directions more than 11.5
// degrees from the normal, 1 where either is normal, where the azimuth means nothing. Its mean over
// either azimuth is 1, so the part reflects exactly u(l) from l, like the separable lobe (Kulla and
// Conty 2017's form), and it is symmetric in l and v. (The sine's own weight, a = 1 - l.xy . v.xy,
// also keeps the mean but left half the separable lobe's light toward the light at 30 degrees.)
const float LAMINA_FORWARD_SINE = 0.2f;
LAMINA_FN vec3 lamina_forward_part(vec3 u_l, vec3 u_v, vec3 coefficient, vec3 l, vec3 v) {
  float s_l = max(sqrt(l.x * l.x + l.y * l.y), LAMINA_FORWARD_SINE);
  float s_v = max(sqrt(v.x * v.x + v.y * v.y), LAMINA_FORWARD_SINE);
  return coefficient * u_l * u_v * (1.0f - (l.x * v.x + l.y * v.y) / (s_l * s_v));
}


// The light that crosses the medium of a layer whose base is a layer bounces between the two
// boundaries: of what enters the gap, 1 / (1 - R_above R_below t^2) reaches the far side in the sum
// of every round trip, R_above being what the upper boundary reflects back down (total internal
// reflection: 1), R_below what the lower one reflects back up and t the medium's one-way
// transmittance, at the direction's cosine in the gap. Under a boundary down to a lower index,
// light the boundary above traps by total reflection passes the lower one only so: the lossless
// stack of a smooth 1.7 coat over a 1.45 layer over white kept 0.86 of the light without the sum.
// lamina_gap_series_kept takes what the upper boundary sends back down per channel (lamina_guide_keep).
LAMINA_FN vec3 lamina_gap_series_kept(vec3 t, vec3 kept_above, float reflected_below) {
  return 1.0f / max(vec3(1.0f) - kept_above * reflected_below * t * t, vec3(1.0e-6f));
}
LAMINA_FN vec3 lamina_gap_series(vec3 t, float reflected_above, float reflected_below) {
  return lamina_gap_series_kept(t, vec3(reflected_above), reflected_below);
}

// The guide of layer i: where a boundary below it leads down to an index n_least lower than its
// own, light in its medium beyond that boundary's critical angle (cosine mu_edge) reaches no base;
// where n_least is above the index over the layer, that light lies beyond the upper boundary's
// critical angle too, and travels on between the two, totally reflected both ways. A rough upper
// boundary sends part of what it reflects down there (lamina_guide_keep), and turns part of it
// back inside mu_edge at each return: of the light sent in, gain = t^2 h / (1 - t^2 (1 - h))
// comes back, h the share turned back and t the medium's transmittance at the guide's cosine; the
// rest the tint absorbs. The cosine is where a lobe puts light beyond an edge (lamina_trap_gain's
// angle, LAMINA_TRAP_SPREAD atan(m) beyond it). In a clear medium gain is 1 and nothing changes.
// Without the loss, a tinted 10-degree coat of 1.7 over a smooth 1.45 layer over Lambert was 11%
// too bright in red against the reference (6.5% with it); guided is false where there is no guide.
struct LaminaGuide {
  bool guided;
  vec2 xy;
  vec3 etas;
  vec3 gain;
};
LAMINA_FN LaminaGuide lamina_guide(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                   LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, float n_least) {
  LaminaGuide g;
  float eta_w = max(params[i].ior / n_least, 1.0f);
  g.guided = n_least < params[i].ior && n_least > params[i].n_above && params[i].m > 0.0f;
  g.xy = lamina_albedo_grid_xy(params[i].m, eta_w);
  g.etas = vec3(0.0f);
  g.gain = vec3(1.0f);
  if (!g.guided) return g;
  g.etas = lamina_cone_etas(g.xy);
  float mu_edge = lamina_safe_sqrt(1.0f - 1.0f / (eta_w * eta_w));
  float mu_w = cos(lamina_beyond_edge_angle(lamina_acos(mu_edge), mu_edge, params[i].m));
  float h = 1.0f - lamina_cone_share_beyond(entries[i].distribution, g.xy, g.etas, mu_w);
  vec3 t_w = one_way_absorption(params[i].absorption, params[i].thickness, mu_w);
  vec3 t2 = t_w * t_w;
  g.gain = t2 * h / max(vec3(1.0f) - t2 * (1.0f - h), vec3(1.0e-6f));
  return g;
}

// Of the light the boundary of layer i reflects back down from a cosine mu in its medium, the share
// that does not end in its guide (lamina_guide): 1 - s (1 - gain), s the share of the reflection's
// lobe beyond the guide's edge.
LAMINA_FN vec3 lamina_guide_keep(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK], int i,
                                 LAMINA_IN(LaminaGuide) guide, float mu) {
  if (!guide.guided) return vec3(1.0f);
  float s = lamina_cone_share_beyond(entries[i].distribution, guide.xy, guide.etas, mu);
  return vec3(1.0f) - s * (vec3(1.0f) - guide.gain);
}

// u(mu) of the entry `start`: the passages down the chain of layers to its diffuse substrate, with
// the series of every gap between two of them (lamina_gap_series).
LAMINA_FN vec3 lamina_diffuse_profile(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                      LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int start, float mu) {
  vec3 u = vec3(1.0f);
  float c = mu;
  int j = start;
  bool walking = true;
  bool in_gap = false;               // whether c is a cosine in the medium of a layer above j
  float reflected_above = 0.0f;      // and what that layer's boundary reflects back down there
  vec3 t_above = vec3(0.0f);         // and the medium's transmittance
  for (int n = 0; n < LAMINA_STACK; ++n) {
    walking = walking && j >= 0 && entries[max(j, 0)].kind == LAMINA_LAYER;
    if (walking) {
      float below = lamina_cosine_below(c, params[j].eta);
      float gain = 0.0f;
      float reflected = 0.0f;
      u = u * lamina_layer_passage(entries[j], params[j], c, below, gain, reflected);
      if (in_gap) u = u * lamina_gap_series(t_above, reflected_above, reflected);
      in_gap = true;
      reflected_above = reflected;
      t_above = one_way_absorption(params[j].absorption, params[j].thickness, below);
      c = below;
      j = entries[j].first;
    }
  }
  return u;
}

// What the boundary of entry b reflects back up of light reaching it from above at cosine mu: E + M
// for a layer, 0 for anything else (a substrate's light is its own part; a mix's is not followed).
LAMINA_FN float lamina_reflected_from_above(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                            LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int b, float mu) {
  if (entries[b].kind != LAMINA_LAYER) return 0.0f;
  float multiple = 0.0f;
  return lamina_boundary_energy(entries[b].distribution, entries[b].fresnel, params[b].grid, mu, params[b].eta,
                                multiple);
}

// Of the diffuse light a base layer b lets up into the medium of layer i, the share that the
// guide's tint (lamina_guide) does not absorb, where b's boundary is the guide's lower edge (its
// index is the chain's least, n_least) and rough; 1 elsewhere. A rough boundary lets light up
// beyond its critical angle too, straight into the guide: the share g of lamina_edge_ramp. The
// light enters where the ramp's transmission puts it, on average w / 3 past the edge's cosine
// (GGX's exponential: w / 2), and leaves back down with a chance 2 T(mu_e) / 3 each time it returns
// (the ramp's mean weighted by itself; the exponential's T(mu_e) / 2). Per return it crosses the
// medium twice (t^2) and leaves with e = 1 - (1 - h_i)(1 - d - (1 - d) h_b), d that chance and h_i,
// h_b the shares of the two boundaries' reflection lobes turned back inside the edge (block C): of
// what enters, gain = t^2 e / (1 - t^2 (1 - e)) comes back out, as in lamina_guide. Returned: 1 - g
// (1 - gain), 1 in a clear medium. The tinted stack of a 1.3 coat over a 10-degree 1.7 layer over a
// 14-degree 1.45 boundary over Lambert was 6.5% too red against the reference without it (g = 0.08
// of its base's light enters the guide), 3.6% with it.
LAMINA_FN vec3 lamina_guide_entry_keep(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                       LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, int b,
                                       float n_least) {
  bool edge_below = entries[b].kind == LAMINA_LAYER && params[b].ior <= n_least && params[b].m > 0.0f;
  if (!edge_below || n_least >= params[i].ior || n_least <= params[i].n_above) return vec3(1.0f);
  int distribution = entries[b].distribution;
  int fresnel = entries[b].fresnel;
  float eta = params[b].eta;
  float mu_edge = lamina_safe_sqrt(1.0f - eta * eta);
  vec2 xy_up = lamina_albedo_grid_xy(params[b].m, 1.0f / eta);
  vec3 ramp = lamina_edge_ramp(distribution, fresnel, params[b].grid, xy_up, eta);
  float t_edge = ramp.x;
  float width = ramp.y;
  float g = ramp.z;
  bool exponential = distribution == 2;
  float mu_in = mu_edge - width * (exponential ? 0.5f : 1.0f / 3.0f);
  vec2 xy_i = lamina_albedo_grid_xy(params[i].m, 1.0f / eta);
  float h_i = 1.0f - lamina_cone_share_beyond(entries[i].distribution, xy_i, lamina_cone_etas(xy_i), mu_in);
  float h_b = 1.0f - lamina_cone_share_beyond(distribution, xy_up, lamina_cone_etas(xy_up), mu_in);
  float down = t_edge * (exponential ? 0.5f : 2.0f / 3.0f);
  float e = 1.0f - (1.0f - h_i) * (1.0f - down - (1.0f - down) * h_b);
  vec3 t = one_way_absorption(params[i].absorption, params[i].thickness, mu_in);
  vec3 t2 = t * t;
  vec3 gain = t2 * e / max(vec3(1.0f) - t2 * (1.0f - e), vec3(1.0e-6f));
  return vec3(1.0f) - g * (vec3(1.0f) - gain);
}

// c of layer i from its base's. The base's diffuse light leaves it with radiance c_B u_B(w) times
// what it received, weighted by u_B of where that came from; the boundary sends R t^2 of it back
// down at the same cosine, where the base takes it in with u_B again. So one round trip keeps
// K = c_B int u_B^2 t^2 R cos over the hemisphere under the boundary (R = 1 outside the exit
// cone, E(mu_out) inside it, integrated over mu_out, where the integrand is smooth: mu dmu =
// mu_out dmu_out / eta^2). (The product c_B (int u_B cos)(int u_B t^2 R cos) / pi, used before,
// equals it only for a uniform u_B, a diffuse substrate right under the layer; under a layer over
// a layer it lost up to 14% of a lossless white stack's light.) R is less what ends in the
// layer's guide (lamina_guide_keep), in the round trip and in the gap's series alike.
// Over a glowing base (LaminaParams.glow) glow receives the same as a matrix: with C_B the base's,
// each round trip's return W = diag(2 pi int u_B^2 t^2 R cos) the same per channel, the light that
// leaves after any number of round trips is C_B + C_B W C_B + ... = (I - C_B W)^-1 C_B, over eta^2.
// The guide's keep scales C_B by its square root on both sides, so that a base's transposed matrix
// gives the transposed result (the adjoint, lamina_diffuse_response); on a diagonal C_B it is the
// scale above. Elsewhere glow receives 0.
LAMINA_FN vec3 lamina_diffuse_coefficient(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                          LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i,
                                          LAMINA_OUT(mat3) glow) {
  int base = entries[i].first;
  vec3 c_base = params[base].diffuse;
  glow = mat3(0.0f);
  if (c_base.x <= 0.0f && c_base.y <= 0.0f && c_base.z <= 0.0f) return vec3(0.0f);
  float eta = params[i].eta;
  float inv_eta2 = 1.0f / (eta * eta);
  float mu_critical = lamina_safe_sqrt(1.0f - inv_eta2);  // beyond it (mu < mu_critical) light stays
  float mu_out_least = lamina_safe_sqrt(1.0f - eta * eta);  // the outer cosine of a grazing ray below
  // u_B is 0 below the cosine where light under the boundary can no longer enter every layer down
  // to the substrate (a boundary down to a lower index reflects the rest totally); the quadrature
  // starts there, as five nodes across that kink counted 2.5% too much.
  float n_least = params[i].ior;
  int j = base;
  for (int n = 0; n < LAMINA_STACK; ++n) {
    bool layer = j >= 0 && entries[max(j, 0)].kind == LAMINA_LAYER;
    if (layer) n_least = min(n_least, params[j].ior);
    j = layer ? entries[j].first : -1;
  }
  float mu_least = min(lamina_safe_sqrt(1.0f - lamina_sqr(n_least / params[i].ior)), mu_critical);
  LaminaGuide guide = lamina_guide(entries, params, i, n_least);
  vec3 entry_keep = lamina_guide_entry_keep(entries, params, i, base, n_least);
  c_base = c_base * entry_keep;
  vec3 w_sum = vec3(0.0f);
  for (int q = 0; q < 5; ++q) {
    float weight = lamina_gauss5_weight(q);
    // Totally reflected: mu in [mu_least, mu_critical].
    float mu = mix(mu_least, mu_critical, lamina_gauss5_node(q));
    vec3 u = lamina_diffuse_profile(entries, params, base, mu);
    vec3 t = one_way_absorption(params[i].absorption, params[i].thickness, mu);
    vec3 keep = lamina_guide_keep(entries, i, guide, mu);
    vec3 series = lamina_gap_series_kept(t, keep, lamina_reflected_from_above(entries, params, base, mu));
    w_sum += (weight * (mu_critical - mu_least) * mu) * keep * u * u * t * t * series;
    // Inside the cone, by the outer cosine.
    float mu_out = mix(mu_out_least, 1.0f, lamina_gauss5_node(q));
    float mu_in = lamina_safe_sqrt(1.0f - (1.0f - mu_out * mu_out) * inv_eta2);
    float multiple = 0.0f;
    float reflected =
        lamina_boundary_energy(entries[i].distribution, entries[i].fresnel, params[i].grid, mu_out, eta, multiple);
    u = lamina_diffuse_profile(entries, params, base, mu_in);
    t = one_way_absorption(params[i].absorption, params[i].thickness, mu_in);
    keep = reflected * lamina_guide_keep(entries, i, guide, mu_in);
    series = lamina_gap_series_kept(t, keep, lamina_reflected_from_above(entries, params, base, mu_in));
    float span = (1.0f - mu_out_least) * inv_eta2;
    w_sum += (weight * span * mu_out) * keep * u * u * t * t * series;
  }
  vec3 k = c_base * (2.0f * LAMINA_PI) * w_sum;
  if (LAMINA_FLUORESCENCE && params[base].glowing) {
    mat3 keep_half = lamina_diagonal(sqrt(entry_keep));
    mat3 c_glow = keep_half * params[base].glow * keep_half;
    glow = inverse(mat3(1.0f) - c_glow * lamina_diagonal((2.0f * LAMINA_PI) * w_sum)) * c_glow * inv_eta2;
  }
  return c_base * inv_eta2 / max(vec3(1.0f) - k, vec3(1.0e-6f));
}

// c of the forward part of layer i over a conductor (lamina_forward_part): 1 / N, N = 2 pi int T(mu_out) t X(mu) mu_out
// dmu_out over the outer cosines (mu dmu = mu_out dmu_out / eta^2, and the solid angle's eta^2), by
// Gauss-Legendre on two halves of [0, 1] in s = sqrt(mu_out) (dmu_out = 2 s ds): X climbs steeply
// at grazing views, where light arrives at the cone's edge, and the nodes even in mu_out missed it
// (a smooth 4-degree coat of 1.2 over a 1-degree mirror: N 3.2% short of a 200000-point sum, and
// the forward part as much too bright, 1.004 at 86 degrees; in s, 0.8% over, and within 0.3% for
// every example and test material).
LAMINA_FN vec3 lamina_forward_coefficient(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                          LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i) {
  vec3 sum = vec3(0.0f);
  for (int q = 0; q < 10; ++q) {
    int half_index = q / 5;
    float root = 0.5f * (float(half_index) + lamina_gauss5_node(q - 5 * half_index));
    float mu_out = root * root;
    float weight = lamina_gauss5_weight(q - 5 * half_index) * root;
    float below = lamina_cosine_below(mu_out, params[i].eta);
    float gain = 0.0f;
    float reflected = 0.0f;
    vec3 passage = lamina_layer_passage(entries[i], params[i], mu_out, below, gain, reflected);
    vec3 echo = vec3(1.0f);
    float inside = 0.0f;
    float keep = 1.0f;
    sum += (weight * mu_out) * passage *
           lamina_trapped_light(entries, params, i, mu_out, below, reflected, echo, inside, keep);
  }
  // A thick absorbing layer can take N below float's range of reciprocals (a random stack: 21.6
  // units of absorption 1.34 made 1 / N infinite in red); where N is below LAMINA_MIN_DENOM the
  // forward part, of the order of N itself, is 0.
  vec3 norm = (2.0f * LAMINA_PI) * sum;
  return vec3(norm.x > LAMINA_MIN_DENOM ? 1.0f / norm.x : 0.0f, norm.y > LAMINA_MIN_DENOM ? 1.0f / norm.y : 0.0f,
              norm.z > LAMINA_MIN_DENOM ? 1.0f / norm.z : 0.0f);
}

// --- tilted entries ----------------------------------------------------------------------------
// An interface or substrate may be tilted by a normal input (a flake, a glitter cell, a normal map):
// its own frame's z is that normal, given in the shading frame (tangent space). The walks hand
// directions from entry to entry in the shading frame; each entry turns what it is handed into its
// own frame (lamina_to_entry), works there as if untilted, and turns the directions it hands on
// back (lamina_from_entry). An untilted entry's frame is the identity, exactly: its numbers are those
// of a stack without normals. A tilted entry's whole reflection (its own lobe and everything below
// it) is weighted by lamina_tilt_weight, which keeps the stack's energy and reciprocity.

// The lowest z of a normal input after normalising: 0.05, 87 degrees from the surface's normal. A
// normal at or below the horizon (a texture's (0, 0, 0), a map's flipped channel) has no frame
// that light from above could see; it is raised there, and (0, 0, 0) becomes (0, 0, 1).
const float LAMINA_MIN_NORMAL_Z = 0.05f;
LAMINA_FN vec3 lamina_entry_normal(vec3 n) { return normalize(vec3(n.x, n.y, max(n.z, LAMINA_MIN_NORMAL_Z))); }

// A filtered normal widens the lobe. A texture that averages its normals over a pixel's footprint
// returns their mean, shorter than 1 where they differ; Toksvig ("Mipmapping Normal Maps", JGT
// 10(3), 2005, sec. 3) reads the variance of their slopes from its length L as (1 - L) / L and
// widens a Blinn-Phong exponent s to s / (1 + s (1 - L) / L), i.e. 1 / s grows by (1 - L) / L.
// A slope m corresponds to 1 / s = m^2 / 2 (Walter et al. 2007, sec. 5.2, alpha_p = 2 / m^2 - 2
// for small m), so the slope becomes sqrt(m^2 + 2 (1 - L) / L): slope variances add, as for two
// Gaussian slope distributions convolved. A normal of length 1 or more is a direction and leaves
// m as it is; at 2/3 and below the slope is 1, the most lamina's lobes take (L is read from 0.5
// up, and NaN as 0.5). m is the slope after Elek's clamp: the spread of the facets' orientations
// adds to the lobe the entry shows, however its own slope came about.
LAMINA_FN float lamina_widened_slope(float m, vec3 normal) {
  float len = length(normal);
  float l = len > 0.5f ? len : 0.5f;
  return len >= 1.0f ? m : min(sqrt(m * m + 2.0f * (1.0f - l) / l), 1.0f);
}

// A select's step (nodes/select.cpp) in a chain over `count` stacks, for the run of stacks [lo, hi)
// that are one stack repeated (one stack k: [k, k + 1)): the share of what reaches the step that
// goes on to the stacks from hi on. With coverage c, the share of
// stack j is (1 - c) where j = floor(index) (index clamped to [0, count - 1]) plus c / count: c = 0
// shows the one stack the index names, c = 1 every stack alike, the mean over a pixel that covers
// many cells whose uniform values the index spreads over [0, count) (texture/voronoi's coverage).
// Such an index faded with its value towards the middle, count / 2 + (1 - c) (cell's - count / 2)
// (lamina_voronoi_cell); the cell's own is read back from it. The step's weight is
// P(stack >= hi) / P(stack >= lo); 0 or 1 exactly when c = 0.
LAMINA_FN float lamina_select_weight(float faded_index, float lo, float hi, float count, float coverage) {
  float c = clamp(coverage, 0.0f, 1.0f);
  float middle = 0.5f * count;
  float index = c > 0.0f && c < 1.0f ? max(middle + (faded_index - middle) / (1.0f - c), 0.0f) : faded_index;
  float up_to = (index < hi ? 1.0f - c : 0.0f) + c * hi / count;  // P(stack < hi)
  float before = (index < lo ? 1.0f - c : 0.0f) + c * lo / count;  // P(stack < lo)
  float reaching = 1.0f - before;
  return reaching > 0.0f ? clamp((1.0f - up_to) / reaching, 0.0f, 1.0f) : (index >= hi ? 1.0f : 0.0f);
}

// Tangents completing a frame around the unit normal n (z > 0): Duff et al. 2017, "Building an
// orthonormal basis, revisited", eq. (3) with sign +1. For n = (0, 0, 1) they are (1, 0, 0) and
// (0, 1, 0) exactly, so turning into and out of the frame changes no bit.
LAMINA_FN void lamina_entry_tangents(vec3 n, LAMINA_OUT(vec3) x, LAMINA_OUT(vec3) y) {
  float a = -1.0f / (1.0f + n.z);
  float b = n.x * n.y * a;
  x = vec3(1.0f + n.x * n.x * a, b, -n.x);
  y = vec3(b, 1.0f + n.y * n.y * a, -n.y);
}

// Whether the entry whose parameters are p is untilted: its normal is (0, 0, 1) exactly (the
// resolved normal is unit), and its frame the identity. The reference solver, which walks flat
// boundaries only, asks the same (cpu::tilted_entry).
LAMINA_FN bool lamina_entry_flat(LAMINA_IN(LaminaParams) p) { return p.normal.x == 0.0f && p.normal.y == 0.0f; }

// A direction in the shading frame turned into the frame of the entry whose parameters are p, and back.
// An untilted entry's turns are skipped (the same for every point of a material whose normals are
// not textured).
LAMINA_FN vec3 lamina_to_entry(LAMINA_IN(LaminaParams) p, vec3 w) {
  if (lamina_entry_flat(p)) return w;
  return vec3(dot(w, p.frame_x), dot(w, p.frame_y), dot(w, p.normal));
}
LAMINA_FN vec3 lamina_from_entry(LAMINA_IN(LaminaParams) p, vec3 w) {
  if (lamina_entry_flat(p)) return w;
  return w.x * p.frame_x + w.y * p.frame_y + w.z * p.normal;
}

// The layer whose frame entry i's directions refract in: its nearest ancestor that is not a mix,
// -1 for the surface's (the shading frame); from its parent's (above[parent], set first: parents
// come before their children).
LAMINA_FN int lamina_frame_above(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                 LAMINA_IN_ARRAY(int) above[LAMINA_STACK], int i) {
  int parent = entries[i].parent;
  if (parent < 0) return -1;
  return entries[parent].kind == LAMINA_MIX ? above[parent] : parent;
}

// A direction in the shading frame turned into the frame of entry j (lamina_frame_above: -1 is the
// shading frame itself), and back.
LAMINA_FN vec3 lamina_to_frame(LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int j, vec3 w) {
  return j < 0 ? w : lamina_to_entry(params[max(j, 0)], w);
}
LAMINA_FN vec3 lamina_from_frame(LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int j, vec3 w) {
  return j < 0 ? w : lamina_from_entry(params[max(j, 0)], w);
}

// The weight of a tilted entry's reflection for directions l and v in its frame, whose cosines in
// the frame of the entry above it (the surface for the top one) are z_above:
//   c(l) c(v),   c(w) = min(1, cos_entry(w) / cos_above(w)).
// The entry's reflection F keeps energy in its own frame, int F cos_entry <= 1; the layer above it
// integrates against cos_above, and int F c(l) c(v) cos_above <= int F min(cos_above, cos_entry)
// <= int F cos_entry <= 1, so the weighted entry keeps energy in the frame above, and by induction
// the whole stack does; the product is symmetric, so reciprocity holds. (Without it, light grazing
// the frame above but facing a tilted flake would count with the flake's larger cosine.) 1 for an
// entry in the frame above's own, where the cosines are equal.
LAMINA_FN vec2 lamina_tilt_weight(vec3 l, vec3 v, vec2 z_above) {
  return vec2(min(1.0f, l.z / z_above.x), min(1.0f, v.z / z_above.y));
}

// A mix's weight from its inputs: the weight itself, or a select's step (lamina_select_weight).
LAMINA_FN float lamina_mix_weight(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaInputs) x) {
  vec4 s = x.scalars;
  return e.model == LAMINA_MIX_SELECT ? lamina_select_weight(s.x, x.colour0.x, s.y, s.w, s.z) : s.x;
}

// The share of a mix of weight w that goes to its first stack (side 0) or its second (side 1).
LAMINA_FN float lamina_side_share(float weight, int side) { return side == 0 ? 1.0f - weight : weight; }

// A flake paint's flakes (flakes.glsl) from its entry and resolved parameters: plain, or coated
// with the film its Fresnel mode names.
LAMINA_FN LaminaFlakes lamina_entry_flakes(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p) {
  LaminaFlakes f = lamina_flakes(p.flake_paint.x, p.flake, p.flake_paint.y, e.distribution, p.m);
  f.film = e.fresnel;
  f.film_eta = p.film_eta;
  f.film_depth = p.film_depth;
  return f;
}

// Every entry's parameters from its inputs, top down: a layer passes its index and its clamped
// slope to the entries below it, a mix passes on what it received. share: the part of the surface
// the stack covers (1 for a material's whole stack; a part's share of its blend, lamina_blend_*).
// clamp_lower: Elek's rule that raises each slope to at least the one above it. model:
// LAMINA_MODEL_*; for the energy-conserving one, bottom up, every entry's diffuse coefficient
// (lamina_diffuse_coefficient).
LAMINA_FN void lamina_stack_resolve(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                    LAMINA_IN_ARRAY(LaminaInputs) inputs[LAMINA_STACK], float share, bool clamp_lower,
                                    int model, LAMINA_OUT_ARRAY(LaminaParams) params[LAMINA_STACK]) {
  for (int i = 0; i < count; ++i) {
    LaminaParams p;
    p.n_above = 1.0f;
    p.m_above = 0.0f;
    p.share = share;
    int parent = entries[i].parent;
    if (parent >= 0) {
      bool below_layer = entries[parent].kind == LAMINA_LAYER;
      p.n_above = below_layer ? params[parent].ior : params[parent].n_above;
      p.m_above = below_layer ? params[parent].m : params[parent].m_above;
      p.share = params[parent].share * (below_layer ? 1.0f : lamina_side_share(params[parent].weight, entries[i].side));
    }
    p.ior = 1.0f;
    p.eta = 1.0f;
    p.m = 0.0f;
    p.thickness = 0.0f;
    p.weight = 0.0f;
    p.sigma = 0.0f;
    p.absorption = vec3(0.0f);
    p.albedo = vec3(0.0f);
    p.flake = vec3(0.0f);
    p.flake_paint = vec2(0.0f);
    p.flake_depth = vec3(0.0f);
    p.flake_base = vec3(0.0f);
    p.n = vec3(1.0f);
    p.k = vec3(0.0f);
    p.film_eta = vec3(1.0f);
    p.film_depth = 0.0f;
    p.normal = lamina_entry_normal(inputs[i].normal);
    lamina_entry_tangents(p.normal, p.frame_x, p.frame_y);
    p.diffuse = vec3(0.0f);
    p.glowing = false;
    p.glow = mat3(0.0f);
    p.forward = vec3(0.0f);
    p.grid = vec2(0.0f);
    p.cone_grid = vec2(0.0f);
    p.cone_etas = vec3(0.0f);
    p.exit_cut = vec2(0.0f);
    p.trap_ramp = vec3(0.0f, 1.0f, 1.0f);
    p.trap_angles = vec2(0.0f, 1.0f);
    p.trap_near = vec3(0.0f);
    p.trap_far = vec3(0.0f);
    p.spread_own = -1.0f;
    p.arrival_y = 0.0f;
    int kind = entries[i].kind;
    bool degrees = entries[i].degrees != 0;
    if (kind == LAMINA_LAYER) {
      p.ior = inputs[i].scalars.x;
      p.eta = p.ior / p.n_above;
      float own = lamina_effective_slope(lamina_slope(inputs[i].scalars.y, degrees), p.m_above, clamp_lower);
      p.m = lamina_widened_slope(own, inputs[i].normal);
      if (entries[i].medium == LAMINA_MEDIUM_ABSORBING) {
        p.absorption = inputs[i].colour2;
        p.thickness = inputs[i].scalars.z;
      }
    } else if (kind == LAMINA_MIX) {
      p.weight = lamina_mix_weight(entries[i], inputs[i]);
    } else if (entries[i].model == LAMINA_SUBSTRATE_CONDUCTOR) {
      // The metal's index relative to the layer above it (Elek's shader uses the absolute one);
      // n stays above 0.001, where the Fresnel equations stay finite.
      p.n = max(inputs[i].colour0, vec3(1.0e-3f)) / p.n_above;
      p.k = inputs[i].colour1 / p.n_above;
      // A thin film's (colour2 its absolute index, scalars.z its thickness in nm), as film.glsl takes them.
      p.film_eta = max(inputs[i].colour2, vec3(1.0e-3f)) / p.n_above;
      p.film_depth = inputs[i].scalars.z * p.n_above;
      float own = lamina_effective_slope(lamina_slope(inputs[i].scalars.y, degrees), p.m_above, clamp_lower);
      p.m = lamina_widened_slope(own, inputs[i].normal);
    } else if (entries[i].model == LAMINA_SUBSTRATE_FLAKE_PAINT) {
      // The flakes' orientation spread is clamped to the layers above like any lobe's.
      float own = lamina_effective_slope(lamina_slope(inputs[i].scalars.y, degrees), p.m_above, clamp_lower);
      p.m = lamina_widened_slope(own, inputs[i].normal);
      p.flake = inputs[i].colour1;
      p.flake_paint = vec2(inputs[i].scalars.x, inputs[i].scalars.z);
      // Coated flakes' film (colour2 its absolute index, scalars.w its thickness in nm) in the binder above.
      p.film_eta = max(inputs[i].colour2, vec3(1.0e-3f)) / p.n_above;
      p.film_depth = inputs[i].scalars.w * p.n_above;
      LaminaFlakes flakes = lamina_entry_flakes(entries[i], p);
      p.flake_base = inputs[i].colour0;
      // Its albedo at normal incidence is what lobe selection reads.
      lamina_flake_paint_resolve(flakes, p.flake_base, p.flake_depth, p.diffuse, p.albedo);
    } else if (LAMINA_FLUORESCENCE && entries[i].model == LAMINA_SUBSTRATE_FLUORESCENT) {
      // Its matrix, and as albedo what it returns of white light (the row sums), which the
      // selection and every white-light query read as a Lambert base's.
      mat3 albedo = lamina_fluorescent_albedo(inputs[i].colour0, vec3(inputs[i].scalars));
      p.glowing = true;
      p.glow = albedo * LAMINA_INV_PI;
      p.albedo = albedo * vec3(1.0f);
      p.diffuse = lambert(p.albedo);
    } else {
      p.albedo = inputs[i].colour0;
      p.sigma = inputs[i].scalars.x;
      // A diffuse substrate's direction-free part: Lambert's albedo / pi, Oren-Nayar's mean value.
      bool rough = entries[i].model == LAMINA_SUBSTRATE_OREN_NAYAR;
      p.diffuse = rough ? oren_nayar_mean(p.albedo, p.sigma) : lambert(p.albedo);
    }
    params[i] = p;
  }
  if (model != LAMINA_MODEL_ENERGY_CONSERVING) return;
  for (int i = count - 1; i >= 0; --i) {
    // An entry no mix shows keeps its first pass (every mix above reads it with weight 0).
    bool shown = params[i].share > 0.0f;
    if (shown && entries[i].kind == LAMINA_LAYER) params[i].grid = lamina_albedo_grid_xy(params[i].m, params[i].eta);
    // Only a layer over a conductor traps light: its quadrature is not spent on the others.
    if (shown && lamina_on_conductor(entries, i)) {
      params[i].cone_grid = lamina_albedo_grid_xy(lamina_trap_slope(entries, params, i), max(params[i].eta, 1.0f));
      params[i].cone_etas = lamina_cone_etas(params[i].cone_grid);
      params[i].spread_own = lamina_spread_own(entries, params, i);
      params[i].arrival_y = lamina_arrival_y(entries, params, i);
      params[i].exit_cut = lamina_exit_cut(entries, params, i);
      params[i].trap_ramp = lamina_trap_ramp(entries, params, i);
      params[i].trap_angles = lamina_trap_angles(entries, params, i);
      params[i].trap_near = lamina_trap_series(entries, params, i, params[i].trap_angles.x);
      params[i].trap_far = lamina_trap_series(entries, params, i, params[i].trap_angles.y);
      params[i].forward = lamina_forward_coefficient(entries, params, i);
    }
    if (shown && entries[i].kind == LAMINA_LAYER) {
      params[i].glowing = params[entries[i].first].glowing;
      params[i].diffuse = lamina_diffuse_coefficient(entries, params, i, params[i].glow);
    }
  }
}

// Whether an entry is a flake paint, whose lobe is a glitter beside a diffuse shade.
LAMINA_FN bool lamina_is_flake_paint(LAMINA_IN(LaminaEntry) e) {
  return e.kind == LAMINA_SUBSTRATE && e.model == LAMINA_SUBSTRATE_FLAKE_PAINT;
}

// The share of a flake paint's draws its glitter takes (lamina_flake_glitter_share); 0 for any other entry.
LAMINA_FN float lamina_flake_share(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p) {
  return lamina_is_flake_paint(e) ? lamina_flake_glitter_share(p.albedo, p.diffuse) : 0.0f;
}

// Whether an entry is a lobe (every interface and substrate; a mix only weighs its stacks).
LAMINA_FN bool lamina_is_lobe(LAMINA_IN(LaminaEntry) e) { return e.kind != LAMINA_MIX; }

// Whether a lobe reflects by microfacets (a layer's interface, a conductor) or diffusely.
LAMINA_FN bool lamina_is_microfacet_lobe(LAMINA_IN(LaminaEntry) e) {
  return e.kind == LAMINA_LAYER || (e.kind == LAMINA_SUBSTRATE && e.model == LAMINA_SUBSTRATE_CONDUCTOR);
}

// A substrate's BRDF at (l, v) in its own frame.
LAMINA_FN vec3 lamina_substrate_eval(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p, vec3 l, vec3 v) {
  if (e.model == LAMINA_SUBSTRATE_CONDUCTOR)
    return lamina_conductor_eval(l, v, p.n, p.k, p.film_eta, p.film_depth, e.distribution, e.fresnel, p.m);
  if (e.model == LAMINA_SUBSTRATE_OREN_NAYAR) return oren_nayar(l, v, p.albedo, p.sigma);
  if (e.model == LAMINA_SUBSTRATE_FLAKE_PAINT)
    return lamina_flake_paint_eval(l, v, lamina_entry_flakes(e, p), p.diffuse, p.flake_depth);
  return lamina_lambert_eval(l, v, p.albedo);
}

// --- light of a colour -------------------------------------------------------------------------
// A stack without a fluorescent base reflects each channel on its own: f is a colour, and the light
// reflected from light L is f L per channel. A fluorescent base moves light from channel to channel
// (lamina_fluorescent_albedo), so what leaves depends on the incident light's colour, not only on
// its amount per channel: the compositions take the light L and return what is reflected of it
// (the *_response functions; lamina_stack_eval and its kin are their L = 1, white light). In a
// glowing stack the light is attenuated on its way down before the base turns it into other
// channels, and on its way up after: every layer's transmission is split into its part down
// (applied to the light it hands on, LaminaEvalStep.lit_on) and its part up (its carry). adjoint
// gives the transpose, F^T(wi, wo) x, as a path traced from the viewer carries its weight x:
// evaluated with wi and wo exchanged and every matrix transposed, since the rest is reciprocal.
// glows is lamina_stack_glows of the stack, which a back end knows per material: false, the
// light's colour is applied at the end and every step of the split is a constant to its compiler.

// Whether a stack has a fluorescent base (constant per material). LAMINA_FLUORESCENCE is the back
// end's: C++ defines it true; the GLSL back end false in a module without a fluorescent material,
// where the light's split and the matrices then fold away (with them, the random stacks' parity on
// llvmpipe took 260 s with a fresh shader cache, against 98 s without).
LAMINA_FN bool lamina_stack_glows(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK]) {
  bool glows = false;
  for (int i = 0; i < count; ++i)
    glows = glows || (entries[i].kind == LAMINA_SUBSTRATE && entries[i].model == LAMINA_SUBSTRATE_FLUORESCENT);
  return LAMINA_FLUORESCENCE && glows;
}

LAMINA_FN mat3 lamina_glow(LAMINA_IN(LaminaParams) p, bool adjoint) { return adjoint ? transpose(p.glow) : p.glow; }

// What a substrate reflects at (l, v) in its own frame of the light `light` (glows: of its stack).
LAMINA_FN vec3 lamina_substrate_response(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p, vec3 l, vec3 v,
                                         vec3 light, bool adjoint, bool glows) {
  if (glows && p.glowing) return (l.z > 0.0f && v.z > 0.0f) ? lamina_glow(p, adjoint) * light : vec3(0.0f);
  return lamina_substrate_eval(e, p, l, v) * light;
}

// The energy-conserving model's diffuse part of an entry, c u(l) u(v), of the light `light`.
LAMINA_FN vec3 lamina_diffuse_response(LAMINA_IN(LaminaParams) p, vec3 u_l, vec3 u_v, vec3 light, bool adjoint,
                                       bool glows) {
  if (glows && p.glowing) return u_v * (lamina_glow(p, adjoint) * (u_l * light));
  return p.diffuse * u_l * u_v * light;
}

// What one entry of lamina_stack_eval passes between its passes.
struct LaminaEvalStep {
  vec3 l_on;   // the L and V the entry hands to the entries below it, in the shading frame
  vec3 v_on;
  vec2 z_on;   // their cosines in the frame they were refracted in (a mix: those it was handed)
  vec2 tilt;   // the entry's lamina_tilt_weight for l and v (1 for a mix)
  vec3 carry;  // a layer's T a t (in a glowing stack, only its part on the way up)
  vec3 f;      // the entry's own lobe, then (bottom up) its whole stack, as light it reflects
  vec3 lit_on; // the light the entry hands to the entries below it (lamina_stack_glows)
};

// The directions entry i of a walk is handed (l and v in the shading frame, z_above their cosines
// in the frame above it) in its own frame, and whether they reach it: both above its horizon (a
// mix: above the horizon of the frame above), and some mix above shows it (a select's chain over
// one cell walks the one stack it shows). Sets the step's tilt weight and clears the rest.
LAMINA_FN bool lamina_eval_enter(LAMINA_IN(LaminaEntry) e, LAMINA_IN(LaminaParams) p, vec3 lt, vec3 vt, vec2 z_above,
                                 LAMINA_OUT(vec3) l, LAMINA_OUT(vec3) v, LAMINA_OUT(LaminaEvalStep) step) {
  l = lamina_to_entry(p, lt);
  v = lamina_to_entry(p, vt);
  bool mixing = e.kind == LAMINA_MIX;
  bool reached = p.share > 0.0f && z_above.x > 0.0f && z_above.y > 0.0f && (mixing || (l.z > 0.0f && v.z > 0.0f));
  step.f = vec3(0.0f);
  step.carry = vec3(0.0f);
  step.l_on = vec3(0.0f);
  step.v_on = vec3(0.0f);
  step.z_on = vec2(0.0f);
  step.lit_on = vec3(0.0f);
  step.tilt = vec2(1.0f);
  if (reached && !mixing) step.tilt = lamina_tilt_weight(l, v, z_above);
  return reached;
}

// Elek's Algorithm 1 generalised to any stack (course sec. 3.1, Elek eq. 2):
//   f(i)(L, V) = f_i(L, V) + T_i f(i+1)(L', V') a_i t_i,   a mix: (1 - w) f(a) + w f(b),
// without recursion: top down, every entry's own lobe at the (L, V) its parent hands it and what
// it hands on (a layer: L', V' and T a t; a mix: its own L, V); bottom up, every entry's f from
// those of its children, in the recursion's order of operations. An entry is reached when both
// directions it is handed point up (a layer that cannot refract hands on one that does not), and
// an unreached entry's f and carry stay 0, so a layer adds f_i + 0 without a branch. What it
// reflects of the light `light` (see lamina_stack_glows): in a glowing stack a layer's absorption
// along L' is the part of its carry T a t applied on the way down.
LAMINA_FN vec3 lamina_stack_response(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                     LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], vec3 wi, vec3 wo,
                                     vec3 light, bool adjoint, bool glows) {
  if (wi.z <= 0.0f || wo.z <= 0.0f || count <= 0) return vec3(0.0f);
  LaminaEvalStep s[LAMINA_STACK];
  // Without a fluorescent base every channel is its own: white light inside, the colour at the end.
  vec3 lit_top = glows ? light : vec3(1.0f);
  vec3 lit_after = glows ? vec3(1.0f) : light;
  // A bare substrate is the only one-entry stack: its lobe is the whole walk. (count is constant
  // per material, so the branch is uniform on the GPU and in SIMD lanes.)
  if (count == 1) {
    vec3 l = vec3(0.0f);
    vec3 v = vec3(0.0f);
    if (!lamina_eval_enter(entries[0], params[0], wi, wo, vec2(wi.z, wo.z), l, v, s[0])) return vec3(0.0f);
    vec3 f = lamina_substrate_response(entries[0], params[0], l, v, lit_top, adjoint, glows);
    return max(f * (s[0].tilt.x * s[0].tilt.y), vec3(0.0f)) * lit_after;
  }
  for (int i = 0; i < count; ++i) {
    int parent = entries[i].parent;
    vec3 l = vec3(0.0f);
    vec3 v = vec3(0.0f);
    bool reached = lamina_eval_enter(entries[i], params[i], parent < 0 ? wi : s[max(parent, 0)].l_on,
                                     parent < 0 ? wo : s[max(parent, 0)].v_on,
                                     parent < 0 ? vec2(wi.z, wo.z) : s[max(parent, 0)].z_on, l, v, s[i]);
    vec3 lit = !glows ? vec3(1.0f) : parent < 0 ? lit_top : s[max(parent, 0)].lit_on;
    int kind = entries[i].kind;
    if (!reached) {
      // not reached: nothing from here down
    } else if (kind == LAMINA_LAYER) {
      vec3 lb = vec3(0.0f);
      vec3 vb = vec3(0.0f);
      vec3 passed = vec3(0.0f);
      s[i].f = lamina_interface_eval(l, v, params[i].eta, entries[i].distribution, entries[i].fresnel, params[i].m,
                                     lb, vb, passed) *
               lit;
      s[i].l_on = lamina_from_entry(params[i], lb);
      s[i].v_on = lamina_from_entry(params[i], vb);
      s[i].z_on = vec2(lb.z, vb.z);
      // a_i: in a glowing stack the absorption along L' goes down with the light and the carry keeps
      // the one along V'; otherwise both in one exponential.
      vec3 down = glows ? one_way_absorption(params[i].absorption, params[i].thickness, lb.z) : vec3(1.0f);
      s[i].carry = passed * (glows ? one_way_absorption(params[i].absorption, params[i].thickness, vb.z)
                                   : absorption(params[i].absorption, params[i].thickness, lb.z, vb.z));
      s[i].lit_on = lit * down;
    } else if (kind == LAMINA_MIX) {
      s[i].l_on = l;
      s[i].v_on = v;
      s[i].z_on = parent < 0 ? vec2(wi.z, wo.z) : s[max(parent, 0)].z_on;
      s[i].lit_on = lit;
    } else {
      s[i].f = lamina_substrate_response(entries[i], params[i], l, v, lit, adjoint, glows);
    }
  }
  for (int i = count - 1; i >= 0; --i) {
    int kind = entries[i].kind;
    if (kind == LAMINA_LAYER) {
      s[i].f = s[i].f + s[entries[i].first].f * s[i].carry;
    } else if (kind == LAMINA_MIX) {
      s[i].f = mix(s[entries[i].first].f, s[entries[i].second].f, params[i].weight);
    }
    s[i].f = s[i].f * (s[i].tilt.x * s[i].tilt.y);
  }
  return max(s[0].f, vec3(0.0f)) * lit_after;
}

LAMINA_FN vec3 lamina_stack_eval(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                 LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], vec3 wi, vec3 wo) {
  return lamina_stack_response(count, entries, params, wi, wo, vec3(1.0f), false, lamina_stack_glows(count, entries));
}

// The energy-conserving composition (see lamina_diffuse_coefficient): the same two passes, where
// every entry carries its specular part s and its diffuse profiles u(l), u(v) (0 where unreached).
// A back end calls it or lamina_stack_eval by the material's model, constant per material. Of the
// light `light` (lamina_stack_glows): in a glowing stack a layer's T(l) t(l) goes down with the light
// and its carry keeps the rest, and the diffuse parts take the light their mix or the top receives.
LAMINA_FN vec3 lamina_stack_response_conserving(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                                LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], vec3 wi,
                                                vec3 wo, vec3 light, bool adjoint, bool glows) {
  if (wi.z <= 0.0f || wo.z <= 0.0f || count <= 0) return vec3(0.0f);
  LaminaEvalStep s[LAMINA_STACK];  // f holds s; carry T(l) t(l) T(v) t(v) / eta^2
  vec3 lit_top = glows ? light : vec3(1.0f);
  vec3 lit_after = glows ? vec3(1.0f) : light;
  if (count == 1) {
    vec3 l = vec3(0.0f);
    vec3 v = vec3(0.0f);
    if (!lamina_eval_enter(entries[0], params[0], wi, wo, vec2(wi.z, wo.z), l, v, s[0])) return vec3(0.0f);
    vec3 f = lamina_substrate_response(entries[0], params[0], l, v, lit_top, adjoint, glows);
    return max(f * (s[0].tilt.x * s[0].tilt.y), vec3(0.0f)) * lit_after;
  }
  vec3 u_l[LAMINA_STACK];          // a layer's passage for l, then (bottom up) the entry's u(l)
  vec3 u_v[LAMINA_STACK];
  vec4 gap_l[LAMINA_STACK];        // a layer's E + M at l and its medium's t at l' (lamina_gap_series)
  vec4 gap_v[LAMINA_STACK];
  for (int i = 0; i < count; ++i) {
    int parent = entries[i].parent;
    vec3 l = vec3(0.0f);
    vec3 v = vec3(0.0f);
    bool reached = lamina_eval_enter(entries[i], params[i], parent < 0 ? wi : s[max(parent, 0)].l_on,
                                     parent < 0 ? wo : s[max(parent, 0)].v_on,
                                     parent < 0 ? vec2(wi.z, wo.z) : s[max(parent, 0)].z_on, l, v, s[i]);
    u_l[i] = vec3(0.0f);
    u_v[i] = vec3(0.0f);
    gap_l[i] = vec4(0.0f);
    gap_v[i] = vec4(0.0f);
    vec3 lit = !glows ? vec3(1.0f) : parent < 0 ? lit_top : s[max(parent, 0)].lit_on;
    int kind = entries[i].kind;
    if (!reached) {
      // not reached: nothing from here down
    } else if (kind == LAMINA_LAYER) {
      vec3 lb = refract_down(l, params[i].eta);
      vec3 vb = refract_down(v, params[i].eta);
      float gain_l = 0.0f;
      float gain_v = 0.0f;
      float reflected_l = 0.0f;
      float reflected_v = 0.0f;
      vec3 passage_l = lamina_layer_passage(entries[i], params[i], l.z, lb.z, gain_l, reflected_l);
      vec3 passage_v = lamina_layer_passage(entries[i], params[i], v.z, vb.z, gain_v, reflected_v);
      u_l[i] = passage_l;
      u_v[i] = passage_v;
      // The gap's transmittance only over a layer base (its series; constant per material).
      bool over_layer = entries[entries[i].first].kind == LAMINA_LAYER;
      vec3 t_l = over_layer ? one_way_absorption(params[i].absorption, params[i].thickness, lb.z) : vec3(0.0f);
      vec3 t_v = over_layer ? one_way_absorption(params[i].absorption, params[i].thickness, vb.z) : vec3(0.0f);
      gap_l[i] = vec4(t_l, reflected_l);
      gap_v[i] = vec4(t_v, reflected_v);
      // Over a conductor, the light it traps: its echo raises the carry (symmetric by the min, and
      // never more than either direction's echo), less what the boundary's spread traps, and the
      // rest leaves by the forward part; over any other base all are nothing.
      vec3 echo_l = vec3(1.0f);
      vec3 echo_v = vec3(1.0f);
      float inside_l = 1.0f;
      float inside_v = 1.0f;
      float keep_l = 1.0f;
      float keep_v = 1.0f;
      bool trapping = lamina_traps_light(entries, params, i);
      vec3 trapped_l = vec3(0.0f);
      vec3 trapped_v = vec3(0.0f);
      if (trapping) {
        trapped_l = lamina_trapped_light(entries, params, i, l.z, lb.z, reflected_l, echo_l, inside_l, keep_l);
        trapped_v = lamina_trapped_light(entries, params, i, v.z, vb.z, reflected_v, echo_v, inside_v, keep_v);
      }
      vec3 boost = min(echo_l, echo_v) * sqrt(keep_l * keep_v);
      if (trapping && lb.z > 0.0f && vb.z > 0.0f) {
        float kept = min(lamina_spread_kept(entries, params, i, lb.z, inside_l),
                         lamina_spread_kept(entries, params, i, vb.z, inside_v));
        boost = boost * kept;
      }
      s[i].f = (vec3(lamina_boundary_reflection(l, v, params[i].eta, entries[i].distribution, entries[i].fresnel,
                                                params[i].m) *
                     (1.0f + gain_l * gain_v)) +
                lamina_forward_part(passage_l * trapped_l, passage_v * trapped_v, params[i].forward, l, v)) *
               lit;
      s[i].l_on = lamina_from_entry(params[i], lb);
      s[i].v_on = lamina_from_entry(params[i], vb);
      s[i].z_on = vec2(lb.z, vb.z);
      s[i].carry = (glows ? vec3(1.0f) : passage_l) * passage_v * boost / (params[i].eta * params[i].eta);
      s[i].lit_on = glows ? lit * passage_l : lit;
    } else if (kind == LAMINA_MIX) {
      s[i].l_on = l;
      s[i].v_on = v;
      s[i].z_on = parent < 0 ? vec2(wi.z, wo.z) : s[max(parent, 0)].z_on;
      s[i].lit_on = lit;
    } else {
      s[i].f = (lamina_substrate_eval(entries[i], params[i], l, v) - params[i].diffuse) * lit;
      u_l[i] = vec3(1.0f);
      u_v[i] = vec3(1.0f);
    }
  }
  for (int i = count - 1; i >= 0; --i) {
    int kind = entries[i].kind;
    if (kind == LAMINA_LAYER) {
      int b = entries[i].first;
      s[i].f = s[i].f + s[b].f * s[i].carry;
      // The diffuse light crosses the gap over a layer base with its series (lamina_gap_series;
      // the base's gap_*.w, its E + M from above, is 0 for any other base).
      u_l[i] = u_l[i] * u_l[b] * lamina_gap_series(vec3(gap_l[i]), gap_l[i].w, gap_l[b].w);
      u_v[i] = u_v[i] * u_v[b] * lamina_gap_series(vec3(gap_v[i]), gap_v[i].w, gap_v[b].w);
    } else if (kind == LAMINA_MIX) {
      int a = entries[i].first;
      int b = entries[i].second;
      vec3 lit = glows ? s[i].lit_on : vec3(1.0f);
      s[i].f = mix(s[a].f + lamina_diffuse_response(params[a], u_l[a], u_v[a], lit, adjoint, glows),
                   s[b].f + lamina_diffuse_response(params[b], u_l[b], u_v[b], lit, adjoint, glows), params[i].weight);
    }
    // A tilted entry's weight (lamina_tilt_weight): both parts, the diffuse one by its profiles.
    s[i].f = s[i].f * (s[i].tilt.x * s[i].tilt.y);
    u_l[i] = u_l[i] * s[i].tilt.x;
    u_v[i] = u_v[i] * s[i].tilt.y;
  }
  return max(s[0].f + lamina_diffuse_response(params[0], u_l[0], u_v[0], lit_top, adjoint, glows), vec3(0.0f)) * lit_after;
}

LAMINA_FN vec3 lamina_stack_eval_conserving(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                            LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], vec3 wi, vec3 wo) {
  return lamina_stack_response_conserving(count, entries, params, wi, wo, vec3(1.0f), false,
                                          lamina_stack_glows(count, entries));
}

// Lobe selection at wo (course sec. 3.2.3): each lobe's estimated share of the reflected energy:
// the Fresnel reflectance of its interface (or its substrate's albedo) times what the layers above
// let through twice, (1 - F)^2 and the absorption along the refracted wo (lamina_selection_step),
// times the mix weights on its path; plus a floor of 1% of the mean, so every lobe stays
// reachable; normalised. Per entry (0 for mixes): weight, v (wo in the entry's frame) and valid
// (wo reaches it).
// The selection's first step: each lobe's estimate (weight), v and valid, as above; returns the sum
// of the estimates and the number of lobes wo reaches, from which lamina_selection_floor and
// lamina_stack_floored_sum normalise them (over a whole stack, or over all the parts of a blend).
LAMINA_FN vec2 lamina_stack_estimate(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                     LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], vec3 wo,
                                     LAMINA_OUT_ARRAY(float) weight[LAMINA_STACK],
                                     LAMINA_OUT_ARRAY(vec3) v[LAMINA_STACK],
                                     LAMINA_OUT_ARRAY(bool) valid[LAMINA_STACK]) {
  float throughput[LAMINA_STACK];
  for (int i = 0; i < count; ++i) {
    int parent = entries[i].parent;
    // wo as handed to the entry, in the shading frame (a mix's frame is the shading frame).
    vec3 handed = wo;
    if (parent < 0) {
      throughput[i] = params[i].share;
      valid[i] = wo.z > 0.0f;
    } else if (entries[parent].kind == LAMINA_MIX) {
      handed = v[parent];
      throughput[i] = throughput[parent] * lamina_side_share(params[parent].weight, entries[i].side);
      valid[i] = valid[parent];
    } else {
      handed = vec3(0.0f);
      throughput[i] = 0.0f;
      valid[i] = false;
      if (valid[parent]) {
        float factor = 0.0f;
        vec3 below = lamina_selection_step(v[parent], params[parent].eta, entries[parent].fresnel,
                                           params[parent].absorption, params[parent].thickness, factor);
        if (below.z > 0.0f) {
          handed = lamina_from_entry(params[parent], below);
          throughput[i] = throughput[parent] * factor;
          valid[i] = true;
        }
      }
    }
    // In the entry's own frame; a tilted lobe is reached only above its horizon, and a lobe no mix
    // shows not at all (it reflects nothing, so it gets no floor share either).
    v[i] = lamina_to_entry(params[i], handed);
    valid[i] = valid[i] && params[i].share > 0.0f && (entries[i].kind == LAMINA_MIX || v[i].z > 0.0f);
  }
  float total = 0.0f;
  int valid_count = 0;
  for (int i = 0; i < count; ++i) {
    float estimate = 0.0f;
    if (lamina_is_lobe(entries[i]) && valid[i]) {
      ++valid_count;
      if (entries[i].kind == LAMINA_LAYER) {
        estimate = lamina_fresnel_dielectric(entries[i].fresnel, v[i].z, params[i].eta);
      } else if (entries[i].model == LAMINA_SUBSTRATE_CONDUCTOR) {
        estimate = lamina_luminance(lamina_metal_fresnel(entries[i], params[i], v[i].z));
      } else {
        estimate = lamina_luminance(params[i].albedo);
      }
      estimate *= throughput[i];
    }
    weight[i] = estimate;
    total += estimate;
  }
  return vec2(total, float(valid_count));
}

// The floor every reachable lobe gets (1% of the mean estimate), from lamina_stack_estimate's sums.
LAMINA_FN float lamina_selection_floor(vec2 totals) { return totals.x > 0.0f ? 0.01f * totals.x / totals.y : 1.0f; }

// An entry's estimate with the floor if it is a reachable lobe.
LAMINA_FN float lamina_floored_estimate(LAMINA_IN(LaminaEntry) e, bool valid, float estimate, float floor_share) {
  return lamina_is_lobe(e) && valid ? estimate + floor_share : estimate;
}

// The sum of a stack's floored estimates, entry by entry.
LAMINA_FN float lamina_stack_floored_sum(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                         LAMINA_IN_ARRAY(float) weight[LAMINA_STACK],
                                         LAMINA_IN_ARRAY(bool) valid[LAMINA_STACK], float floor_share) {
  float sum = 0.0f;
  for (int i = 0; i < count; ++i) sum += lamina_floored_estimate(entries[i], valid[i], weight[i], floor_share);
  return sum;
}

// The selection over a whole stack.
LAMINA_FN void lamina_stack_select(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                   LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], vec3 wo,
                                   LAMINA_OUT_ARRAY(float) weight[LAMINA_STACK], LAMINA_OUT_ARRAY(vec3) v[LAMINA_STACK],
                                   LAMINA_OUT_ARRAY(bool) valid[LAMINA_STACK]) {
  vec2 totals = lamina_stack_estimate(count, entries, params, wo, weight, v, valid);
  if (totals.y == 0.0f) return;
  float floor_share = lamina_selection_floor(totals);
  float sum = lamina_stack_floored_sum(count, entries, weight, valid, floor_share);
  for (int i = 0; i < count; ++i)
    weight[i] = lamina_floored_estimate(entries[i], valid[i], weight[i], floor_share) / sum;
}

// The share of a conductor lobe's samples (entry i, wo in its frame v) drawn cosine-weighted over
// the outer hemisphere for the forward part of the layer over it (energy-conserving model), which
// leaves where the metal's own lobe never points (over a smooth metal its density there is 0): the
// share of the metal's reflection at v that falls outside the layer's exit cone and is trapped
// (lamina_conductor_cone_share), held within [LAMINA_FORWARD_DRAWN, 1 - LAMINA_FORWARD_DRAWN] so
// that both parts are always drawn; 0 where the layer has no forward part (every other entry,
// and the Weidlich-Wilkie model, whose lobes are then drawn exactly as before).
const float LAMINA_FORWARD_DRAWN = 0.1f;
LAMINA_FN float lamina_forward_sampling_share(LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                              LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK], int i, vec3 v) {
  int parent = max(entries[i].parent, 0);
  vec3 forward = params[parent].forward;
  bool has_forward = entries[i].parent >= 0 && lamina_traps_light(entries, params, parent) &&
                     max(forward.x, max(forward.y, forward.z)) > 0.0f;
  if (!has_forward) return 0.0f;
  float trapped =
      lamina_cone_share_beyond(entries[i].distribution, params[parent].cone_grid, params[parent].cone_etas, v.z);
  return clamp(trapped, LAMINA_FORWARD_DRAWN, 1.0f - LAMINA_FORWARD_DRAWN);
}

// A lobe draws directions in its own frame, below the layers above it. Directions inside the
// exit cone (sin < 1/n, n the frame's absolute index) are carried up by Snell's law, with the
// solid-angle Jacobian; a microfacet lobe's directions outside the cone, which cannot leave the
// stack, are spread over the outer hemisphere by cos_out = cos_in / cos_critical (Jacobian
// cos_critical), so every lobe's density integrates to exactly 1. Diffuse lobes draw cosine-
// weighted directions inside the cone only, which is the cosine distribution outside. A conductor
// under a layer with a forward part draws lamina_forward_sampling_share of its directions
// cosine-weighted outside, directly.
// The density of wi under the selection (weight, v, valid) at wo.
LAMINA_FN float lamina_stack_pdf(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                 LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK],
                                 LAMINA_IN_ARRAY(float) weight[LAMINA_STACK], LAMINA_IN_ARRAY(vec3) v[LAMINA_STACK],
                                 LAMINA_IN_ARRAY(bool) valid[LAMINA_STACK], vec3 wi, vec3 wo) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  // wi refracted down to every entry, in the shading frame, with d omega_below / d omega_outside
  // along the way (turning into and out of a layer's frame keeps solid angles).
  vec3 w[LAMINA_STACK];
  float jacobian[LAMINA_STACK];
  int above[LAMINA_STACK];
  for (int i = 0; i < count; ++i) {
    int parent = entries[i].parent;
    above[i] = lamina_frame_above(entries, above, i);
    w[i] = wi;
    jacobian[i] = 1.0f;
    if (parent >= 0 && entries[parent].kind == LAMINA_MIX) {
      w[i] = w[parent];
      jacobian[i] = jacobian[parent];
    } else if (parent >= 0) {
      float eta = params[parent].eta;
      vec3 from_above = lamina_to_entry(params[parent], w[parent]);
      vec3 below = refract_down(from_above, eta);
      jacobian[i] = jacobian[parent] * refraction_jacobian(from_above.z, below.z, eta);
      w[i] = lamina_from_entry(params[parent], below);
    }
  }
  float pdf = 0.0f;
  for (int i = 0; i < count; ++i) {
    if (lamina_is_lobe(entries[i]) && weight[i] > 0.0f && valid[i]) {
      // A lobe's draws are tested against the exit cone in the frame of the layer above it, where
      // they refract (lamina_stack_sample): they reach wi where wi refracts down to the entry (the
      // direction in that frame is inside the cone then; a microfacet lobe's must also lie above
      // its own horizon, where it draws), and a microfacet lobe's spread outside the cone reaches
      // it too. The forward part's are drawn outside, so they reach every wi.
      int a = above[i];
      float n_frame = params[i].n_above;
      vec3 w_frame = lamina_to_frame(params, a, w[i]);
      vec3 w_own = lamina_to_entry(params[i], w[i]);
      // A flake paint draws its glitter as a microfacet lobe and its shade as a diffuse one.
      bool flakes = lamina_is_flake_paint(entries[i]);
      float glitter = lamina_flake_share(entries[i], params[i]);
      bool facets = lamina_is_microfacet_lobe(entries[i]);
      float density = 0.0f;
      if (facets || flakes) {
        float through = w_frame.z > 0.0f && w_own.z > 0.0f ? jacobian[i] : 0.0f;
        vec3 outer = lamina_to_frame(params, a, wi);
        vec3 spread = vec3(0.0f);
        if (n_frame > 1.0f && outer.z > 0.0f)
          spread = lamina_to_entry(params[i], lamina_from_frame(params, a, lamina_spread_source(outer, n_frame)));
        density = lamina_microfacet_lobe_pdf(entries[i].distribution, params[i].m, v[i], w_own, through, spread,
                                             n_frame);
      }
      if (!facets) {
        float diffuse = w_frame.z > 0.0f ? lamina_diffuse_lobe_pdf(w_frame, jacobian[i], n_frame) : 0.0f;
        density = glitter * density + (1.0f - glitter) * diffuse;
      }
      float forward = lamina_forward_sampling_share(entries, params, i, v[i]);
      pdf += weight[i] * ((1.0f - forward) * density + forward * wi.z * LAMINA_INV_PI);
    }
  }
  return pdf;
}

// The entry whose lobe u_lobe picks by the selection weights; -1 if none can be drawn.
LAMINA_FN int lamina_stack_choose(int count, LAMINA_IN_ARRAY(float) weight[LAMINA_STACK], float u_lobe) {
  int chosen = -1;
  float cumulative = 0.0f;
  bool found = false;
  for (int i = 0; i < count; ++i) {
    if (!found && weight[i] > 0.0f) {
      chosen = i;
      cumulative += weight[i];
      found = u_lobe < cumulative;
    }
  }
  return chosen;
}

// A direction drawn from the lobe of entry `chosen` (of the selection whose v is given) with u,
// carried up to the outside through the layers above it (refract_up, bottom to top); vec3(0) if
// none could be drawn or it cannot leave. Every entry is read at a loop's own index, never at the
// data-dependent `chosen`: unrolled, a GLSL compiler reads the stack's constants and runs each
// lobe's own sampling code where it is chosen.
LAMINA_FN vec3 lamina_stack_sample(int count, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_STACK],
                                   LAMINA_IN_ARRAY(LaminaParams) params[LAMINA_STACK],
                                   LAMINA_IN_ARRAY(vec3) v[LAMINA_STACK], int chosen, vec2 u) {
  if (chosen < 0) return vec3(0.0f);
  bool inside_cone = true;
  vec3 w = vec3(0.0f);
  int above[LAMINA_STACK];
  for (int i = 0; i < count; ++i) {
    above[i] = lamina_frame_above(entries, above, i);
    if (i == chosen) {
      // A conductor's share for its layer's forward part: cosine-weighted, already outside.
      // A microfacet lobe reflects in its own frame; its draw is tested against the exit cone in
      // the frame of the layer above it (lamina_frame_above), where it refracts. A diffuse lobe draws
      // in that frame directly, cosine-weighted inside the cone: so every direction a tilted lobe
      // reflects into can be drawn. The forward part's are drawn in the shading frame, outside.
      int a = above[i];
      float forward = lamina_forward_sampling_share(entries, params, i, v[i]);
      // A flake paint's glitter takes the draws with u.x below its share, its shade the others.
      bool flakes = lamina_is_flake_paint(entries[i]);
      float glitter = lamina_flake_share(entries[i], params[i]);
      if (u.x < forward) {
        w = lamina_sample_diffuse_lobe(vec2(u.x / forward, u.y), 1.0f);
        inside_cone = false;
      } else if (lamina_is_microfacet_lobe(entries[i]) || (flakes && u.x < glitter)) {
        bool own_inside = true;
        vec2 u_lobe = flakes ? vec2(u.x / glitter, u.y) : vec2((u.x - forward) / (1.0f - forward), u.y);
        vec3 own = lamina_sample_microfacet_lobe(entries[i].distribution, params[i].m, v[i], u_lobe, 1.0f, own_inside);
        vec3 in_frame = own.z > 0.0f ? lamina_to_frame(params, a, lamina_from_entry(params[i], own)) : vec3(0.0f);
        w = lamina_from_frame(params, a, lamina_leave_or_spread(in_frame, params[i].n_above, inside_cone));
      } else {
        vec2 u_lobe = flakes ? vec2((u.x - glitter) / (1.0f - glitter), u.y) : u;
        w = lamina_from_frame(params, a, lamina_sample_diffuse_lobe(u_lobe, params[i].n_above));
      }
    }
  }
  if (dot(w, w) <= 0.0f) return vec3(0.0f);
  // Up through the layers above it, nearest first: bottom up, an entry is on the way when it is the
  // chosen one or the parent of one on the way (children come after their parents).
  bool on_way[LAMINA_STACK];
  bool leaves = true;
  for (int i = count - 1; i >= 0; --i) {
    int kind = entries[i].kind;
    bool below = false;
    if (kind == LAMINA_LAYER) below = on_way[entries[i].first];
    if (kind == LAMINA_MIX) below = on_way[entries[i].first] || on_way[entries[i].second];
    on_way[i] = i == chosen || below;
    if (below && kind == LAMINA_LAYER && inside_cone && leaves) {
      vec3 local = lamina_to_entry(params[i], w);
      vec3 up = refract_up(local, params[i].eta);
      leaves = local.z > 0.0f && up.z > 0.0f;
      w = lamina_from_entry(params[i], up);
    }
  }
  // A tilted lobe's direction may leave below the surface's horizon: none.
  if (!leaves || w.z <= 0.0f) return vec3(0.0f);
  return normalize(w);
}

// --- a blend of parts ----------------------------------------------------------------------------
// Every mix of a compiled stack lies above every layer and substrate (compile.cpp hands a layer over
// a mix down into each stack it blends), so a stack is its blend, the tree of mixes at its top, over
// parts, each a chain of layers down to a substrate: f = sum over parts of share_k f_k, share_k the
// product of the mix weights on the path to part k (lamina_side_share), f_k the part evaluated as a
// stack of its own. That is the composition above, rearranged (it walks the mixes in the same
// loops). A back end evaluates a long stack so, one part at a time, in loops over the parts that
// copy a part into arrays of LAMINA_STACK entries, the longest part's length, so that the loops over
// entries stay short: GLSL compilers unroll no loop of more than 32 iterations, and then compile the
// whole stack's loops slowly (graph/limits.h, kGlslUnrolledEntries).
// The arrays: the blend's entries (its mixes and its parts' first entries, each with its parent and
// side in the blend) hold LAMINA_BLEND entries; part k's entries, parameters and selection hold
// [k LAMINA_STACK, k LAMINA_STACK + counts[k]) of arrays of LAMINA_PARTS LAMINA_STACK entries.

// A material's parameters at one shading point: its whole stack's (lamina_stack_resolve), or its
// blend's parts' and their shares (lamina_blend_resolve). The blend's functions take the point
// itself: handed an array of parameters, or a member of the point, Mesa's GLSL compiler copies it
// into every inlined call, and llvmpipe then took minutes to compile Lavender Lepidolite.
struct LaminaPoint {
  LaminaParams params[LAMINA_STACK];
  LaminaParams parts[LAMINA_PARTS * LAMINA_STACK];
  float share[LAMINA_PARTS];
};

// The lobe selection over a blend's parts at one wo, per entry as lamina_stack_select's.
struct LaminaPartsSelection {
  float weight[LAMINA_PARTS * LAMINA_STACK];
  vec3 v[LAMINA_PARTS * LAMINA_STACK];
  bool valid[LAMINA_PARTS * LAMINA_STACK];
};

// Part k's entries and parameters, in arrays of a stack's length for the composition above.
LAMINA_FN void lamina_part_entries(int k, LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                   LAMINA_OUT_ARRAY(LaminaEntry) e[LAMINA_STACK]) {
  for (int j = 0; j < LAMINA_STACK; ++j) e[j] = entries[k * LAMINA_STACK + j];
}
LAMINA_FN void lamina_part_params(int k, LAMINA_IN(LaminaPoint) point, LAMINA_OUT_ARRAY(LaminaParams) p[LAMINA_STACK]) {
  for (int j = 0; j < LAMINA_STACK; ++j) p[j] = point.parts[k * LAMINA_STACK + j];
}

// Every blend entry's share of the surface, top down (a part's first entry holds the part's).
LAMINA_FN void lamina_blend_shares(int count, LAMINA_IN_ARRAY(LaminaEntry) blend[LAMINA_BLEND],
                                   LAMINA_IN_ARRAY(LaminaInputs) inputs[LAMINA_BLEND],
                                   LAMINA_OUT_ARRAY(float) share[LAMINA_BLEND]) {
  float weight[LAMINA_BLEND];
  for (int i = 0; i < count; ++i) {
    int parent = blend[i].parent;
    weight[i] = blend[i].kind == LAMINA_MIX ? lamina_mix_weight(blend[i], inputs[i]) : 0.0f;
    share[i] = parent < 0 ? 1.0f : share[max(parent, 0)] * lamina_side_share(weight[max(parent, 0)], blend[i].side);
  }
}

// The parameters of every part (lamina_stack_resolve with the part's share).
LAMINA_FN void lamina_blend_resolve(int parts, LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                    LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                    LAMINA_IN_ARRAY(LaminaInputs) inputs[LAMINA_PARTS * LAMINA_STACK],
                                    LAMINA_IN_ARRAY(float) share[LAMINA_PARTS], bool clamp_lower, int model,
                                    LAMINA_OUT(LaminaPoint) point) {
  for (int k = 0; k < parts; ++k) {
    point.share[k] = share[k];
    LaminaEntry e[LAMINA_STACK];
    lamina_part_entries(k, entries, e);
    LaminaInputs x[LAMINA_STACK];
    for (int j = 0; j < LAMINA_STACK; ++j) x[j] = inputs[k * LAMINA_STACK + j];
    LaminaParams p[LAMINA_STACK];
    lamina_stack_resolve(counts[k], e, x, share[k], clamp_lower, model, p);
    for (int j = 0; j < LAMINA_STACK; ++j) point.parts[k * LAMINA_STACK + j] = p[j];
  }
}

// f(wi, wo) of the blend: its parts' f, each by the composition of the material's model, weighed by
// their shares.
LAMINA_FN vec3 lamina_blend_response(int parts, LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                     LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                     LAMINA_IN(LaminaPoint) point, int model, vec3 wi, vec3 wo, vec3 light,
                                     bool adjoint) {
  vec3 f = vec3(0.0f);
  for (int k = 0; k < parts; ++k) {
    LaminaEntry e[LAMINA_STACK];
    LaminaParams p[LAMINA_STACK];
    lamina_part_entries(k, entries, e);
    lamina_part_params(k, point, p);
    bool glows = lamina_stack_glows(counts[k], e);
    vec3 part = model == LAMINA_MODEL_ENERGY_CONSERVING
                    ? lamina_stack_response_conserving(counts[k], e, p, wi, wo, light, adjoint, glows)
                    : lamina_stack_response(counts[k], e, p, wi, wo, light, adjoint, glows);
    f += point.share[k] * part;
  }
  return f;
}

LAMINA_FN vec3 lamina_blend_eval(int parts, LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                 LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                 LAMINA_IN(LaminaPoint) point, int model, vec3 wi, vec3 wo) {
  return lamina_blend_response(parts, counts, entries, point, model, wi, wo, vec3(1.0f), false);
}

// The lobe selection over all the blend's lobes (lamina_stack_select's, with the floor and the
// normalisation over every part); an entry beyond its part's count gets weight 0, and the arrays
// beyond the last part are left as they were.
LAMINA_FN void lamina_blend_select(int parts, LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                   LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                   LAMINA_IN(LaminaPoint) point, vec3 wo, LAMINA_OUT(LaminaPartsSelection) s) {
  vec2 totals = vec2(0.0f);
  for (int k = 0; k < parts; ++k) {
    LaminaEntry e[LAMINA_STACK];
    LaminaParams p[LAMINA_STACK];
    lamina_part_entries(k, entries, e);
    lamina_part_params(k, point, p);
    float w[LAMINA_STACK];
    vec3 wo_own[LAMINA_STACK];
    bool reached[LAMINA_STACK];
    totals += lamina_stack_estimate(counts[k], e, p, wo, w, wo_own, reached);
    for (int j = 0; j < LAMINA_STACK; ++j) {
      bool used = j < counts[k];
      s.weight[k * LAMINA_STACK + j] = used ? w[j] : 0.0f;
      s.v[k * LAMINA_STACK + j] = used ? wo_own[j] : vec3(0.0f);
      s.valid[k * LAMINA_STACK + j] = used && reached[j];
    }
  }
  if (totals.y == 0.0f) return;
  float floor_share = lamina_selection_floor(totals);
  float sum = 0.0f;
  for (int k = 0; k < parts; ++k) {
    LaminaEntry e[LAMINA_STACK];
    lamina_part_entries(k, entries, e);
    float w[LAMINA_STACK];
    bool reached[LAMINA_STACK];
    for (int j = 0; j < LAMINA_STACK; ++j) {
      w[j] = s.weight[k * LAMINA_STACK + j];
      reached[j] = s.valid[k * LAMINA_STACK + j];
    }
    sum += lamina_stack_floored_sum(counts[k], e, w, reached, floor_share);
  }
  for (int i = 0; i < parts * LAMINA_STACK; ++i)
    s.weight[i] = lamina_floored_estimate(entries[i], s.valid[i], s.weight[i], floor_share) / sum;
}

// The density of wi under the blend's selection: the sum of its parts' (lamina_stack_pdf), whose
// weights are already shares of the whole.
LAMINA_FN float lamina_blend_pdf(int parts, LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                 LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                 LAMINA_IN(LaminaPoint) point, LAMINA_IN(LaminaPartsSelection) s, vec3 wi,
                                 vec3 wo) {
  float pdf = 0.0f;
  for (int k = 0; k < parts; ++k) {
    LaminaEntry e[LAMINA_STACK];
    LaminaParams p[LAMINA_STACK];
    lamina_part_entries(k, entries, e);
    lamina_part_params(k, point, p);
    float w[LAMINA_STACK];
    vec3 wo_own[LAMINA_STACK];
    bool reached[LAMINA_STACK];
    for (int j = 0; j < LAMINA_STACK; ++j) {
      w[j] = s.weight[k * LAMINA_STACK + j];
      wo_own[j] = s.v[k * LAMINA_STACK + j];
      reached[j] = s.valid[k * LAMINA_STACK + j];
    }
    pdf += lamina_stack_pdf(counts[k], e, p, w, wo_own, reached, wi, wo);
  }
  return pdf;
}

// The entry (k LAMINA_STACK + its index in part k) whose lobe u_lobe picks by the selection
// weights, in the order lamina_stack_choose reads a whole stack: the part where the running sum of
// the parts' weights passes u_lobe, then the lobe in it; -1 if none can be drawn.
LAMINA_FN int lamina_blend_choose(int parts, LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                  LAMINA_IN(LaminaPartsSelection) s, float u_lobe) {
  int part = -1;
  float before = 0.0f;  // the weight of the parts before `part`
  float cumulative = 0.0f;
  bool found = false;
  for (int k = 0; k < parts; ++k) {
    float total = 0.0f;
    for (int j = 0; j < LAMINA_STACK; ++j) total += j < counts[k] ? s.weight[k * LAMINA_STACK + j] : 0.0f;
    if (!found && total > 0.0f) {
      part = k;
      before = cumulative;
      cumulative += total;
      found = u_lobe < cumulative;
    }
  }
  if (part < 0) return -1;
  float w[LAMINA_STACK];
  for (int j = 0; j < LAMINA_STACK; ++j) w[j] = s.weight[part * LAMINA_STACK + j];
  int chosen = lamina_stack_choose(counts[part], w, u_lobe - before);
  return chosen < 0 ? -1 : part * LAMINA_STACK + chosen;
}

// A direction drawn from the lobe lamina_blend_choose chose (lamina_stack_sample in its part).
LAMINA_FN vec3 lamina_blend_sample(LAMINA_IN_ARRAY(int) counts[LAMINA_PARTS],
                                   LAMINA_IN_ARRAY(LaminaEntry) entries[LAMINA_PARTS * LAMINA_STACK],
                                   LAMINA_IN(LaminaPoint) point, LAMINA_IN(LaminaPartsSelection) s, int chosen,
                                   vec2 u) {
  if (chosen < 0) return vec3(0.0f);
  int k = chosen / LAMINA_STACK;
  LaminaEntry e[LAMINA_STACK];
  LaminaParams p[LAMINA_STACK];
  lamina_part_entries(k, entries, e);
  lamina_part_params(k, point, p);
  vec3 wo_own[LAMINA_STACK];
  for (int j = 0; j < LAMINA_STACK; ++j) wo_own[j] = s.v[k * LAMINA_STACK + j];
  return lamina_stack_sample(counts[k], e, p, wo_own, chosen - k * LAMINA_STACK, u);
}
