// lamina kernels: the material preview, defined once for its two renderers: the sphere of
// `lamina plot` (graph/cpu/preview.cpp, through the CPU evaluator) and `lamina glsl --shader
// sphere` (graph/glsl/sphere_shader.cpp, through the generated functions). Each writes only the
// loops that call its material's eval and sample; everything else is here, so both draw one picture.
//
// The picture: the unit sphere filling the shorter side of a viewport, seen orthographically along
// -z with y up, lit by one directional light from the upper left and a uniform sky. A pixel is the
// mean of LAMINA_PREVIEW_SUBSAMPLES^2 subsamples (lamina_preview_subsample, in that order); one off
// the sphere shows the background, one on it lamina_preview_display(light + sky), where light is
// lamina_preview_light of eval(wi, wo, uv) and sky is lamina_preview_sky of the weights of the
// LAMINA_PREVIEW_SKY_POINTS directions sample(lamina_preview_sky_view(wo), u, u_lobe, uv) draws from
// lamina_preview_sky_point, taken once per pixel, at its first subsample on the sphere.

// Subsamples per pixel along each axis.
const int LAMINA_PREVIEW_SUBSAMPLES = 4;

// The sky's reflection is a uniform environment's: its radiance times the directional albedo at wo.
// The albedo is estimated by importance sampling, from the same points in every pixel, so that the
// picture is smooth rather than noisy; this many per pixel.
const int LAMINA_PREVIEW_SKY_POINTS = 64;

// The sky's radiance unless a renderer is told otherwise (lamina plot --ambient): a white Lambertian
// surface shows this much on top of the light. Without it a smooth metal is black wherever it does
// not mirror the light.
const float LAMINA_PREVIEW_AMBIENT = 0.15f;

// Towards the light, (-1, 1, 1) normalised: from the upper left, on the viewer's side.
const vec3 LAMINA_PREVIEW_LIGHT = vec3(-0.577350269f, 0.577350269f, 0.577350269f);

// The light's irradiance at normal incidence: pi, so that a white Lambertian surface facing it shows 1.
const float LAMINA_PREVIEW_IRRADIANCE = LAMINA_PI;

// Towards the viewer.
const vec3 LAMINA_PREVIEW_VIEW = vec3(0.0f, 0.0f, 1.0f);

// Around the sphere, as display sRGB: mid grey, so that the unlit side shows its outline.
const vec3 LAMINA_PREVIEW_BACKGROUND = vec3(0.24f, 0.245f, 0.26f);

// The background as the linear value the subsamples average.
LAMINA_FN vec3 lamina_preview_background() { return srgb_to_linear(LAMINA_PREVIEW_BACKGROUND); }

// Subsample k of the pixel whose lower-left corner is `pixel` (integer coordinates, y up): the
// centres of an n x n grid over the pixel, row by row from the bottom left.
LAMINA_FN vec2 lamina_preview_subsample(vec2 pixel, int k) {
  int n = LAMINA_PREVIEW_SUBSAMPLES;
  return pixel + (vec2(float(k % n), float(k / n)) + vec2(0.5f)) / float(n);
}

// The point of the sphere's projection under p, a position in pixels in a viewport of `viewport`
// pixels (origin at its lower-left corner, y up): the unit disk spans the shorter side, centred.
LAMINA_FN vec2 lamina_preview_disk(vec2 p, vec2 viewport) { return (2.0f * p - viewport) / min(viewport.x, viewport.y); }

LAMINA_FN bool lamina_preview_on_sphere(vec2 q) { return dot(q, q) < 1.0f; }

// The sphere's normal, which is also its point, over q.
LAMINA_FN vec3 lamina_preview_normal(vec2 q) { return vec3(q.x, q.y, lamina_safe_sqrt(1.0f - dot(q, q))); }

// Texture coordinates: u the longitude about the y axis over 2 pi (0.5 facing the viewer, growing
// to the right), v the angle from the top pole over pi.
LAMINA_FN vec2 lamina_preview_uv(vec3 n) {
  return vec2(atan(n.x, n.z) / (2.0f * LAMINA_PI) + 0.5f, acos(clamp(n.y, -1.0f, 1.0f)) / LAMINA_PI);
}

