// lamina kernels: procedural textures (gradient noise, fBm, marble, Voronoi cells) from integer
// hashing, so that the CPU and every GPU draw the same random numbers: a lattice point's
// randomness is a function of its integer coordinates alone, computed in 32-bit unsigned
// arithmetic, which wraps identically in C++ and GLSL. No sin-fract hash, whose result depends on
// the platform's float precision.

// The pcg3d hash of Jarzynski and Olano, "Hash Functions for GPU Rendering" (JCGT 9(3), 2020,
// sec. 3 and listing of pcg3d): a linear congruential step per component, then two rounds in
// which each component absorbs the product of the other two, with an xor-shift between them.
LAMINA_FN uvec3 lamina_hash3(uvec3 v) {
  v = v * 1664525u + uvec3(1013904223u);
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v = v ^ (v >> 16u);
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// The hash of an integer lattice point under a seed: the seed moves the lattice by a different
// odd multiple per axis (the golden-ratio constant and two Murmur3 finaliser constants), so that
// seeds give independent patterns.
LAMINA_FN uvec3 lamina_hash_cell(ivec3 cell, uint seed) {
  return lamina_hash3(uvec3(cell) + seed * uvec3(2654435769u, 2246822507u, 3266489909u));
}

// The point a procedural texture reads: space 0 the texture coordinates (u, v, 0), space 1 the
// world-space position; times scale (features per unit).
LAMINA_FN vec3 lamina_space_point(vec2 uv, vec3 position, int space, float scale) {
  return (space == 1 ? position : vec3(uv, 0.0f)) * scale;
}

// The footprint a texture filters over, in units of uv: the context's over uv (space 0), at most
// 1e6 and 0 when it is not a positive number (NaN included); over position a point sample, since
// the context gives the pixel's size in uv only.
LAMINA_FN float lamina_space_footprint(float footprint, int space) {
  return space == 1 || !(footprint > 0.0f) ? 0.0f : min(footprint, 1.0e6f);
}

// A uniform number in [0, 1) from the top 24 bits of a hash, which a float holds exactly.
LAMINA_FN float lamina_hash_unit(uint h) { return float(h >> 8u) * (1.0f / 16777216.0f); }

// A coordinate the lattice functions can floor into an int: finite (NaN and inf read as 0) and
// within +-1e6, where float still resolves a sixteenth of a cell.
LAMINA_FN vec3 lamina_lattice_point(vec3 p) {
  vec3 q = vec3(abs(p.x) <= 1.0e6f ? p.x : 0.0f, abs(p.y) <= 1.0e6f ? p.y : 0.0f, abs(p.z) <= 1.0e6f ? p.z : 0.0f);
  return q;
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3 ("Improving Noise", SIGGRAPH 2002, sec. 4): its
// first and second derivatives vanish at 0 and 1, so the noise has no creases at cell faces.
LAMINA_FN vec3 lamina_fade(vec3 t) { return t * t * t * (t * (t * 6.0f - vec3(15.0f)) + vec3(10.0f)); }

// The gradient at a lattice point dotted with the offset d from it: one of the 12 vectors from the
// centre of a cube to its edges' midpoints, as in "Improving Noise" (sec. 3), picked by the hash:
// which coordinate is 0 from (h >> 2) mod 3, the signs of the other two from the low bits.
LAMINA_FN float lamina_gradient_dot(uint h, vec3 d) {
  float s1 = (h & 1u) != 0u ? -1.0f : 1.0f;
  float s2 = (h & 2u) != 0u ? -1.0f : 1.0f;
  uint axis = (h >> 2u) % 3u;
  vec3 g = axis == 0u ? vec3(0.0f, s1, s2) : (axis == 1u ? vec3(s1, 0.0f, s2) : vec3(s1, s2, 0.0f));
  return dot(g, d);
}

// Gradient noise at p (Perlin 2002): the gradients of the cell's 8 corners dotted with the offsets
// to p, blended with the fade curve. 0 at every lattice point; within about [-1, 1]. A point with
// p.z = 0 gives 2D noise over (x, y).
LAMINA_FN float lamina_perlin(vec3 p, uint seed) {
  vec3 q = lamina_lattice_point(p);
  vec3 base = floor(q);
  vec3 f = q - base;
  ivec3 cell = ivec3(base);
  vec3 w = lamina_fade(f);
  float n000 = lamina_gradient_dot(lamina_hash_cell(cell, seed).x, f);
  float n100 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(1, 0, 0), seed).x, f - vec3(1.0f, 0.0f, 0.0f));
  float n010 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(0, 1, 0), seed).x, f - vec3(0.0f, 1.0f, 0.0f));
  float n110 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(1, 1, 0), seed).x, f - vec3(1.0f, 1.0f, 0.0f));
  float n001 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(0, 0, 1), seed).x, f - vec3(0.0f, 0.0f, 1.0f));
  float n101 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(1, 0, 1), seed).x, f - vec3(1.0f, 0.0f, 1.0f));
  float n011 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(0, 1, 1), seed).x, f - vec3(0.0f, 1.0f, 1.0f));
  float n111 = lamina_gradient_dot(lamina_hash_cell(cell + ivec3(1, 1, 1), seed).x, f - vec3(1.0f, 1.0f, 1.0f));
  float x00 = mix(n000, n100, w.x);
  float x10 = mix(n010, n110, w.x);
  float x01 = mix(n001, n101, w.x);
  float x11 = mix(n011, n111, w.x);
  return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

