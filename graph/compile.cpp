#include "graph/compile.h"

#include <filesystem>
#include <map>
#include <optional>

#include "graph/cpu/image.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "nodes/kernels/kernels.h"
#include "nodes/metals.h"

namespace lamina {

namespace {

class Compiler {
 public:
  Compiler(const Graph& graph, const std::string& file, const AssetPolicy& policy)
      : g_(graph), file_(file), policy_(policy) {}

  Program run() {
    program_.name = g_.material().name;
    program_.source_file = file_;
    program_.clamp_lower_roughness = g_.material().clamp_lower_roughness.value_or(true);
    for (size_t i : g_.topological_order()) {
      if (!g_.used(i)) continue;
      NodeKind kind = g_.decl(i).kind;
      if (kind == NodeKind::Texture || kind == NodeKind::Math) compile_texture(i);
    }
    program_.root = stack_node(g_.surface());
    program_.slot_count = slots_;
    return std::move(program_);
  }

 private:
  struct Output {
    ScalarRef scalar;
    ColorRef color;
  };

  int allocate(int count) {
    int first = slots_;
    slots_ += count;
    return first;
  }

  const Value& value(size_t i, const char* name) const {
    const Value* v = g_.value(i, name);
    if (!v) throw std::logic_error("compile: " + g_.node(i).id + " has no value for " + name);
    return *v;
  }

  const Output& linked_output(const Link& link) const {
    if (auto j = index_of(link.node)) return outputs_.at({*j, g_.decl(*j).find_output(link.output)->name});
    throw std::logic_error("compile: dangling link " + to_string(link));
  }

  std::optional<size_t> index_of(const std::string& id) const {
    if (ids_.empty())
      for (size_t j = 0; j < g_.size(); ++j) ids_.emplace(g_.node(j).id, j);
    auto it = ids_.find(id);
    return it == ids_.end() ? std::nullopt : std::optional<size_t>(it->second);
  }

  ScalarRef scalar(size_t i, const char* name) const {
    const Value& v = value(i, name);
    if (const auto* link = std::get_if<Link>(&v)) return linked_output(*link).scalar;
    return ScalarRef{float(std::get<double>(v)), -1};
  }

  ColorRef color(size_t i, const char* name) const {
    const Value& v = value(i, name);
    if (const auto* link = std::get_if<Link>(&v)) return linked_output(*link).color;
    const auto& c = std::get<Vec3d>(v);
    return ColorRef{glm::vec3(float(c[0]), float(c[1]), float(c[2])), -1};
  }

  glm::vec2 vec2(size_t i, const char* name) const {
    const auto& v = std::get<Vec2d>(value(i, name));
    return glm::vec2(float(v[0]), float(v[1]));
  }

  const std::string& text(size_t i, const char* name) const { return std::get<std::string>(value(i, name)); }

  RoughnessRef roughness(size_t i) const {
    if (g_.node(i).find("alpha")) return RoughnessRef{scalar(i, "alpha"), false};
    return RoughnessRef{scalar(i, "roughness_deg"), true};
  }

  // Enum values are checked against their declarations before compiling.
  static Distribution distribution(const std::string& name) {
    if (name == "blinn") return Distribution::Blinn;
    if (name == "ggx") return Distribution::Ggx;
    if (name == "beckmann") return Distribution::Beckmann;
    throw std::logic_error("compile: unknown distribution " + name);
  }

  static Fresnel fresnel(const std::string& name) {
    if (name == "schlick") return Fresnel::Schlick;
    if (name == "lazanyi") return Fresnel::Lazanyi;
    if (name == "exact") return Fresnel::Exact;
    throw std::logic_error("compile: unknown fresnel " + name);
  }

  void set_output(size_t i, const std::string& name, Output out) { outputs_[{i, name}] = out; }

  void compile_texture(size_t i) {
    const std::string& type = g_.decl(i).type;
    if (type == "texture/checker") {
      CheckerOp op{color(i, "color_a"), color(i, "color_b"), vec2(i, "scale"), allocate(3), allocate(1), g_.node(i).id};
      set_output(i, "color", Output{{}, ColorRef{{}, op.color_slot}});
      set_output(i, "value", Output{ScalarRef{0.0f, op.value_slot}, {}});
      program_.ops.push_back(op);
    } else if (type == "texture/image") {
      ImageOp op;
      op.node = g_.node(i).id;
      op.file = text(i, "file");
      try {
        const Reference ref = resolve_reference(file_, op.file, ReferenceScope::AssetRoots, policy_);
        op.image = load_image_reference(ref, text(i, "color_space") == "srgb", policy_);
      } catch (const std::runtime_error& e) {  // ReferenceError, ImageError: the file changed since the check
        throw IoError(file_ + ": texture file '" + op.file + "': " + e.what());
      }
      op.uv_scale = vec2(i, "uv_scale");
      op.uv_offset = vec2(i, "uv_offset");
      op.uv_rotation_deg = float(std::get<double>(value(i, "uv_rotation_deg")));
      const std::string& wrap = text(i, "wrap");
      op.wrap = wrap == "clamp" ? 1 : wrap == "mirror" ? 2 : 0;
      op.color_slot = allocate(3);
      op.value_slot = allocate(1);
      op.alpha_slot = allocate(1);
      set_output(i, "color", Output{{}, ColorRef{{}, op.color_slot}});
      set_output(i, "value", Output{ScalarRef{0.0f, op.value_slot}, {}});
      set_output(i, "alpha", Output{ScalarRef{0.0f, op.alpha_slot}, {}});
      program_.ops.push_back(op);
    } else if (type == "math/remap") {
      RemapOp op;
      op.node = g_.node(i).id;
      op.value = scalar(i, "value");
      op.in_min = float(std::get<double>(value(i, "in_min")));
      op.in_max = float(std::get<double>(value(i, "in_max")));
      op.out_min = float(std::get<double>(value(i, "out_min")));
      op.out_max = float(std::get<double>(value(i, "out_max")));
      op.clamp = std::get<bool>(value(i, "clamp"));
      if (op.value.slot < 0) {
        // Constant input: fold the remap away, with the kernel every evaluator runs.
        float out = kernels::remap_value(op.value.constant, op.in_min, op.in_max, op.out_min, op.out_max, op.clamp);
        set_output(i, "value", Output{ScalarRef{out, -1}, {}});
        return;
      }
      op.value_slot = allocate(1);
      set_output(i, "value", Output{ScalarRef{0.0f, op.value_slot}, {}});
      program_.ops.push_back(op);
    } else {
      throw std::logic_error("compile: no CPU texture operation for " + type);
    }
  }

