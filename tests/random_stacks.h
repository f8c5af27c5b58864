// Random valid materials, for tests that must hold for every stack and not only the examples: a
// seeded generator of material files whose stacks nest layers (with clear, absorbing or no media)
// and mixes or selects over every substrate, with every distribution and Fresnel term, both models and
// roughness forms, and some parameters driven by textures (a checker, a noise, Voronoi cells or a
// marble, remapped into the parameter's range; colours from a checker, Voronoi cells or a math/mix
// of two by a noise). The checker must accept every file it writes; a refusal is a generator bug
// the caller reports. Which texture and whether a mix is a select come from a second stream of
// draws, so that adding kinds there leaves the stacks of the first stream as they were.
// Every random draw is a statement of its own: the operands of + are evaluated in an order each
// compiler chooses, so one expression with two draws would give GCC and clang different stacks.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

namespace lamina::test {

class RandomStacks {
 public:
  explicit RandomStacks(uint32_t seed) : rng_(seed), kinds_(seed ^ 0x9E3779B9u) {}

  // A material file with `count` materials named random_0, random_1, ...
  std::string file(int count) {
    std::ostringstream out;
    out << R"({"format": 1, "materials": [)";
    for (int m = 0; m < count; ++m) out << (m ? ",\n" : "\n") << material("random_" + std::to_string(m));
    out << "\n]}\n";
    return out.str();
  }

