// Fitting glTF's reference BRDF to a target BRDF; the objective and search are documented in
// pbr_fit.h (fit_pbr(const FitTarget&)).
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <numbers>

#include "graph/gltf/appearance.h"
#include "graph/gltf/hemisphere_quadrature.h"
#include "graph/gltf/pbr_fit.h"

namespace lamina::gltf {

namespace {

constexpr std::array<float, 6> kViewDegrees{0.0f, 25.0f, 45.0f, 60.0f, 72.0f, 80.0f};
// From below a 0.1 degree coat (alpha ~ 0.0017) up to a matte lobe.
constexpr std::array<float, 5> kAlphas{0.0015f, 0.008f, 0.04f, 0.15f, 0.5f};
constexpr int kPerStrategy = 48;
constexpr double kAlbedoWeight = 4.0;
constexpr double kMinAlbedo = 0.05;
constexpr int kSweeps = 24;
constexpr double kKeepRatio = 0.95;     // an extension must lower J below this fraction of it ...
constexpr double kKeepAbsolute = 1e-4;  // ... and by more than this fraction of the target's own J

glm::vec3 view_direction(float degrees) {
  float theta = degrees * std::numbers::pi_v<float> / 180.0f;
  return {std::sin(theta), 0.0f, std::cos(theta)};
}

struct Pair {
  glm::vec3 wi, wo;
  float weight;    // cos(theta_i) / (count * pdf): g = f * weight * count
  glm::vec3 term;  // target f * weight
};

// The fixed direction set with the target's values, and J for candidate parameters.
class Objective {
 public:
  explicit Objective(const FitTarget& target) {
    for (float degrees : kViewDegrees) {
      glm::vec3 wo = view_direction(degrees);
      View view;
      view.begin = pairs_.size();
      for (const WeightedDirection& d : hemisphere_quadrature(wo, kAlphas, kPerStrategy)) {
        ++view.count;
        if (d.weight <= 0.0f) continue;  // a zero term on both sides: nothing to compare
        pairs_.push_back({d.wi, wo, d.weight, target.eval(d.wi, wo) * d.weight});
      }
      view.end = pairs_.size();
      views_.push_back(view);
    }
    // Albedo residuals are relative per channel (as FitError measures them), rescaled by the mean
    // albedo so that they keep the units of the pair residuals; 0.05 keeps near-black channels sane.
    glm::dvec3 mean_albedo(0.0);
    for (View& view : views_) {
      for (size_t k = view.begin; k < view.end; ++k) view.albedo += glm::dvec3(pairs_[k].term);
      mean_albedo += view.albedo;
    }
    double reference = (mean_albedo.x + mean_albedo.y + mean_albedo.z) / (3.0 * double(views_.size()));
    for (View& view : views_) {
      glm::dvec3 scale = reference / glm::max(view.albedo, glm::dvec3(kMinAlbedo));
      view.albedo_weight = kAlbedoWeight * scale * scale;
    }
    target_j_ = evaluate_zero();
  }

  // J at `p` with p.base_color replaced by its clamped least-squares optimum.
  double solve(PbrParams& p) const {
    // Per channel, every residual is u + v x in the base colour x: accumulate sum u^2, u v, v^2.
    glm::dvec3 uu(0.0), uv(0.0), vv(0.0);
    for (const View& view : views_) {
      double m = double(view.count);
      glm::dvec3 su(0.0), sv(0.0);  // albedo residual: sum of the pair residuals' u and v
      for (size_t k = view.begin; k < view.end; ++k) {
        const Pair& pair = pairs_[k];
        PbrAffine f = pbr_eval_affine(p, pair.wi, pair.wo);
        // Monte-Carlo terms g = m * f * weight; pair residual (g_fit - g) / sqrt(m).
        glm::dvec3 u = glm::dvec3(f.a * pair.weight - pair.term), v = glm::dvec3(f.b * pair.weight);
        su += u;
        sv += v;
        uu += u * u * m;
        uv += u * v * m;
        vv += v * v * m;
      }
      uu += view.albedo_weight * su * su;
      uv += view.albedo_weight * su * sv;
      vv += view.albedo_weight * sv * sv;
    }
    double j = 0.0;
    for (int c = 0; c < 3; ++c) {
      // An iridescent fit keeps its base colour (the film's base; pbr_eval_affine's `a` holds the
      // film's reflectance at it).
      double x = p.iridescence > 0.0f ? double(p.base_color[c])
                 : vv[c] > 0.0        ? std::clamp(-uv[c] / vv[c], 0.0, 1.0)
                                      : 0.0;
      p.base_color[c] = float(x);
      j += uu[c] + 2.0 * x * uv[c] + x * x * vv[c];
    }
    return std::max(j, 0.0);
  }