// The mean of |lamina_perlin| over the plane z = 0 (2D noise over uv) and over space, measured
// over 4 million uniform points (tests/nodes/procedural_test.cpp checks both to 1%): what an octave
// of turbulence averages to over a footprint that covers many of its cells.
const float LAMINA_TURBULENCE_MEAN_2D = 0.2003f;
const float LAMINA_TURBULENCE_MEAN_3D = 0.2191f;

// Fractal sums of gradient noise (Musgrave's fBm in Ebert et al., "Texturing and Modeling", 3rd
// ed., ch. 16; Perlin's turbulence, "An Image Synthesizer", SIGGRAPH 1985, sec. 5): octave o has
// frequency lacunarity^o and amplitude gain^o and its own seed (seed + o), so octaves do not share
// lattice points. turbulence sums |noise| instead of noise. The sum is divided by the sum of the
// amplitudes: within about [-1, 1] (fBm) or [0, 1] (turbulence) at every octave count.
// footprint, the pixel's width in cells of the first octave, filters by clamping (Norton, Rockwood
// and Skolmoski, "Clamping: A Method of Antialiasing Textured Surfaces by Bandwidth Limiting in
// Object Space", SIGGRAPH 1982): an octave whose cells the pixel covers fades to its mean, fully
// kept up to half a cell per pixel, gone from one cell on, so that a receding surface converges to
// the average instead of flickering. 0 is a point sample.
LAMINA_FN float lamina_fbm(vec3 p, int octaves, float lacunarity, float gain, uint seed, bool turbulence,
                           float footprint) {
  float sum = 0.0f;
  float amplitudes = 0.0f;
  float amplitude = 1.0f;
  float frequency = 1.0f;
  // A faded octave's mean: 0 for fBm; for turbulence the plane's (z = 0: 2D noise) or space's.
  float mean = turbulence ? (p.z == 0.0f ? LAMINA_TURBULENCE_MEAN_2D : LAMINA_TURBULENCE_MEAN_3D) : 0.0f;
  for (int o = 0; o < octaves; ++o) {
    float n = lamina_perlin(p * frequency, seed + uint(o));
    float kept = clamp(2.0f - 2.0f * footprint * frequency, 0.0f, 1.0f);
    sum += amplitude * mix(mean, turbulence ? abs(n) : n, kept);
    amplitudes += amplitude;
    amplitude *= gain;
    frequency *= lacunarity;
  }
  return amplitudes > 0.0f ? sum / amplitudes : 0.0f;
}

// Perlin's marble ("An Image Synthesizer", sec. 5: sin of a coordinate plus turbulence) as a value
// in [0, 1]: 0.5 + 0.5 sin(2 pi (stripes dot(p, direction) + strength t)), t the turbulence of p.
// width, the stripe periods a pixel spans along u and along v, filters the sine as a box over the
// square pixel does exactly for undisplaced stripes: the box is the product of one along u and one
// along v, each of which multiplies a sine by its sinc, so the mean is the sine at the centre times
// sinc(width.x) sinc(width.y); many stripes per pixel converge to 0.5.
LAMINA_FN float lamina_sinc(float x) {
  float a = LAMINA_PI * x;
  return abs(a) < 1.0e-4f ? 1.0f : sin(a) / a;
}