 private:
  std::string material(const std::string& name) {
    nodes_.str("");
    next_id_ = 0;
    layers_left_ = 3;
    mixes_left_ = 2;
    const std::string surface = stack(0);
    std::ostringstream m;
    m << R"({"name": ")" << name << R"(", "clamp_lower_roughness": )" << (chance(0.7) ? "true" : "false")
      << R"(, "model": ")" << (chance(0.5) ? "energy_conserving" : "weidlich_wilkie") << R"(", "surface": "@)"
      << surface << R"(", "nodes": [)" << nodes_.str() << "]}";
    return m.str();
  }

  // Writes a stack node (and what it needs) and returns its id.
  std::string stack(int depth) {
    if (layers_left_ > 0 && chance(0.55)) {
      --layers_left_;
      const std::string id = fresh("layer");
      const std::string iface = interface();
      const std::string medium = this->medium();
      const std::string base = stack(depth + 1);
      node(id, R"("type": "layer", "interface": "@)" + iface + "\"" +
                   (medium.empty() ? "" : R"(, "medium": "@)" + medium + "\"") + R"(, "base": "@)" + base + "\"");
      return id;
    }
    if (mixes_left_ > 0 && depth < 4 && chance(0.3)) {
      --mixes_left_;
      if (kind_chance(0.3)) return select(depth);
      const std::string id = fresh("mix");
      const std::string weight = scalar(0.0, 1.0);
      const std::string a = stack(depth + 1);
      const std::string b = stack(depth + 1);
      node(id, R"("type": "mix", "weight": )" + weight + R"(, "a": "@)" + a + R"(", "b": "@)" + b + "\"");
      return id;
    }
    return substrate();
  }

  // One of 2 to 4 stacks per Voronoi cell: the cell's value remapped to [0, N).
  std::string select(int depth) {
    const std::string id = fresh("select");
    const int count = 2 + kind_pick(3);
    const std::string cells = voronoi();
    const std::string index = fresh("index");
    node(index, R"("type": "math/remap", "value": "@)" + cells + R"(.value", "out_max": )" + std::to_string(count));
    std::string stacks;
    for (int k = 0; k < count; ++k) {
      const std::string below = stack(depth + 1);
      stacks += R"(, "stack_)" + std::to_string(k) + R"(": "@)" + below + "\"";
    }
    node(id, R"("type": "select", "index": "@)" + index + "\"" + stacks);
    return id;
  }

  std::string interface() {
    const std::string id = fresh("iface");
    const std::string ior = scalar(1.0, 2.4);
    const std::string slope = roughness();
    const std::string tilt = normal();
    node(id, R"("type": "interface/dielectric", "ior": )" + ior + ", " + slope + microfacet() + tilt);
    return id;
  }

  // "" for a layer without a medium input (clear).
  std::string medium() {
    const double u = uniform(0.0, 1.0);
    if (u < 0.3) return "";
    const std::string id = fresh("medium");
    if (u < 0.5) {
      node(id, R"("type": "medium/clear")");
    } else {
      const std::string thickness = scalar(0.0, 40.0);
      node(id, R"("type": "medium/absorbing", "thickness": )" + thickness + R"(, "absorption": )" + colour(0.0, 1.5));
    }
    return id;
  }

  std::string substrate() {
    const std::string id = fresh("base");
    const std::string tilt = normal();
    const double u = uniform(0.0, 1.0);
    if (u < 0.22) {
      node(id, R"("type": "substrate/lambert", "albedo": )" + albedo() + tilt);
    } else if (u < 0.3) {
      node(id, R"("type": "substrate/fluorescent", )" + fluorescence() + tilt);
    } else if (u < 0.36) {
      const std::string paint = flake_paint();
      const std::string slope = roughness();
      node(id, R"("type": "substrate/flake_paint", )" + paint + ", " + slope + distribution() + tilt);
    } else if (u < 0.55) {
      const std::string a = albedo();
      node(id, R"("type": "substrate/oren_nayar", "albedo": )" + a + R"(, "sigma": )" + scalar(0.0, 1.2) + tilt);
    } else if (u < 0.75) {
      static const char* metals[] = {"aluminium", "chromium", "copper", "gold", "silver"};
      const std::string metal = metals[pick(5)];
      const std::string slope = roughness();
      node(id, R"("type": "substrate/conductor", "metal": ")" + metal + "\", " + slope + microfacet() + tilt);
    } else if (u < 0.9) {
      const std::string n = colour(0.1, 3.0);
      const std::string k = colour(0.0, 8.0);
      const std::string slope = roughness();
      node(id, R"("type": "substrate/conductor", "n": )" + n + R"(, "k": )" + k + ", " + slope + microfacet() + tilt);
    } else {
      // A thin film over a metal or a dielectric (k from 0), of any thickness up to 2 um.
      static const char* integrations[] = {"spectral", "rgb"};
      const std::string n = colour(0.1, 3.0);
      const std::string k = colour(0.0, 8.0);
      const std::string thickness = scalar(0.0, 2000.0);
      const std::string film = colour(1.0, 3.0);
      const std::string slope = roughness();
      const std::string integration = integrations[pick(2)];
      node(id, R"("type": "substrate/thin_film", "n": )" + n + R"(, "k": )" + k + R"(, "thickness_nm": )" + thickness +
                   R"(, "film_ior": )" + film + R"(, "integration": ")" + integration + "\", " + slope +
                   distribution() + tilt);
    }
    return id;
  }

  // A fluorescent base's albedo and shifts: constants within the energy bound (each channel returns at
  // most what it receives, as the checker demands), or, one time in four, a Voronoi cell's colour as
  // albedo with shifts that may exceed it, which the kernels scale back.
  std::string fluorescence() {
    if (chance(0.25))
      return R"("albedo": "@)" + voronoi() + R"(.color", "green_to_red": )" + scalar(0.0, 1.0) +
             R"(, "blue_to_red": )" + scalar(0.0, 1.0) + R"(, "blue_to_green": )" + scalar(0.0, 1.0);
    const double r = uniform(0.0, 1.0), g = uniform(0.0, 1.0), b = uniform(0.0, 1.0);
    const double green_to_red = 0.999 * uniform(0.0, 1.0 - g);
    const double blue_out = 0.999 * uniform(0.0, 1.0 - b);
    const double to_red = uniform(0.0, 1.0);
    return R"("albedo": [)" + number(r) + ", " + number(g) + ", " + number(b) + R"(], "green_to_red": )" +
           number(green_to_red) + R"(, "blue_to_red": )" + number(blue_out * to_red) + R"(, "blue_to_green": )" +
           number(blue_out * (1.0 - to_red));
  }

  // A flake paint's base, coverage, flake colour and transmittance: a colour within a flake's bound
  // (it reflects at most what it does not pass, as the checker demands), or, one time in four, a
  // Voronoi cell's colour with a transmittance that may exceed the bound, which the kernels clamp;
  // or, one time in four, coated flakes (a film up to 600 nm of any index, either fold).
  std::string flake_paint() {
    const std::string a = albedo();
    const std::string base = R"("base_color": )" + a + R"(, "coverage": )" + scalar(0.0, 4.0);
    const double u = uniform(0.0, 1.0);
    if (u < 0.25)
      return base + R"(, "flake_color": "@)" + voronoi() + R"(.color", "flake_transmittance": )" + scalar(0.0, 1.0);
    if (u < 0.5) {
      static const char* integrations[] = {"spectral", "rgb"};
      const std::string thickness = scalar(0.0, 600.0);
      const std::string film = colour(1.0, 3.0);
      return base + R"(, "film_thickness_nm": )" + thickness + R"(, "film_ior": )" + film + R"(, "integration": ")" +
             integrations[pick(2)] + "\"";
    }
    const double t = uniform(0.0, 1.0);
    const std::string flake = colour(0.0, 0.999 * (1.0 - t));
    return base + R"(, "flake_color": )" + flake + R"(, "flake_transmittance": )" + number(t);
  }

  // One interface or substrate in four is tilted (from the second stream): by a constant normal up
  // to 40 degrees from +z, or by Voronoi cells' normals (glitter facets, flakes). "" otherwise.
  std::string normal() {
    if (!kind_chance(0.25)) return "";
    if (kind_chance(0.5)) {
      const double theta = kind_uniform(0.0, 40.0) * 3.14159265358979 / 180.0;
      const double phi = kind_uniform(0.0, 2.0 * 3.14159265358979);
      return R"(, "normal": [)" + number(std::sin(theta) * std::cos(phi)) + ", " +
             number(std::sin(theta) * std::sin(phi)) + ", " + number(std::cos(theta)) + "]";
    }
    const std::string id = fresh("facets");
    const std::string where = space();
    const std::string scale = number(kind_uniform(2.0, 20.0));
    const std::string tilt = number(kind_uniform(0.0, 30.0));
    const std::string seed = std::to_string(kind_pick(1000));
    node(id, R"("type": "texture/voronoi", )" + where + R"(, "scale": )" + scale + R"(, "tilt_deg": )" + tilt +
                 R"(, "seed": )" + seed);
    return R"(, "normal": "@)" + id + R"(.normal")";
  }

  // Roughness in either form, sometimes from a texture.
  std::string roughness() {
    if (chance(0.75)) return R"("roughness_deg": )" + scalar(0.5, 40.0);
    return R"("alpha": )" + scalar(0.01, 0.8);
  }

  std::string microfacet() {
    static const char* fresnels[] = {"exact", "schlick", "lazanyi"};
    const std::string with_distribution = distribution();
    const std::string fresnel = fresnels[pick(3)];
    return with_distribution + R"(, "fresnel": ")" + fresnel + "\"";
  }
  std::string distribution() {
    static const char* distributions[] = {"beckmann", "blinn", "ggx"};
    return std::string(R"(, "distribution": ")") + distributions[pick(3)] + "\"";
  }

  // A float in [lo, hi]: a constant, or one time in five a checker's value remapped into a random
  // sub-range (the remap's clamp keeps it there).
  std::string scalar(double lo, double hi) {
    const double a = uniform(lo, hi);
    if (!chance(0.2)) return number(a);
    const double b = uniform(lo, hi);
    const std::string id = fresh("remap");
    const std::string source = grey();
    node(id, R"("type": "math/remap", "value": ")" + source + R"(", "out_min": )" + number(a) + R"(, "out_max": )" +
                 number(b));
    return "\"@" + id + ".value\"";
  }

  // A grey map in [0, 1], as a link: a checker's value, a noise, Voronoi cells' value or a marble.
  std::string grey() {
    const int which = kind_pick(4);
    if (which == 1) return "@" + noise();
    if (which == 2) return "@" + voronoi() + ".value";
    if (which == 3) return "@" + marble();
    return "@" + checker() + ".value";
  }

  // A diffuse albedo: a constant, or one time in four a checker's colour, Voronoi cells' colour or
  // a math/mix of two colours by a noise.
  std::string albedo() {
    if (!chance(0.25)) return colour(0.0, 1.0);
    const int which = kind_pick(3);
    if (which == 1) return "\"@" + voronoi() + ".color\"";
    if (which == 2) {
      const std::string id = fresh("tint");
      const std::string a = colour(0.0, 1.0);
      const std::string b = colour(0.0, 1.0);
      const std::string by = noise();
      node(id, R"("type": "math/mix", "a": )" + a + R"(, "b": )" + b + R"(, "factor": "@)" + by + "\"");
      return "\"@" + id + "\"";
    }
    return "\"@" + checker() + ".color\"";
  }

  // Procedural textures over uv or position, with parameters from the second stream.
  std::string space() { return kind_chance(0.5) ? R"("space": "uv")" : R"("space": "position")"; }
  std::string noise() {
    const std::string id = fresh("noise");
    const std::string where = space();
    const std::string scale = number(kind_uniform(1.0, 12.0));
    const std::string mode = kind_chance(0.5) ? "fbm" : "turbulence";
    const std::string octaves = std::to_string(1 + kind_pick(5));
    const std::string seed = std::to_string(kind_pick(1000));
    node(id, R"("type": "texture/noise", )" + where + R"(, "scale": )" + scale + R"(, "mode": ")" + mode +
                 R"(", "octaves": )" + octaves + R"(, "seed": )" + seed);
    return id;
  }
  std::string voronoi() {
    const std::string id = fresh("cells");
    const std::string where = space();
    const std::string scale = number(kind_uniform(2.0, 20.0));
    const std::string jitter = number(kind_uniform(0.0, 1.0));
    const std::string seed = std::to_string(kind_pick(1000));
    node(id, R"("type": "texture/voronoi", )" + where + R"(, "scale": )" + scale + R"(, "jitter": )" + jitter +
                 R"(, "seed": )" + seed);
    return id;
  }
  std::string marble() {
    const std::string id = fresh("marble");
    const std::string where = space();
    const std::string stripes = number(kind_uniform(0.5, 6.0));
    const std::string strength = number(kind_uniform(0.0, 3.0));
    const std::string octaves = std::to_string(1 + kind_pick(4));
    node(id, R"("type": "texture/marble", )" + where + R"(, "stripes": )" + stripes + R"(, "strength": )" + strength +
                 R"(, "octaves": )" + octaves);
    return id;
  }

  std::string checker() {
    const std::string id = fresh("checker");
    const std::string a = colour(0.0, 1.0);
    const std::string b = colour(0.0, 1.0);
    const double su = uniform(1.0, 9.0);
    const double sv = uniform(1.0, 9.0);
    node(id, R"("type": "texture/checker", "color_a": )" + a + R"(, "color_b": )" + b + R"(, "scale": [)" + number(su) +
                 ", " + number(sv) + "]");
    return id;
  }

  std::string colour(double lo, double hi) {
    const double r = uniform(lo, hi);
    const double g = uniform(lo, hi);
    const double b = uniform(lo, hi);
    return "[" + number(r) + ", " + number(g) + ", " + number(b) + "]";
  }

  void node(const std::string& id, const std::string& body) {
    nodes_ << (nodes_.tellp() > 0 ? ",\n    " : "\n    ") << R"({"id": ")" << id << "\", " << body << "}";
  }

  std::string fresh(const char* kind) { return std::string(kind) + "_" + std::to_string(next_id_++); }
  static std::string number(double x) {
    std::ostringstream s;
    s.precision(9);
    s << x;
    return s.str();
  }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  // The second stream: kinds of texture, selects and the new textures' parameters.
  double kind_uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(kinds_); }
  bool kind_chance(double p) { return kind_uniform(0.0, 1.0) < p; }
  int kind_pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(kinds_); }

  std::mt19937 rng_;
  std::mt19937 kinds_;
  std::ostringstream nodes_;
  int next_id_ = 0;
  int layers_left_ = 0;
  int mixes_left_ = 0;
};

}  // namespace lamina::test