  double target_j() const { return target_j_; }

 private:
  struct View {
    size_t begin = 0, end = 0;
    int count = 0;                  // directions drawn, including those below the horizon
    glm::dvec3 albedo{0.0};         // the target's, estimated on these directions
    glm::dvec3 albedo_weight{0.0};  // of the squared albedo residual, per channel
  };

  double evaluate_zero() const {
    double j = 0.0;
    for (const View& view : views_) {
      glm::dvec3 sum(0.0);
      for (size_t k = view.begin; k < view.end; ++k) {
        glm::dvec3 t(pairs_[k].term);
        j += glm::dot(t, t) * double(view.count);
        sum += t;
      }
      j += glm::dot(view.albedo_weight, sum * sum);
    }
    return j;
  }

  std::vector<Pair> pairs_;
  std::vector<View> views_;
  double target_j_ = 0.0;
};

// One searched parameter: where it lives in PbrParams, its bounds and its initial step.
struct Dim {
  float PbrParams::*scalar = nullptr;
  int color_channel = -1;  // >= 0: a channel of `colour`
  float lo, hi, step;
  glm::vec3 PbrParams::*colour = &PbrParams::specular_color;
  float& of(PbrParams& p) const { return color_channel >= 0 ? (p.*colour)[color_channel] : p.*scalar; }
};

const Dim kDimMetallic{&PbrParams::metallic, -1, 0.0f, 1.0f, 0.125f};
const Dim kDimRoughness{&PbrParams::roughness, -1, 0.03f, 1.0f, 0.05f};
const Dim kDimClearcoat{&PbrParams::clearcoat, -1, 0.0f, 1.0f, 0.125f};
const Dim kDimCoatRoughness{&PbrParams::clearcoat_roughness, -1, 0.03f, 1.0f, 0.02f};
const Dim kDimIor{&PbrParams::ior, -1, 1.05f, 3.0f, 0.1f};
const Dim kDimSpecular{&PbrParams::specular, -1, 0.0f, 1.0f, 0.125f};
const Dim kDimSpecularR{nullptr, 0, 0.0f, 10.0f, 0.25f};
const Dim kDimSpecularG{nullptr, 1, 0.0f, 10.0f, 0.25f};
const Dim kDimSpecularB{nullptr, 2, 0.0f, 10.0f, 0.25f};
// An iridescent fit's base colour (not solved in closed form: the film's reflectance depends on it).
const Dim kDimBaseR{nullptr, 0, 0.0f, 1.0f, 0.05f, &PbrParams::base_color};
const Dim kDimBaseG{nullptr, 1, 0.0f, 1.0f, 0.05f, &PbrParams::base_color};
const Dim kDimBaseB{nullptr, 2, 0.0f, 1.0f, 0.05f, &PbrParams::base_color};

struct Candidate {
  PbrParams params;
  double j = 0.0;
};

Candidate evaluate(const Objective& objective, PbrParams p) {
  double j = objective.solve(p);
  return {p, j};
}

// Coordinate descent: each sweep tries +step and -step on every parameter, keeping an improvement
// and halving a parameter's step when neither helps. Fixed sweep count: deterministic cost.
Candidate descend(const Objective& objective, Candidate best, const std::vector<Dim>& dims) {
  std::vector<float> steps;
  for (const Dim& d : dims) steps.push_back(d.step);
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    for (size_t i = 0; i < dims.size(); ++i) {
      bool improved = false;
      for (float sign : {1.0f, -1.0f}) {
        PbrParams p = best.params;
        float& value = dims[i].of(p);
        float moved = std::clamp(value + sign * steps[i], dims[i].lo, dims[i].hi);
        if (moved == value) continue;
        value = moved;
        Candidate c = evaluate(objective, p);
        if (c.j < best.j) {
          best = c;
          improved = true;
          break;
        }
      }
      if (!improved) steps[i] *= 0.5f;
    }
  }
  return best;
}

// The best grid point: every combination of the values given per parameter, starting from `start`.
Candidate grid(const Objective& objective, const PbrParams& start,
               const std::vector<std::pair<Dim, std::vector<float>>>& axes) {
  Candidate best = evaluate(objective, start);
  std::vector<size_t> index(axes.size(), 0);
  while (true) {
    PbrParams p = start;
    for (size_t a = 0; a < axes.size(); ++a) axes[a].first.of(p) = axes[a].second[index[a]];
    Candidate c = evaluate(objective, p);
    if (c.j < best.j) best = c;
    size_t a = 0;
    while (a < axes.size() && ++index[a] == axes[a].second.size()) index[a++] = 0;
    if (a == axes.size()) break;
  }
  return best;
}

bool worth_keeping(double with, double without, double target_j) {
  return with < kKeepRatio * without && without - with > kKeepAbsolute * target_j;
}

float relative_albedo_error(glm::vec3 fit, glm::vec3 target) {
  float worst = 0.0f;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(fit[c] - target[c]) / std::max(target[c], 0.01f));
  return worst;
}