// The shading context of the sphere's point over q (the viewport's size in pixels as in
// lamina_preview_disk): uv as lamina_preview_uv, the position the sphere's point itself (so that
// textures over position show), and the footprint the uv span of one subsample, from the uv one
// subsample across and one up, the finite differences dFdx and dFdy would take on the GPU, here the
// same on the CPU; u's differences are taken across its seam. The subsamples resolve the rest of
// the pixel.
LAMINA_FN LaminaContext lamina_preview_context(vec2 q, vec2 viewport) {
  vec3 n = lamina_preview_normal(q);
  LaminaContext ctx = lamina_context(lamina_preview_uv(n));
  float step = 2.0f / (min(viewport.x, viewport.y) * float(LAMINA_PREVIEW_SUBSAMPLES));
  vec2 across = lamina_preview_uv(lamina_preview_normal(q + vec2(step, 0.0f))) - ctx.uv;
  vec2 up = lamina_preview_uv(lamina_preview_normal(q + vec2(0.0f, step))) - ctx.uv;
  across.x -= floor(across.x + 0.5f);
  up.x -= floor(up.x + 0.5f);
  ctx.position = n;
  ctx.footprint = max(length(across), length(up));
  return ctx;
}

// A world direction w in the shading frame at normal n: z along n, x along the tangent, which
// follows the lines of latitude (the direction u grows in; x at the poles), y = z cross x.
LAMINA_FN vec3 lamina_preview_local(vec3 w, vec3 n) {
  vec3 t = vec3(n.z, 0.0f, -n.x);
  t = dot(t, t) > 1.0e-12f ? normalize(t) : vec3(1.0f, 0.0f, 0.0f);
  vec3 b = cross(n, t);
  return normalize(vec3(dot(t, w), dot(b, w), dot(n, w)));
}

// The light's reflected radiance, f cos_i E, given f = eval(wi, wo, uv); 0 when the light is
// behind the surface.
LAMINA_FN vec3 lamina_preview_light(vec3 f, vec3 wi) {
  return wi.z > 0.0f ? f * (wi.z * LAMINA_PREVIEW_IRRADIANCE) : vec3(0.0f);
}

// Point i of the sky estimator, the numbers (u.x, u.y, u_lobe) sample() draws with. u_lobe is
// stratified, so each lobe gets the points of a run of consecutive i in proportion to its weight;
// u follows the R2 sequence (Roberts 2018, "The unreasonable effectiveness of quasirandom
// sequences"), whose every run of consecutive points covers the square evenly.
LAMINA_FN vec3 lamina_preview_sky_point(int i) {
  float x = float(i);
  return vec3(fract(0.5f + x * 0.754877666f), fract(0.5f + x * 0.569840291f),
               (x + 0.5f) / float(LAMINA_PREVIEW_SKY_POINTS));
}

// The view direction the sky is estimated at: wo turned about the normal to azimuth 0. A material
// whose every lobe is isotropic (all of lamina's, while no entry's normal is tilted) reflects the sky
// the same for both; turned, the fixed points meet every wo of one cos(theta_o) alike, so the
// estimate depends on cos(theta_o) and uv alone, and a renderer may tabulate it over cos(theta_o)
// for a material without textures (graph/cpu/preview.cpp does).
LAMINA_FN vec3 lamina_preview_sky_view(vec3 wo) { return vec3(sqrt(wo.x * wo.x + wo.y * wo.y), 0.0f, wo.z); }

// One sky point's estimate of the directional albedo, f cos_i / pdf of the direction wi that sample()
// drew with density pdf and returned f for; 0 when it drew none.
LAMINA_FN vec3 lamina_preview_sky_weight(vec3 f, vec3 wi, float pdf) {
  return pdf > 0.0f ? f * (wi.z / pdf) : vec3(0.0f);
}

// The sky's reflected radiance from the sum of a pixel's sky weights: its radiance times the
// estimated albedo.
LAMINA_FN vec3 lamina_preview_sky(vec3 weight_sum, vec3 ambient) {
  return ambient * (weight_sum / float(LAMINA_PREVIEW_SKY_POINTS));
}

// A subsample on the sphere as its pixel averages it: the radiance at exposure 1, clipped to
// [0, 1]; black when it is not finite.
LAMINA_FN vec3 lamina_preview_display(vec3 radiance) {
  if (!(abs(radiance.x + radiance.y + radiance.z) <= 3.0e38f)) return vec3(0.0f);
  return clamp(radiance, vec3(0.0f), vec3(1.0f));
}

// The pixel, linear, from the sum over its subsamples (sRGB-encode it for display).
LAMINA_FN vec3 lamina_preview_mean(vec3 sum) {
  return sum / float(LAMINA_PREVIEW_SUBSAMPLES * LAMINA_PREVIEW_SUBSAMPLES);
}