LAMINA_FN float lamina_marble(float stripe_coordinate, float turbulence_value, float strength, vec2 width) {
  float attenuation = lamina_sinc(width.x) * lamina_sinc(width.y);
  return 0.5f + 0.5f * attenuation * sin(2.0f * LAMINA_PI * (stripe_coordinate + strength * turbulence_value));
}

// Worley's cellular texture ("A Cellular Texture Basis Function", SIGGRAPH 1996) on a jittered
// grid: every unit cell holds one feature point at its centre moved by jitter * (u - 0.5), u
// uniform in [0, 1)^3 from the cell's hash. F1 and F2 are the distances from p to the nearest and
// second nearest feature points among the 3x3 cells around p (3x3x3 when three_d; in 2D, p.z and
// the points' z are 0). Returns (F1, F2); cell is the nearest point's cell. A tie keeps the cell
// visited first, in the fixed order of the loops.
LAMINA_FN vec2 lamina_voronoi(vec3 p, bool three_d, float jitter, uint seed, LAMINA_OUT(ivec3) cell) {
  vec3 q = lamina_lattice_point(p);
  q.z = three_d ? q.z : 0.0f;
  ivec3 home = ivec3(floor(q));
  int reach_z = three_d ? 1 : 0;
  float f1 = 1.0e30f;
  float f2 = 1.0e30f;
  cell = home;
  for (int dz = -reach_z; dz <= reach_z; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 c = home + ivec3(dx, dy, dz);
        uvec3 h = lamina_hash_cell(c, seed);
        vec3 u = vec3(lamina_hash_unit(h.x), lamina_hash_unit(h.y), lamina_hash_unit(h.z));
        vec3 point = vec3(c) + vec3(0.5f) + jitter * (u - vec3(0.5f));
        point.z = three_d ? point.z : 0.0f;
        vec3 d = point - q;
        float d2 = dot(d, d);
        bool nearer = d2 < f1;
        f2 = nearer ? f1 : min(f2, d2);
        cell = nearer ? c : cell;
        f1 = nearer ? d2 : f1;
      }
    }
  }
  return vec2(sqrt(f1), sqrt(f2));
}

// A cell's attributes, from a second and third hash of its point's hash: a value in [0, 1)
// (random_value.x), a colour in [0, 1)^3 (random_value.yzw), and two more uniforms for its normal
// (the return value).
LAMINA_FN vec2 lamina_cell_randoms(ivec3 cell, uint seed, LAMINA_OUT(vec4) random_value) {
  uvec3 a = lamina_hash3(lamina_hash_cell(cell, seed) ^ uvec3(2747636419u, 2654435769u, 3266489917u));
  uvec3 b = lamina_hash3(a);
  random_value = vec4(lamina_hash_unit(a.x), lamina_hash_unit(a.y), lamina_hash_unit(a.z), lamina_hash_unit(b.x));
  return vec2(lamina_hash_unit(b.y), lamina_hash_unit(b.z));
}

// Elek's metal flakes (Elek 2010, sec. 4.1): a flake map of one random colour c per cell of the
// unit grid at p (its scale tiles it: about 1000 times over uv in Elek's paint), read without
// filtering, so that each shading point sees the one flake it hits; the flake's normal
//   N = normalize(max(d, 1) (0, 0, 1) + (2 c - 1)),
// d the distance to the viewer, fades towards +z as the paint recedes and its flakes blur together.
LAMINA_FN vec3 lamina_flake_normal(vec3 p, uint seed, float view_distance) {
  uvec3 h = lamina_hash_cell(ivec3(floor(lamina_lattice_point(p))), seed);
  vec3 c = vec3(lamina_hash_unit(h.x), lamina_hash_unit(h.y), lamina_hash_unit(h.z));
  // d at least 1 (Elek's max), at most 1e6, and 1 when it is not a number.
  float d = view_distance > 1.0f ? min(view_distance, 1.0e6f) : 1.0f;
  return normalize(d * vec3(0.0f, 0.0f, 1.0f) + (2.0f * c - vec3(1.0f)));
}

