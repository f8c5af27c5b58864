#include "graph/gltf/fallback.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "graph/cpu/evaluator.h"
#include "graph/parallel.h"
#include "nodes/kernels/kernels.h"

namespace lamina::gltf {

namespace {

PbrParams lerp(const PbrParams& a, const PbrParams& b, float t) {
  PbrParams p;
  p.base_color = glm::mix(a.base_color, b.base_color, t);
  p.metallic = std::lerp(a.metallic, b.metallic, t);
  p.roughness = std::lerp(a.roughness, b.roughness, t);
  p.ior = std::lerp(a.ior, b.ior, t);
  p.specular = std::lerp(a.specular, b.specular, t);
  p.specular_color = glm::mix(a.specular_color, b.specular_color, t);
  p.clearcoat = std::lerp(a.clearcoat, b.clearcoat, t);
  p.clearcoat_roughness = std::lerp(a.clearcoat_roughness, b.clearcoat_roughness, t);
  p.iridescence = std::lerp(a.iridescence, b.iridescence, t);
  p.iridescence_ior = std::lerp(a.iridescence_ior, b.iridescence_ior, t);
  p.iridescence_thickness = std::lerp(a.iridescence_thickness, b.iridescence_thickness, t);
  return p;
}

uint8_t to_byte(float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

void widen(FitError& worst, const FitError& e) {
  worst.albedo_normal = std::max(worst.albedo_normal, e.albedo_normal);
  worst.unreachable_normal = std::max(worst.unreachable_normal, e.unreachable_normal);
  worst.albedo_grazing = std::max(worst.albedo_grazing, e.albedo_grazing);
  worst.rms = std::max(worst.rms, e.rms);
  worst.lightness = std::max(worst.lightness, e.lightness);
  worst.colour = std::max(worst.colour, e.colour);
}

// The distinct texture states over the bake grid: which state each texel has, and each state's
// registers and first texel.
struct StateGrid {
  std::vector<std::vector<float>> registers;
  std::vector<glm::vec2> first_uv;
  std::vector<int> texels;
  std::vector<int> state_of;  // per texel, row-major from the top-left
};

// A texel's shading context: its centre, and a footprint of one texel, so that detail finer than a
// texel (Voronoi cells, noise octaves) bakes as its mean rather than as whichever value the centre hits.
ShadingContext texel_context(glm::vec2 uv, int size) {
  ShadingContext ctx;
  ctx.uv = uv;
  ctx.footprint = 1.0f / float(size);
  return ctx;
}

StateGrid texture_states(const cpu::Evaluator& evaluator, int size) {
  StateGrid grid;
  std::map<std::vector<float>, int> index;
  grid.state_of.resize(static_cast<size_t>(size) * static_cast<size_t>(size));
  ShadingContext ctx = texel_context(glm::vec2(0.0f), size);
  for (int row = 0; row < size; ++row)
    for (int column = 0; column < size; ++column) {
      ctx.uv = glm::vec2((float(column) + 0.5f) / float(size), (float(row) + 0.5f) / float(size));
      auto registers = evaluator.texture_registers(ctx);
      auto [it, inserted] = index.emplace(std::move(registers), static_cast<int>(grid.registers.size()));
      if (inserted) {
        grid.registers.push_back(it->first);
        grid.first_uv.push_back(ctx.uv);
        grid.texels.push_back(0);
      }
      ++grid.texels[static_cast<size_t>(it->second)];
      grid.state_of[static_cast<size_t>(row) * static_cast<size_t>(size) + static_cast<size_t>(column)] = it->second;
    }
  return grid;
}

// Register-space distances with every register scaled to its range over the grid, so that a
// colour in [0, 1] and a remapped weight count alike.
class StateMetric {
 public:
  explicit StateMetric(const std::vector<std::vector<float>>& states) {
    const size_t n = states.front().size();
    lo_.assign(n, std::numeric_limits<float>::max());
    scale_.assign(n, std::numeric_limits<float>::lowest());
    for (const auto& s : states)
      for (size_t i = 0; i < n; ++i) {
        lo_[i] = std::min(lo_[i], s[i]);
        scale_[i] = std::max(scale_[i], s[i]);
      }
    for (size_t i = 0; i < n; ++i) {
      float range = scale_[i] - lo_[i];
      scale_[i] = range > 0.0f ? 1.0f / range : 0.0f;
    }
  }
  double distance2(const std::vector<float>& a, const std::vector<float>& b) const {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      double d = double(a[i] - b[i]) * double(scale_[i]);
      sum += d * d;
    }
    return sum;
  }
  // Where the projection of x falls on the segment a..b, clamped to [0, 1].
  float along(const std::vector<float>& x, const std::vector<float>& a, const std::vector<float>& b) const {
    double dot = 0.0, length2 = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      double ab = double(b[i] - a[i]) * double(scale_[i]);
      dot += double(x[i] - a[i]) * double(scale_[i]) * ab;
      length2 += ab * ab;
    }
    return length2 > 0.0 ? static_cast<float>(std::clamp(dot / length2, 0.0, 1.0)) : 0.0f;
  }