  LayerInterface interface(size_t i) const {
    const std::string& type = g_.decl(i).type;
    if (type == "interface/dielectric")
      return DielectricInterface{scalar(i, "ior"), roughness(i), distribution(text(i, "distribution")),
                                 fresnel(text(i, "fresnel")), g_.node(i).id};
    throw std::logic_error("compile: no CPU interface for " + type);
  }

  LayerMedium medium(std::optional<size_t> i) const {
    if (!i) return ClearMedium{};
    if (g_.decl(*i).type == "medium/clear") return ClearMedium{g_.node(*i).id};
    if (g_.decl(*i).type == "medium/absorbing")
      return AbsorbingMedium{scalar(*i, "thickness"), color(*i, "absorption"), g_.node(*i).id};
    throw std::logic_error("compile: no CPU medium for " + g_.decl(*i).type);
  }

  int stack_node(size_t i) {
    if (auto it = stack_index_.find(i); it != stack_index_.end()) return it->second;
    const std::string& type = g_.decl(i).type;
    StackNode node;
    if (type == "layer") {
      LayerNode layer{interface(*g_.linked(i, "interface")), medium(g_.linked(i, "medium")), -1, g_.node(i).id};
      layer.base = stack_node(*g_.linked(i, "base"));
      node = layer;
    } else if (type == "mix") {
      MixNode mix{scalar(i, "weight"), -1, -1, g_.node(i).id};
      mix.a = stack_node(*g_.linked(i, "a"));
      mix.b = stack_node(*g_.linked(i, "b"));
      node = mix;
    } else if (type == "substrate/lambert") {
      node = LambertNode{color(i, "albedo"), g_.node(i).id};
    } else if (type == "substrate/oren_nayar") {
      node = OrenNayarNode{color(i, "albedo"), scalar(i, "sigma"), g_.node(i).id};
    } else if (type == "substrate/conductor") {
      ConductorNode c;
      c.node = g_.node(i).id;
      if (const Value* metal = g_.node(i).find("metal")) {
        c.metal = std::get<std::string>(*metal);
        const Metal* m = find_metal(c.metal);
        c.n = ColorRef{glm::vec3(float(m->n[0]), float(m->n[1]), float(m->n[2])), -1};
        c.k = ColorRef{glm::vec3(float(m->k[0]), float(m->k[1]), float(m->k[2])), -1};
      } else {
        c.n = color(i, "n");
        c.k = color(i, "k");
      }
      c.roughness = roughness(i);
      c.distribution = distribution(text(i, "distribution"));
      c.fresnel = fresnel(text(i, "fresnel"));
      node = c;
    } else {
      throw std::logic_error("compile: no CPU stack node for " + type);
    }
    program_.stack.push_back(node);
    int index = int(program_.stack.size()) - 1;
    stack_index_[i] = index;
    return index;
  }

  const Graph& g_;
  const std::string& file_;
  const AssetPolicy& policy_;
  Program program_;
  int slots_ = 0;
  std::map<std::pair<size_t, std::string>, Output> outputs_;
  std::map<size_t, int> stack_index_;
  mutable std::map<std::string, size_t> ids_;  // node id -> index, built on first use
};

}  // namespace

Program compile(const Graph& graph, const std::string& material_file, const AssetPolicy& policy) {
  return Compiler(graph, material_file, policy).run();
}

Program compile(const Graph& graph, const std::string& material_file) {
  return compile(graph, material_file, AssetPolicy{}.with_default_root(material_file));
}

Program compile(const Document& document, std::string_view material) {
  const Material* found = document.find_material(material);
  if (!found) {
    std::vector<std::string> names;
    for (const auto& m : document.materials) names.push_back(m.name);
    throw Error(
        {Diagnostic{Severity::Error, document.path, "/materials", "no material named '" + std::string(material) + "'",
                    "materials in this file: " + join_alternatives(names)}});
  }
  // That material alone is checked again (its textures decoded as the check decodes them), so
  // that compiling each material of a file of thousands costs time linear in the file.
  Document single;
  single.path = document.path;
  single.policy = document.policy;
  single.format = document.format;
  single.materials.push_back(*found);
  CheckedFile checked = check_text(write_document(single), document.path, document.policy);
  if (!checked.ok()) throw Error(checked.diagnostics.errors());
  return compile(*checked.graphs[0], document.path, checked.document.policy);
}

}  // namespace lamina