// A unit normal tilted from +z with the slope distribution of a microfacet model of slope m
// (tan of the roughness angle), from two uniforms u in [0, 1): the inversion of the distribution's
// slope CDF of Walter et al., "Microfacet Models for Refraction" (EGSR 2007), eq. 28 for Beckmann,
// tan^2 theta = -m^2 ln(1 - u.x), and eq. 35 for GGX, tan^2 theta = m^2 u.x / (1 - u.x); the
// azimuth is 2 pi u.y. distribution: 0 Beckmann, 2 GGX (microfacet.glsl's numbering; Blinn
// tilts as Beckmann, whose slopes it matches).
LAMINA_FN vec3 lamina_tilted_normal(vec2 u, float m, int distribution) {
  float rest = 1.0f - u.x;  // in (0, 1]: u.x < 1
  float tan2 = distribution == 2 ? m * m * u.x / rest : -m * m * log(rest);
  float cos_theta = 1.0f / sqrt(1.0f + tan2);
  float sin_theta = sqrt(max(1.0f - cos_theta * cos_theta, 0.0f));
  float phi = 2.0f * LAMINA_PI * u.y;
  return vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

// --- what the texture nodes output ---------------------------------------------------------------

// texture/noise's value in [0, 1]: 0.5 + 0.5 fBm, or the turbulence itself; footprint in cells of
// the first octave (lamina_fbm).
LAMINA_FN float lamina_noise_value(vec3 p, int octaves, float lacunarity, float gain, uint seed, bool turbulence,
                                   float footprint) {
  float s = lamina_fbm(p, octaves, lacunarity, gain, seed, turbulence, footprint);
  return clamp(turbulence ? s : 0.5f + 0.5f * s, 0.0f, 1.0f);
}

// texture/marble's value in [0, 1] at the unscaled point p: stripes across direction (stripes per
// unit of p along it), displaced by strength times the turbulence of p scale; footprint in units
// of p.
LAMINA_FN float lamina_marble_value(vec3 p, float scale, vec3 direction, float stripes, float strength, int octaves,
                                    float lacunarity, float gain, uint seed, float footprint) {
  float t = lamina_fbm(p * scale, octaves, lacunarity, gain, seed, true, footprint * scale);
  vec2 width = stripes * footprint * vec2(abs(direction.x), abs(direction.y));
  return lamina_marble(stripes * dot(p, direction), t, strength, width);
}

// texture/voronoi's outputs at one point.
struct LaminaVoronoi {
  vec2 distances;  // F1, F2
  float value;     // the nearest cell's random value in [0, 1)
  vec3 colour;     // its random colour in [0, 1)^3
  vec3 normal;     // its random unit normal, tilted from +z by slope m's distribution
  float coverage;  // how much of the pattern the pixel averages: 0 a point sample, 1 many cells
};

// tilt_deg: the RMS slope angle of the cells' normals (m = tan(tilt_deg)); distribution as for
// lamina_tilted_normal. footprint: the pixel's width in cells. A pixel over many cells should show
// their mean, not whichever cell its centre hits (which flickers as the surface moves), so the
// cell's attributes fade to their means over the pattern: fully kept up to half a cell per pixel,
// gone from two cells on (about 4 cells in the pixel); the coverage is 1 - kept. The value and
// colour are uniform and fade to 1/2. The normal fades to the mean normal (0, 0, L) with
// L = 2 / (2 + m^2), which lamina_widened_slope reads as a slope variance of m^2 added to the lobe
// it tilts: the cells' slope distribution convolved into the lobe (to first order in m^2, L is
// the mean of cos theta over the cells, 1 - m^2 / 2). The distances stay point samples.
LAMINA_FN LaminaVoronoi lamina_voronoi_cell(vec3 p, bool three_d, float jitter, uint seed, float tilt_deg,
                                            int distribution, float footprint) {
  ivec3 cell = ivec3(0);
  LaminaVoronoi r;
  r.distances = lamina_voronoi(p, three_d, jitter, seed, cell);
  vec4 random_value = vec4(0.0f);
  vec2 u = lamina_cell_randoms(cell, seed, random_value);
  float kept = clamp((2.0f - footprint) / 1.5f, 0.0f, 1.0f);
  float m = tan(tilt_deg * LAMINA_PI / 180.0f);
  r.value = mix(0.5f, random_value.x, kept);
  r.colour = mix(vec3(0.5f), vec3(random_value.y, random_value.z, random_value.w), kept);
  r.normal = mix(vec3(0.0f, 0.0f, 2.0f / (2.0f + m * m)), lamina_tilted_normal(u, m, distribution), kept);
  r.coverage = 1.0f - kept;
  return r;
}

// Elek's patina weight (sec. 4.2): 1 - smoothstep(extent - transition, extent + transition, p), 1
// where the grey map p is below extent by more than transition (patina), 0 above it by more.
LAMINA_FN float lamina_patina_weight(float p, float extent, float transition) {
  return 1.0f - smoothstep_value(p, extent - transition, extent + transition);
}