// The result's parameters and its errors (FitError) for the best candidate.
void finish(const Objective& objective, const FitTarget& target, const Candidate& best, FitResult& result) {
  result.params = best.params;
  glm::vec3 normal = view_direction(0.0f), grazing = view_direction(80.0f);
  const glm::vec3 target_normal = target.albedo(normal);
  result.error.albedo_normal = relative_albedo_error(pbr_albedo(best.params, normal), target_normal);
  for (int c = 0; c < 3; ++c)
    if (target_normal[c] > 1.0f)
      result.error.unreachable_normal =
          std::max(result.error.unreachable_normal, (target_normal[c] - 1.0f) / target_normal[c]);
  result.error.albedo_grazing = relative_albedo_error(pbr_albedo(best.params, grazing), target.albedo(grazing));
  result.error.rms = objective.target_j() > 0.0 ? float(std::sqrt(best.j / objective.target_j())) : 0.0f;
  FitTarget fitted;
  fitted.eval = [&](glm::vec3 wi, glm::vec3 wo) { return pbr_eval(best.params, wi, wo); };
  fitted.albedo = [&](glm::vec3 wo) { return pbr_albedo(best.params, wo); };
  const glm::vec3 seen = lab_from_linear_srgb(sphere_colour(target));
  const glm::vec3 shown = lab_from_linear_srgb(sphere_colour(fitted));
  result.error.lightness = std::abs(shown.x - seen.x);
  result.error.colour = chromatic_difference(shown, seen);
}

}  // namespace

FitResult fit_pbr(const FitTarget& target) {
  Objective objective(target);
  const std::vector<float> roughness_grid{0.03f, 0.06f, 0.1f, 0.15f, 0.2f, 0.3f, 0.4f, 0.5f, 0.65f, 0.8f, 1.0f};

  // Plain metallic-roughness.
  PbrParams plain_start;
  plain_start.metallic = 0.0f;
  plain_start.roughness = 0.5f;
  Candidate plain = grid(objective, plain_start, {{kDimMetallic, {0.0f, 0.5f, 1.0f}}, {kDimRoughness, roughness_grid}});
  plain = descend(objective, plain, {kDimMetallic, kDimRoughness});

  FitResult result;
  Candidate best = plain;
  std::vector<Dim> dims{kDimMetallic, kDimRoughness};

  // KHR_materials_clearcoat: a second, usually sharper lobe over the base.
  {
    PbrParams start = best.params;
    start.clearcoat = 1.0f;
    // Within the bounds: a smoother coat is a mirror the direction set cannot see, which a viewer
    // would show as reflected environment the fit never paid for.
    start.clearcoat_roughness = 0.1f;
    Candidate coated = grid(objective, start,
                            {{kDimCoatRoughness, {0.03f, 0.06f, 0.1f, 0.15f, 0.25f, 0.4f}},
                             {kDimRoughness, {best.params.roughness, 0.3f, 0.6f, 1.0f}},
                             {kDimMetallic, {best.params.metallic, 0.0f, 1.0f}}});
    std::vector<Dim> coated_dims = dims;
    coated_dims.push_back(kDimClearcoat);
    coated_dims.push_back(kDimCoatRoughness);
    coated = descend(objective, coated, coated_dims);
    if (worth_keeping(coated.j, best.j, objective.target_j())) {
      best = coated;
      dims = coated_dims;
      result.uses_clearcoat = true;
    }
  }
  // KHR_materials_ior: the dielectric's F0.
  {
    Candidate with_ior = grid(objective, best.params, {{kDimIor, {1.2f, 1.33f, 1.5f, 1.7f, 2.0f, 2.5f}}});
    std::vector<Dim> ior_dims = dims;
    ior_dims.push_back(kDimIor);
    with_ior = descend(objective, with_ior, ior_dims);
    if (worth_keeping(with_ior.j, best.j, objective.target_j())) {
      best = with_ior;
      dims = ior_dims;
      result.uses_ior = true;
    }
  }
  // KHR_materials_specular: the dielectric's specular strength and F0 colour.
  {
    std::vector<Dim> specular_dims = dims;
    for (const Dim& d : {kDimSpecular, kDimSpecularR, kDimSpecularG, kDimSpecularB}) specular_dims.push_back(d);
    Candidate with_specular = descend(objective, best, specular_dims);
    if (worth_keeping(with_specular.j, best.j, objective.target_j())) {
      best = with_specular;
      result.uses_specular = true;
    }
  }

  finish(objective, target, best, result);
  return result;
}

