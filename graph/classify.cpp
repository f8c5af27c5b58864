#include "graph/classify.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "graph/number_text.h"

namespace lamina {

std::string class_name(const std::string& letter) {
  static const char* names[] = {"glossy paint",   "tinted glazing", "frosted paint", "metal foil",
                                "metallic paint", "frosted metal",  "patina",        "multi-layer"};
  if (letter.size() != 1 || letter[0] < 'a' || letter[0] > 'h') return "unclassified";
  return names[letter[0] - 'a'];
}

namespace {

struct Roughness {
  double degrees = 0.0;
  bool textured = false;
  bool smooth() const { return !textured && degrees < kSmoothBelowDeg; }
  std::string text() const {
    if (textured) return "textured roughness, taken as rough";
    return number_text(degrees) + " deg " + (smooth() ? "< " : ">= ") + number_text(kSmoothBelowDeg);
  }
};

Roughness roughness_of(const Graph& g, size_t i) {
  const Node& n = g.node(i);
  Roughness r;
  if (const Value* v = n.find("roughness_deg")) {
    if (const double* d = std::get_if<double>(v))
      r.degrees = *d;
    else
      r.textured = true;
  } else if (const Value* a = n.find("alpha")) {
    if (const double* d = std::get_if<double>(a))
      r.degrees = std::atan(*d) * 180.0 / std::numbers::pi;
    else
      r.textured = true;
  }
  return r;
}

// A layer's medium tints when its node says so (NodeDecl::tint); no medium is clear.
bool tinted(const Graph& g, std::optional<size_t> medium, std::string& why) {
  if (!medium || !g.decl(*medium).tint) {
    why = "clear";
    return false;
  }
  Tint t = g.decl(*medium).tint(g, *medium);
  why = t.why;
  return t.tinted;
}

Classification result(const std::string& letter, std::string reason) {
  return {letter, class_name(letter), std::move(reason), {letter}};
}

// One way down through the stack: the layers met and the substrate reached. A mix forks the way.
struct Path {
  std::vector<size_t> layers;
  size_t substrate;
};

// Returns false when a structural input is missing (only possible in a graph built from a
// document with errors).
bool collect_paths(const Graph& g, size_t at, std::vector<size_t> layers, std::vector<Path>& paths) {
  while (g.decl(at).kind == NodeKind::Layer) {
    auto base = g.linked(at, "base");
    if (!base || !g.linked(at, "interface")) return false;
    layers.push_back(at);
    at = *base;
  }
  if (g.decl(at).kind == NodeKind::Mix || g.decl(at).kind == NodeKind::Select) {
    // Each run of a repeated stack once (Graph::stack_runs): a sparse glitter map's 15 transparent
    // places are one way down.
    if (g.stacks_below(at).size() < 2) return false;
    for (const Graph::StackRun& run : g.stack_runs(at))
      if (!collect_paths(g, run.node, layers, paths)) return false;
    return true;
  }
  paths.push_back({std::move(layers), at});
  return true;
}

Classification classify_path(const Graph& g, const Path& path) {
  const NodeDecl& base = g.decl(path.substrate);
  if (path.layers.empty()) return {"", "unlayered substrate", "a bare " + base.type + " has no layer", {}};
  if (path.layers.size() >= 2)
    return result("h", std::to_string(path.layers.size()) + " dielectric layers over " + base.type);

  size_t layer = path.layers.front();
  Roughness top_r = roughness_of(g, *g.linked(layer, "interface"));
  std::string top_text = (top_r.smooth() ? "smooth top (" : "rough top (") + top_r.text() + ")";
  if (base.metal) {
    Roughness base_r = roughness_of(g, path.substrate);
    std::string base_text =
        (base_r.smooth() ? "smooth " : "rough ") + base.metal_noun + " base (" + base_r.text() + ")";
    std::string reason = top_text + " over " + base_text;
    if (top_r.smooth()) return result(base_r.smooth() ? "d" : "e", reason);
    return result(base_r.smooth() ? "f" : "g", reason);
  }
  std::string reason = top_text + " over a diffuse base (" + base.type + ")";
  if (!top_r.smooth()) return result("c", reason);
  std::string why;
  bool tint = tinted(g, g.linked(layer, "medium"), why);
  return result(tint ? "b" : "a", reason + ", " + why + " varnish");
}

}  // namespace

Classification classify(const Graph& graph) {
  std::vector<Path> paths;
  if (!collect_paths(graph, graph.surface(), {}, paths))
    return {"", "incomplete stack", "a layer or mix lacks a structural input", {}};
  std::vector<Classification> parts;
  for (const auto& path : paths) parts.push_back(classify_path(graph, path));
  bool uniform = std::all_of(parts.begin(), parts.end(),
                             [&](const Classification& c) { return c.letter == parts.front().letter; });
  if (parts.size() == 1) return parts.front();
  if (uniform) {
    Classification c = parts.front();
    c.reason = "every stack of the mix: " + c.reason;
    return c;
  }
  // A mix of stacks of different classes agrees with any of them.
  Classification c;
  c.name = "mix of";
  for (size_t k = 0; k < parts.size(); ++k) {
    const auto& part = parts[k];
    std::string label = part.letter.empty() ? part.name : part.letter + ")";
    if (std::find(c.accepted.begin(), c.accepted.end(), part.letter) == c.accepted.end() && !part.letter.empty())
      c.accepted.push_back(part.letter);
    c.name += (k ? (k + 1 == parts.size() ? " and " : ", ") : " ") + label;
    c.reason += (k ? "; " : "") + std::string("stack ") + std::to_string(k + 1) + ": " + part.reason;
  }
  return c;
}

}  // namespace lamina
