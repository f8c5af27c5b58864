// Random valid materials, for tests that must hold for every stack and not only the examples: a
// seeded generator of material files whose stacks nest layers (with clear, absorbing or no media)
// and mixes over every substrate, with every distribution and Fresnel term, both models and roughness forms,
// and some parameters driven by textures (a checker, remapped into the parameter's range). The
// checker must accept every file it writes; a refusal is a generator bug the caller reports.
// Every random draw is a statement of its own: the operands of + are evaluated in an order each
// compiler chooses, so one expression with two draws would give GCC and clang different stacks.
#pragma once

#include <cstdint>
#include <random>
#include <sstream>
#include <string>

namespace lamina::test {

class RandomStacks {
 public:
  explicit RandomStacks(uint32_t seed) : rng_(seed) {}

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
      const std::string id = fresh("mix");
      const std::string weight = scalar(0.0, 1.0);
      const std::string a = stack(depth + 1);
      const std::string b = stack(depth + 1);
      node(id, R"("type": "mix", "weight": )" + weight + R"(, "a": "@)" + a + R"(", "b": "@)" + b + "\"");
      return id;
    }
    return substrate();
  }

  std::string interface() {
    const std::string id = fresh("iface");
    const std::string ior = scalar(1.0, 2.4);
    const std::string slope = roughness();
    node(id, R"("type": "interface/dielectric", "ior": )" + ior + ", " + slope + microfacet());
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
    const double u = uniform(0.0, 1.0);
    if (u < 0.3) {
      node(id, R"("type": "substrate/lambert", "albedo": )" + albedo());
    } else if (u < 0.55) {
      const std::string a = albedo();
      node(id, R"("type": "substrate/oren_nayar", "albedo": )" + a + R"(, "sigma": )" + scalar(0.0, 1.2));
    } else if (u < 0.75) {
      static const char* metals[] = {"aluminium", "chromium", "copper", "gold", "silver"};
      const std::string metal = metals[pick(5)];
      const std::string slope = roughness();
      node(id, R"("type": "substrate/conductor", "metal": ")" + metal + "\", " + slope + microfacet());
    } else {
      const std::string n = colour(0.1, 3.0);
      const std::string k = colour(0.0, 8.0);
      const std::string slope = roughness();
      node(id, R"("type": "substrate/conductor", "n": )" + n + R"(, "k": )" + k + ", " + slope + microfacet());
    }
    return id;
  }

  // Roughness in either form, sometimes from a texture.
  std::string roughness() {
    if (chance(0.75)) return R"("roughness_deg": )" + scalar(0.5, 40.0);
    return R"("alpha": )" + scalar(0.01, 0.8);
  }

  std::string microfacet() {
    static const char* distributions[] = {"beckmann", "blinn", "ggx"};
    static const char* fresnels[] = {"exact", "schlick", "lazanyi"};
    const std::string distribution = distributions[pick(3)];
    const std::string fresnel = fresnels[pick(3)];
    return R"(, "distribution": ")" + distribution + R"(", "fresnel": ")" + fresnel + "\"";
  }

  // A float in [lo, hi]: a constant, or one time in five a checker's value remapped into a random
  // sub-range (the remap's clamp keeps it there).
  std::string scalar(double lo, double hi) {
    const double a = uniform(lo, hi);
    if (!chance(0.2)) return number(a);
    const double b = uniform(lo, hi);
    const std::string id = fresh("remap");
    node(id, R"("type": "math/remap", "value": "@)" + checker() + R"(.value", "out_min": )" + number(a) +
                 R"(, "out_max": )" + number(b));
    return "\"@" + id + ".value\"";
  }

  // A diffuse albedo: a constant, or one time in four a checker's colour.
  std::string albedo() {
    if (chance(0.25)) return "\"@" + checker() + ".color\"";
    return colour(0.0, 1.0);
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

  std::mt19937 rng_;
  std::ostringstream nodes_;
  int next_id_ = 0;
  int layers_left_ = 0;
  int mixes_left_ = 0;
};

}  // namespace lamina::test