FitResult fit_pbr_iridescent(const FitTarget& target, const PbrParams& film) {
  Objective objective(target);
  // The extension's film takes the base's reflection with a phase of 0 or pi; a metal's lies between,
  // which shifts the film's colours as a thicker or thinner film would. So the thickness is searched
  // over a quarter wave either way (a whole period of the phase), then with the roughness and the
  // base colour, whose reflectance sets the extension's second boundary.
  const float d = film.iridescence_thickness;
  const float quarter_wave = 550.0f / (4.0f * std::max(film.iridescence_ior, 1.0f));
  const Dim thickness{&PbrParams::iridescence_thickness, -1, std::max(0.0f, d - quarter_wave), d + quarter_wave,
                      quarter_wave / 8.0f};
  std::vector<float> thicknesses;
  for (int i = -6; i <= 6; ++i)
    thicknesses.push_back(std::clamp(d + float(i) * quarter_wave / 6.0f, thickness.lo, thickness.hi));
  Candidate best =
      grid(objective, film, {{kDimRoughness, {0.03f, 0.06f, 0.1f, 0.2f, 0.3f, 0.5f, 0.8f}}, {thickness, thicknesses}});
  best = descend(objective, best, {kDimRoughness, thickness, kDimBaseR, kDimBaseG, kDimBaseB});
  FitResult result;
  result.uses_iridescence = true;
  finish(objective, target, best, result);
  return result;
}

FitResult fit_pbr(const cpu::Evaluator& material, const ShadingContext& ctx) {
  // Bound once: a textured material resolves its stack here, not at each of the fit's evaluations.
  // Flat: glTF's lobes cannot tilt and the fallback bakes no normal maps, so a facet that a normal
  // input tilts is fitted as its own lobe about the mirror direction (Evaluator::bind_untilted).
  // Fitted tilted, its off-mirror highlight became a broad rough lobe of another colour (an
  // Aventurine glass facet tilted 4.6 degrees: |Delta L*| 8.6 and (a*, b*) 12.0 on the sphere).
  const cpu::ShadingPoint point = material.bind_untilted(ctx);
  FitTarget target;
  target.eval = [&](glm::vec3 wi, glm::vec3 wo) { return point.eval(wi, wo); };
  target.albedo = [&](glm::vec3 wo) { return point.albedo(wo); };
  const cpu::ShadingPoint::Stack stack = point.stack();
  const kernels::LaminaEntry& top = stack.entries[0];
  // A thin-film surface (substrate/thin_film); coated flakes under a binder are baked as any paint.
  if (top.kind == kernels::LAMINA_SUBSTRATE && top.model == kernels::LAMINA_SUBSTRATE_CONDUCTOR &&
      kernels::lamina_is_film(top.fresnel)) {
    const kernels::LaminaParams& film = stack.params[0];
    PbrParams start;
    start.metallic = 1.0f;
    start.roughness = 0.5f;
    start.base_color = kernels::conductor_f0(film.n, film.k);
    start.iridescence = 1.0f;
    // The extension has one index; the green channel's (at the top, the medium above is air).
    start.iridescence_ior = film.film_eta.y;
    start.iridescence_thickness = film.film_depth;
    return fit_pbr_iridescent(target, start);
  }
  return fit_pbr(target);
}

}  // namespace lamina::gltf