 private:
  std::vector<float> lo_, scale_;
};

// Farthest-point sampling: the state farthest from the mean first, then repeatedly the state
// farthest from those chosen. Extremes come first, then the gaps between them fill in.
std::vector<int> representatives(const std::vector<std::vector<float>>& states, const StateMetric& metric, int count) {
  std::vector<float> mean(states.front().size(), 0.0f);
  for (const auto& s : states)
    for (size_t i = 0; i < s.size(); ++i) mean[i] += s[i] / float(states.size());
  std::vector<double> nearest(states.size());
  for (size_t s = 0; s < states.size(); ++s) nearest[s] = metric.distance2(states[s], mean);
  std::vector<int> chosen;
  while (static_cast<int>(chosen.size()) < count) {
    size_t best = static_cast<size_t>(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
    if (!chosen.empty() && nearest[best] <= 0.0) break;
    chosen.push_back(static_cast<int>(best));
    for (size_t s = 0; s < states.size(); ++s)
      nearest[s] = chosen.size() == 1 ? metric.distance2(states[s], states[best])
                                      : std::min(nearest[s], metric.distance2(states[s], states[best]));
  }
  return chosen;
}

struct Range {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  void add(float v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  // Constant when every texel would store the same byte.
  bool varies() const { return to_byte(lo) != to_byte(hi); }
};

// The fallback from per-texel parameters: factors where a parameter is uniform, textures where it
// varies. ior, the specular extension and the film's index have no per-texel form worth baking
// here; they take the texel-weighted mean.
void bake(const std::vector<PbrParams>& texel_params, int size, Fallback& out) {
  Range base[3], metallic, roughness, clearcoat, clearcoat_roughness;
  float thinnest = std::numeric_limits<float>::max(), thickest = 0.0f;
  double ior = 0.0, specular = 0.0, film_ior = 0.0;
  glm::dvec3 specular_color(0.0), base_mean(0.0);
  double metallic_mean = 0.0, roughness_mean = 0.0, clearcoat_mean = 0.0, clearcoat_roughness_mean = 0.0;
  for (const auto& p : texel_params) {
    // glTF stores base colour textures sRGB-encoded: their bytes vary where the encoded values do.
    const glm::vec3 srgb = kernels::srgb_from_linear(p.base_color);
    for (int c = 0; c < 3; ++c) base[c].add(srgb[c]);
    metallic.add(p.metallic);
    roughness.add(p.roughness);
    clearcoat.add(p.clearcoat);
    clearcoat_roughness.add(p.clearcoat_roughness);
    ior += p.ior;
    film_ior += p.iridescence_ior;
    thinnest = std::min(thinnest, p.iridescence_thickness);
    thickest = std::max(thickest, p.iridescence_thickness);
    specular += p.specular;
    specular_color += glm::dvec3(p.specular_color);
    base_mean += glm::dvec3(p.base_color);
    metallic_mean += p.metallic;
    roughness_mean += p.roughness;
    clearcoat_mean += p.clearcoat;
    clearcoat_roughness_mean += p.clearcoat_roughness;
  }
  const double n = static_cast<double>(texel_params.size());
  PbrParams& f = out.params;
  f.ior = static_cast<float>(ior / n);
  f.specular = static_cast<float>(specular / n);
  f.specular_color = glm::vec3(specular_color / n);
  const size_t texels = texel_params.size();
  if (out.uses_iridescence) {
    f.iridescence = 1.0f;
    f.iridescence_ior = static_cast<float>(film_ior / n);
    f.iridescence_thickness = thickest;
    out.iridescence_thickness_min = thickest;
    // A thickness texture, from the thinnest film to the thickest, where the two differ by more than
    // half a byte's step of a range from 0 to the thickest (1 nm added so that a film of 0 nm counts).
    if (thickest - thinnest > (thickest + 1.0f) / 510.0f) {
      BakedImage image{size, 3, std::vector<uint8_t>(texels * 3, 0)};
      for (size_t t = 0; t < texels; ++t) {
        image.pixels[t * 3] = 255;
        image.pixels[t * 3 + 1] = to_byte((texel_params[t].iridescence_thickness - thinnest) / (thickest - thinnest));
      }
      out.iridescence_thickness = std::move(image);
      out.iridescence_thickness_min = thinnest;
    }
  }

  if (base[0].varies() || base[1].varies() || base[2].varies()) {
    BakedImage image{size, 3, std::vector<uint8_t>(texels * 3)};
    for (size_t t = 0; t < texels; ++t) {
      glm::vec3 srgb = kernels::srgb_from_linear(texel_params[t].base_color);
      for (int c = 0; c < 3; ++c) image.pixels[t * 3 + static_cast<size_t>(c)] = to_byte(srgb[c]);
    }
    out.base_color = std::move(image);
    f.base_color = glm::vec3(1.0f);
  } else {
    f.base_color = glm::vec3(base_mean / n);
  }
  if (metallic.varies() || roughness.varies()) {
    BakedImage image{size, 3, std::vector<uint8_t>(texels * 3, 0)};
    for (size_t t = 0; t < texels; ++t) {
      image.pixels[t * 3 + 1] = to_byte(texel_params[t].roughness);
      image.pixels[t * 3 + 2] = to_byte(texel_params[t].metallic);
    }
    out.metallic_roughness = std::move(image);
    f.metallic = f.roughness = 1.0f;
  } else {
    f.metallic = static_cast<float>(metallic_mean / n);
    f.roughness = static_cast<float>(roughness_mean / n);
  }
  if (out.uses_clearcoat && (clearcoat.varies() || clearcoat_roughness.varies())) {
    BakedImage image{size, 3, std::vector<uint8_t>(texels * 3, 0)};
    for (size_t t = 0; t < texels; ++t) {
      image.pixels[t * 3] = to_byte(texel_params[t].clearcoat);
      image.pixels[t * 3 + 1] = to_byte(texel_params[t].clearcoat_roughness);
    }
    out.clearcoat = std::move(image);
    f.clearcoat = f.clearcoat_roughness = 1.0f;
  } else {
    f.clearcoat = static_cast<float>(clearcoat_mean / n);
    f.clearcoat_roughness = static_cast<float>(clearcoat_roughness_mean / n);
  }
}

// Which entries a baked normal texture follows: the base's (glTF's normalTexture: the substrates)
// or the coat's (KHR_materials_clearcoat's clearcoatNormalTexture: the top interface of each stack
// a mix blends, the one whose lobe the clearcoat fits).
enum class Surface { base, coat };

bool on_surface(const std::vector<StackEntry>& stack, size_t i, Surface surface) {
  const StackEntry& e = stack[i];
  if (surface == Surface::base) return e.kind == kernels::LAMINA_SUBSTRATE;
  return e.kind == kernels::LAMINA_LAYER && (e.parent < 0 || stack[size_t(e.parent)].kind == kernels::LAMINA_MIX);
}

// Whether a texture tilts some entry of the surface.
bool tilted_by_texture(const Program& program, Surface surface) {
  for (size_t i = 0; i < program.stack.size(); ++i)
    if (on_surface(program.stack, i, surface) && program.stack[i].normal.linked()) return true;
  return false;
}

// The surface's normal at a point: the mean of its entries' normals, each weighted by its share of
// the stack (its cells' coverage under a select). Not normalised: texels average it.
glm::vec3 surface_normal(const cpu::Evaluator& evaluator, const ShadingContext& ctx, Surface surface) {
  const std::vector<cpu::Evaluator::EntryCover> covers = evaluator.entry_covers(ctx);
  const std::vector<StackEntry>& stack = evaluator.program().stack;
  glm::vec3 sum(0.0f);
  for (size_t i = 0; i < covers.size(); ++i)
    if (on_surface(stack, i, surface)) sum += covers[i].share * covers[i].normal;
  return sum;
}

// Subsamples per texel side for the normal texture.
constexpr int kNormalSubsamples = 2;

// A texel of a normal texture: the surface's normal averaged over it, and whether the texel
// resolves it (its points' normals agree).
struct TexelNormal {
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  bool resolved = true;
};

// Texel (row, column) of a size x size bake: the surface's normal averaged over kNormalSubsamples^2
// points of the texel, each with its own share of the footprint, normalised. The fit is of the
// untilted point (Evaluator::bind_untilted), so the texture puts the tilt back. Texture nodes that
// filter over the footprint (Voronoi glitter) and those that do not (texture/flakes, sampled
// without filtering as Elek's flakes are) bake alike, as their mean over the texel. The texel
// resolves the tilt when the mean of its points' unit normals is longer than cos 1 degree: inside
// one glitter cell, not over many flakes.
TexelNormal texel_normal(const cpu::Evaluator& evaluator, int row, int column, int size, Surface surface) {
  const int n = kNormalSubsamples;
  ShadingContext ctx;
  ctx.footprint = 1.0f / float(size * n);
  glm::vec3 sum(0.0f), unit_sum(0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      ctx.uv =
          glm::vec2((float(column * n + i) + 0.5f) / float(size * n), (float(row * n + j) + 0.5f) / float(size * n));
      const glm::vec3 normal = surface_normal(evaluator, ctx, surface);
      sum += normal;
      if (glm::dot(normal, normal) > 0.0f) unit_sum += glm::normalize(normal);
    }
  TexelNormal texel;
  if (glm::dot(sum, sum) > 0.0f) texel.normal = glm::normalize(sum);
  texel.resolved = glm::length(unit_sum) >= 0.99985f * float(n * n);  // cos(1 degree)
  return texel;
}

// glTF's normal texture encoding: n * 0.5 + 0.5 per component.
uint8_t normal_byte(float n) { return to_byte(0.5f * n + 0.5f); }

// The normal texture of the texels' normals where it helps: when some texels are a byte's step
// from flat, and at least half of those resolve their tilt. Otherwise it would show the bake's
// sampling noise (flakes finer than a texel) rather than facets, and the fallback stays flat.
std::optional<BakedImage> bake_normals(const std::vector<TexelNormal>& texels, int size) {
  const uint8_t flat[3] = {normal_byte(0.0f), normal_byte(0.0f), normal_byte(1.0f)};
  BakedImage image{size, 3, std::vector<uint8_t>(texels.size() * 3)};
  size_t tilted = 0, resolved = 0;
  for (size_t t = 0; t < texels.size(); ++t) {
    bool off_flat = false;
    for (int c = 0; c < 3; ++c) {
      const uint8_t b = normal_byte(texels[t].normal[c]);
      image.pixels[t * 3 + static_cast<size_t>(c)] = b;
      off_flat = off_flat || b != flat[c];
    }
    tilted += off_flat ? 1 : 0;
    resolved += off_flat && texels[t].resolved ? 1 : 0;
  }
  if (tilted == 0 || 2 * resolved < tilted) return std::nullopt;
  return image;
}

}  // namespace

int auto_bake_size(const Program& program) {
  float detail = 0.0f;
  for (const TextureOp& op : program.ops)
    if (op.decl && op.decl->uv_detail) detail = std::max(detail, op.decl->uv_detail(op));
  int size = kMinAutoBakeSize;
  while (size < kMaxAutoBakeSize && float(size) < 2.0f * detail) size *= 2;
  return size;
}

Fallback fit_fallback(const Program& program, const FallbackOptions& options) {
  const cpu::Evaluator evaluator(program);
  Fallback out;
  auto record = [&](const FitResult& fit, glm::vec2 uv, int texels) {
    out.states.push_back({fit, uv, texels});
    out.uses_ior = out.uses_ior || fit.uses_ior;
    out.uses_specular = out.uses_specular || fit.uses_specular;
    out.uses_clearcoat = out.uses_clearcoat || fit.uses_clearcoat;
    out.uses_iridescence = out.uses_iridescence || fit.uses_iridescence;
    widen(out.worst, fit.error);
  };

  if (program.ops.empty()) {
    ShadingContext ctx;
    ctx.uv = glm::vec2(0.5f);
    FitResult fit = fit_pbr(evaluator, ctx);
    record(fit, ctx.uv, 1);
    out.params = fit.params;
    out.iridescence_thickness_min = fit.params.iridescence_thickness;
    return out;
  }

  const int size = options.bake_size > 0 ? options.bake_size : auto_bake_size(program);
  out.bake_size = size;
  const StateGrid grid = texture_states(evaluator, size);
  const size_t state_count = grid.registers.size();
  std::vector<PbrParams> state_params(state_count);
  auto fit_state = [&](size_t s) { return fit_pbr(evaluator, texel_context(grid.first_uv[s], size)); };

  if (static_cast<int>(state_count) <= options.max_states) {
    for (size_t s = 0; s < state_count; ++s) {
      FitResult fit = fit_state(s);
      record(fit, grid.first_uv[s], grid.texels[s]);
      state_params[s] = fit.params;
    }
  } else {
    // Fit a few representative states; every other state interpolates between the two nearest
    // along the segment joining them (exact for a material that varies along one register).
    out.interpolated = true;
    const StateMetric metric(grid.registers);
    const std::vector<int> chosen = representatives(grid.registers, metric, std::max(2, options.max_states));
    std::vector<PbrParams> chosen_params;
    for (int s : chosen) {
      FitResult fit = fit_state(static_cast<size_t>(s));
      record(fit, grid.first_uv[static_cast<size_t>(s)], grid.texels[static_cast<size_t>(s)]);
      chosen_params.push_back(fit.params);
    }
    for (size_t s = 0; s < state_count; ++s) {
      size_t first = 0, second = 0;
      double d_first = std::numeric_limits<double>::max(), d_second = d_first;
      for (size_t c = 0; c < chosen.size(); ++c) {
        double d = metric.distance2(grid.registers[s], grid.registers[static_cast<size_t>(chosen[c])]);
        if (d < d_first) {
          second = first, d_second = d_first;
          first = c, d_first = d;
        } else if (d < d_second) {
          second = c, d_second = d;
        }
      }
      float t = metric.along(grid.registers[s], grid.registers[static_cast<size_t>(chosen[first])],
                             grid.registers[static_cast<size_t>(chosen[second])]);
      state_params[s] = lerp(chosen_params[first], chosen_params[second], t);
    }
  }

  std::vector<PbrParams> texel_params(grid.state_of.size());
  for (size_t t = 0; t < texel_params.size(); ++t)
    texel_params[t] = state_params[static_cast<size_t>(grid.state_of[t])];
  bake(texel_params, size, out);

  // A normal texture only for a surface a texture tilts: the base's, and the coat's where the fit
  // gave the material a clearcoat (without one, the top interface's lobe is the base's specular,
  // whose normal is the base's).
  const auto bake_surface = [&](Surface surface) {
    std::vector<TexelNormal> texel_normals(grid.state_of.size());
    parallel_for(static_cast<size_t>(size), [&](size_t row) {
      for (int column = 0; column < size; ++column)
        texel_normals[row * static_cast<size_t>(size) + static_cast<size_t>(column)] =
            texel_normal(evaluator, static_cast<int>(row), column, size, surface);
    });
    return bake_normals(texel_normals, size);
  };
  if (tilted_by_texture(program, Surface::base)) out.normal = bake_surface(Surface::base);
  if (out.uses_clearcoat && tilted_by_texture(program, Surface::coat))
    out.clearcoat_normal = bake_surface(Surface::coat);
  return out;
}

}  // namespace lamina::gltf
