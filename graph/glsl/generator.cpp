#include "graph/glsl/generator.h"

#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "graph/cpu/image.h"
#include "graph/glsl/glsl_text.h"
#include "graph/glsl/kernel_items.h"
#include "graph/glsl/sphere_shader.h"
#include "graph/lobes.h"
#include "nodes/kernels/kernels.h"
#include "nodes/metals.h"

namespace lamina::glsl {

namespace k = lamina::kernels;

namespace {

struct TargetInfo {
  Target target;
  const char* name;     // as on the command line
  const char* version;  // the module's first line
};
const TargetInfo kTargetInfo[] = {{Target::Glsl330, "330", "#version 330 core"},
                                  {Target::Glsl450, "450", "#version 450 core"},
                                  {Target::Es300, "es300", "#version 300 es"}};

const TargetInfo& info(Target target) {
  for (const TargetInfo& t : kTargetInfo)
    if (t.target == target) return t;
  return kTargetInfo[0];
}

const char* version_line(Target target) { return info(target).version; }

// The material file's name without its directories, so that the output does not depend on how
// the file was named on the command line.
std::string source_name(const Program& p) { return std::filesystem::path(p.source_file).filename().string(); }

}  // namespace

const char* target_name(Target target) { return info(target).name; }

bool parse_target(const std::string& text, Target& target) {
  for (const TargetInfo& t : kTargetInfo)
    if (text == t.name) {
      target = t.target;
      return true;
    }
  return false;
}

namespace {

const char* distribution_name(Distribution d) {
  switch (d) {
    case Distribution::Beckmann: return "beckmann";
    case Distribution::Blinn: return "blinn";
    case Distribution::Ggx: return "ggx";
  }
  return "beckmann";
}

// std140: float aligns to 4, vec2 to 8, vec3 to 16 (and takes 12 bytes).
size_t std140_align(const std::string& type) { return type == "float" ? 4 : type == "vec2" ? 8 : 16; }
size_t std140_size(const std::string& type) { return type == "float" ? 4 : type == "vec2" ? 8 : 12; }

// Emits the GLSL of one material. Functions are named <prefix>_...; every value a node reads is
// a literal, a uniform block member or a texture register, chosen once in `input`.
class MaterialEmitter {
 public:
  MaterialEmitter(const Program& program, const Options& options, MaterialInterface& out)
      : p_(program), o_(options), mi_(out), lobes_(collect_lobes(program)) {
    mi_.material = p_.name;
    mi_.prefix = "lamina_" + name_part(p_.name);
    if (o_.uniforms) {
      mi_.block = mi_.prefix + "_block";
      mi_.instance = mi_.prefix + "_u";
    }
    for (size_t i = 0; i < p_.stack.size(); ++i) stack_names_.push_back(locals_.unique(name_part(node_id(int(i)))));
  }

  std::string emit() {
    std::string resolve = emit_resolve();  // first: it collects the uniforms and samplers
    std::ostringstream s;
    s << "// ================================================================================\n";
    s << "// material \"" << p_.name << "\" from " << source_name(p_) << "\n";
    s << "// ================================================================================\n\n";
    if (o_.uniforms) emit_block(s);
    for (const SamplerBinding& b : mi_.samplers)
      s << "// node \"" << b.node << "\" (texture/image): " << b.file << ", " << b.width << " x " << b.height
        << " texels\nuniform sampler2D " << b.name << ";\n\n";
    s << resolve;
    std::set<int> done;
    emit_node(s, p_.root, done);
    emit_eval(s);
    emit_lobes(s);
    emit_pdf(s);
    emit_sample(s);
    return s.str();
  }

 private:
  // --- names and values ---------------------------------------------------------------------------

  std::string node_id(int index) const {
    return std::visit([](const auto& n) { return n.node; }, p_.stack[size_t(index)]);
  }
  std::string fn(const std::string& what) const { return mi_.prefix + "_" + what; }
  std::string node_fn(int index) const { return fn("node_" + stack_names_[size_t(index)]); }
  std::string params_type() const { return fn("params"); }

  // A member of the uniform block holding `value`, named after the node and parameter that gave it;
  // a node shared by several layers keeps one member.
  std::string uniform(const std::string& node, const std::string& parameter, const std::string& type,
                      std::vector<float> value) {
    std::string name = name_part(node) + "_" + parameter;
    for (const UniformField& f : mi_.uniforms)
      if (f.node == node && f.parameter == parameter) return mi_.instance + "." + f.name;
    name = block_names_.unique(name);
    size_t align = std140_align(type);
    block_end_ = (block_end_ + align - 1) / align * align;
    mi_.uniforms.push_back({name, type, block_end_, std::move(value), node, parameter});
    block_end_ += std140_size(type);
    mi_.block_size = (block_end_ + 15) / 16 * 16;
    return mi_.instance + "." + name;
  }

  std::string input(const ScalarRef& r, const std::string& node, const std::string& parameter) {
    if (r.slot >= 0) return scalar_regs_.at(r.slot);
    if (o_.uniforms) return uniform(node, parameter, "float", {r.constant});
    return float_literal(r.constant);
  }
  std::string input(const ColorRef& r, const std::string& node, const std::string& parameter) {
    if (r.slot >= 0) return color_regs_.at(r.slot);
    if (o_.uniforms) return uniform(node, parameter, "vec3", {r.constant.x, r.constant.y, r.constant.z});
    return vec3_literal(r.constant);
  }
  std::string plain(float v, const std::string& node, const std::string& parameter) {
    return o_.uniforms ? uniform(node, parameter, "float", {v}) : float_literal(v);
  }
  std::string plain(glm::vec2 v, const std::string& node, const std::string& parameter) {
    return o_.uniforms ? uniform(node, parameter, "vec2", {v.x, v.y}) : vec2_literal(v);
  }

  // A stack parameter after the evaluator's clamping: folded to a literal when it is constant
  // and inlined (the C++ kernels compute it, so the value is the CPU's to the bit), otherwise the
  // GLSL expression `glsl` with $ standing for the input.
  template <typename Ref, typename Fold>
  std::string resolved(const Ref& r, const std::string& node, const std::string& parameter, Fold fold,
                       const std::string& glsl) {
    if (r.slot < 0 && !o_.uniforms) {
      auto v = fold(r.constant);
      if constexpr (std::is_same_v<decltype(v), float>)
        return float_literal(v);
      else
        return vec3_literal(v);
    }
    return replace_all(glsl, "$", input(r, node, parameter));
  }

  void field(const std::string& stack_name, const std::string& what, const char* type, const std::string& value,
             const std::string& comment) {
    fields_ << "  " << type << " " << stack_name << "_" << what << ";  // " << comment << "\n";
    assigns_ << "  p." << stack_name << "_" << what << " = " << value << ";\n";
  }

  static std::string roughness_name(const RoughnessRef& r) { return r.degrees ? "roughness_deg" : "alpha"; }
  static float slope(const RoughnessRef& r, float value) { return k::lamina_slope(value, r.degrees); }
  static std::string slope_glsl(const RoughnessRef& r) {
    return std::string("lamina_slope($, ") + (r.degrees ? "true" : "false") + ")";
  }

  // --- resolve: texture operations, then the stack's parameters ----------------------------------

  std::string emit_resolve() {
    std::ostringstream ops;
    for (const TextureOp& op : p_.ops) std::visit([&](const auto& o) { emit_op(ops, o); }, op);
    for (size_t i = 0; i < p_.stack.size(); ++i)
      std::visit([&](const auto& n) { stack_fields(int(i), n); }, p_.stack[i]);

    std::ostringstream s;
    s << "// The parameters of every stack node at one shading point, clamped to their declared ranges.\n";
    s << "struct " << params_type() << " {\n" << fields_.str() << "};\n\n";
    s << params_type() << " " << fn("resolve") << "(vec2 uv) {\n";
    s << ops.str();
    s << "  " << params_type() << " p;\n" << assigns_.str() << "  return p;\n}\n\n";
    return s.str();
  }

  std::string register_name(const std::string& node, const char* output) {
    return locals_.unique("t_" + name_part(node) + "_" + output);
  }

  void emit_op(std::ostringstream& s, const CheckerOp& op) {
    std::string value = register_name(op.node, "value"), color = register_name(op.node, "color");
    s << "  // node \"" << op.node << "\" (texture/checker)\n";
    s << "  float " << value << " = checker_value(uv, " << plain(op.scale, op.node, "scale") << ");\n";
    s << "  vec3 " << color << " = mix(" << input(op.color_a, op.node, "color_a") << ", "
      << input(op.color_b, op.node, "color_b") << ", " << value << ");\n";
    scalar_regs_[op.value_slot] = value;
    color_regs_[op.color_slot] = color;
  }

  void emit_op(std::ostringstream& s, const ImageOp& op) {
    SamplerBinding b;
    b.name = samplers_.unique(fn("image_" + name_part(op.node)));
    b.node = op.node;
    b.file = op.file;
    b.width = op.image ? op.image->width : 0;
    b.height = op.image ? op.image->height : 0;
    mi_.samplers.push_back(b);
    std::string texel = register_name(op.node, "texel"), color = register_name(op.node, "color"),
                value = register_name(op.node, "value"), alpha = register_name(op.node, "alpha");
    static const char* kWrap[] = {"repeat", "clamp", "mirror"};
    s << "  // node \"" << op.node << "\" (texture/image), wrap " << kWrap[op.wrap % 3] << "\n";
    s << call("  vec2 " + texel + "_uv = lamina_image_uv",
              {"uv", plain(op.uv_rotation_deg, op.node, "uv_rotation_deg"), plain(op.uv_scale, op.node, "uv_scale"),
               plain(op.uv_offset, op.node, "uv_offset")},
              ";");
    s << "  vec4 " << texel << " = lamina_image_bilinear(" << b.name << ", " << texel << "_uv, " << op.wrap << ");\n";
    s << "  vec3 " << color << " = " << texel << ".xyz;\n";
    s << "  float " << value << " = lamina_luminance(" << texel << ".xyz);\n";
    s << "  float " << alpha << " = " << texel << ".w;\n";
    color_regs_[op.color_slot] = color;
    scalar_regs_[op.value_slot] = value;
    scalar_regs_[op.alpha_slot] = alpha;
  }

  void emit_op(std::ostringstream& s, const RemapOp& op) {
    std::string value = register_name(op.node, "value");
    s << "  // node \"" << op.node << "\" (math/remap)\n";
    s << call(
        "  float " + value + " = remap_value",
        {input(op.value, op.node, "value"), plain(op.in_min, op.node, "in_min"), plain(op.in_max, op.node, "in_max"),
         plain(op.out_min, op.node, "out_min"), plain(op.out_max, op.node, "out_max"), op.clamp ? "true" : "false"},
        ";");
    scalar_regs_[op.value_slot] = value;
  }

  void stack_fields(int index, const LayerNode& n) {
    const std::string& sn = stack_names_[size_t(index)];
    const auto& d = std::get<DielectricInterface>(n.interface);
    field(sn, "ior", "float",
          resolved(
              d.ior, d.node, "ior", [](float x) { return glm::clamp(x, 1.0f, 4.0f); }, "clamp($, 1.0f, 4.0f)"),
          "interface \"" + d.node + "\": absolute index below it");
    field(sn, "m", "float",
          resolved(
              d.roughness.value, d.node, roughness_name(d.roughness), [&](float x) { return slope(d.roughness, x); },
              slope_glsl(d.roughness)),
          "interface \"" + d.node + "\": Beckmann RMS slope");
    if (const auto* a = std::get_if<AbsorbingMedium>(&n.medium)) {
      field(sn, "absorption", "vec3",
            resolved(
                a->absorption, a->node, "absorption", [](glm::vec3 c) { return glm::max(c, glm::vec3(0.0f)); },
                "max($, vec3(0.0f))"),
            "medium \"" + a->node + "\": per micrometre");
      field(sn, "thickness", "float",
            resolved(
                a->thickness, a->node, "thickness", [](float x) { return glm::max(x, 0.0f); }, "max($, 0.0f)"),
            "medium \"" + a->node + "\": micrometres");
    }
  }
  void stack_fields(int index, const MixNode& n) {
    field(stack_names_[size_t(index)], "weight", "float",
          resolved(
              n.weight, n.node, "weight", [](float x) { return glm::clamp(x, 0.0f, 1.0f); }, "clamp($, 0.0f, 1.0f)"),
          "mix \"" + n.node + "\": share of b");
  }
  void stack_fields(int index, const LambertNode& n) {
    field(stack_names_[size_t(index)], "albedo", "vec3", clamped_albedo(n.albedo, n.node),
          "lambert \"" + n.node + "\"");
  }
  void stack_fields(int index, const OrenNayarNode& n) {
    const std::string& sn = stack_names_[size_t(index)];
    field(sn, "albedo", "vec3", clamped_albedo(n.albedo, n.node), "oren_nayar \"" + n.node + "\"");
    field(sn, "sigma", "float",
          resolved(
              n.sigma, n.node, "sigma", [](float x) { return glm::clamp(x, 0.0f, k::LAMINA_PI / 2.0f); },
              "clamp($, 0.0f, LAMINA_PI / 2.0f)"),
          "oren_nayar \"" + n.node + "\": radians");
  }
  void stack_fields(int index, const ConductorNode& n) {
    const std::string& sn = stack_names_[size_t(index)];
    std::string what = "conductor \"" + n.node + "\"" + (n.metal.empty() ? "" : " (" + n.metal + ")");
    field(sn, "n", "vec3",
          resolved(
              n.n, n.node, "n",
              [](glm::vec3 c) { return glm::clamp(c, glm::vec3(1.0e-3f), glm::vec3(float(kMaxConductorIndex))); },
              "clamp($, vec3(1.0e-3f), vec3(" + float_literal(float(kMaxConductorIndex)) + "))"),
          what + ": absolute index");
    field(sn, "k", "vec3",
          resolved(
              n.k, n.node, "k",
              [](glm::vec3 c) { return glm::clamp(c, glm::vec3(0.0f), glm::vec3(float(kMaxConductorIndex))); },
              "clamp($, vec3(0.0f), vec3(" + float_literal(float(kMaxConductorIndex)) + "))"),
          what + ": extinction");
    field(sn, "m", "float",
          resolved(
              n.roughness.value, n.node, roughness_name(n.roughness), [&](float x) { return slope(n.roughness, x); },
              slope_glsl(n.roughness)),
          what + ": Beckmann RMS slope");
  }
  std::string clamped_albedo(const ColorRef& albedo, const std::string& node) {
    return resolved(
        albedo, node, "albedo", [](glm::vec3 c) { return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f)); },
        "clamp($, vec3(0.0f), vec3(1.0f))");
  }

  void emit_block(std::ostringstream& s) {
    s << "// Constant parameters of \"" << p_.name << "\" for live editing: std140, " << mi_.block_size
      << " bytes;\n// offsets also in the module header and the JSON side file.\n";
    s << "layout(std140) uniform " << mi_.block << " {\n";
    for (const UniformField& f : mi_.uniforms)
      s << "  " << f.type << " " << f.name << ";  // offset " << f.offset << ": node \"" << f.node << "\" "
        << f.parameter << "\n";
    s << "} " << mi_.instance << ";\n\n";
  }

  // --- eval: one function per stack node, bottom up ----------------------------------------------

  std::string clamp_flag() const { return p_.clamp_lower_roughness ? "true" : "false"; }

  void emit_node(std::ostringstream& s, int index, std::set<int>& done) {
    if (!done.insert(index).second) return;
    const StackNode& node = p_.stack[size_t(index)];
    if (const auto* layer = std::get_if<LayerNode>(&node)) emit_node(s, layer->base, done);
    if (const auto* mix = std::get_if<MixNode>(&node)) {
      emit_node(s, mix->a, done);
      emit_node(s, mix->b, done);
    }
    const std::string& sn = stack_names_[size_t(index)];
    std::string signature = call("vec3 " + node_fn(index),
                                 {params_type() + " p", "vec3 l", "vec3 v", "float n_above", "float m_above"}, " {");
    if (const auto* layer = std::get_if<LayerNode>(&node)) {
      const auto& d = std::get<DielectricInterface>(layer->interface);
      const auto* a = std::get_if<AbsorbingMedium>(&layer->medium);
      std::string medium_node = a ? a->node : std::get<ClearMedium>(layer->medium).node;
      s << "// node \"" << layer->node << "\" (layer): interface \"" << d.node << "\" (interface/dielectric, "
        << distribution_name(d.distribution) << ")";
      if (a)
        s << ", medium \"" << a->node << "\" (medium/absorbing)";
      else if (!medium_node.empty())
        s << ", medium \"" << medium_node << "\" (medium/clear)";
      s << ", base \"" << node_id(layer->base) << "\".\n";
      s << "// f = f_interface + f_below(L', V') T a t (course sec. 3.1, Elek eq. 2).\n" << signature;
      s << "  float m = lamina_effective_slope(p." << sn << "_m, m_above, " << clamp_flag() << ");\n";
      s << "  vec3 l_below;\n  vec3 v_below;\n  vec3 carry;\n";
      s << call("  vec3 f = lamina_interface_eval",
                {"l", "v", "p." + sn + "_ior / n_above", std::to_string(int(d.distribution)),
                 std::to_string(int(d.fresnel)), "m", a ? "p." + sn + "_absorption" : "vec3(0.0f)",
                 a ? "p." + sn + "_thickness" : "0.0f", "l_below", "v_below", "carry"},
                ";");
      s << "  if (l_below.z <= 0.0f || v_below.z <= 0.0f) {\n    return f;\n  }\n";
      s << "  return f + " << node_fn(layer->base) << "(p, l_below, v_below, p." << sn << "_ior, m) * carry;\n}\n\n";
    } else if (const auto* mix = std::get_if<MixNode>(&node)) {
      s << "// node \"" << mix->node << "\" (mix): \"" << node_id(mix->a) << "\" and \"" << node_id(mix->b) << "\".\n"
        << signature;
      s << call("  return mix",
                {node_fn(mix->a) + "(p, l, v, n_above, m_above)", node_fn(mix->b) + "(p, l, v, n_above, m_above)",
                 "p." + sn + "_weight"},
                ";")
        << "}\n\n";
    } else if (const auto* lambert = std::get_if<LambertNode>(&node)) {
      s << "// node \"" << lambert->node << "\" (substrate/lambert).\n" << signature;
      s << "  return lamina_lambert_eval(l, v, p." << sn << "_albedo);\n}\n\n";
    } else if (const auto* on = std::get_if<OrenNayarNode>(&node)) {
      s << "// node \"" << on->node << "\" (substrate/oren_nayar).\n" << signature;
      s << "  return oren_nayar(l, v, p." << sn << "_albedo, p." << sn << "_sigma);\n}\n\n";
    } else if (const auto* c = std::get_if<ConductorNode>(&node)) {
      s << "// node \"" << c->node << "\" (substrate/conductor, " << distribution_name(c->distribution)
        << "): the metal's index relative to the medium above it.\n"
        << signature;
      s << "  float m = lamina_effective_slope(p." << sn << "_m, m_above, " << clamp_flag() << ");\n";
      s << "  return lamina_conductor_eval(l, v, p." << sn << "_n / n_above, p." << sn << "_k / n_above, "
        << int(c->distribution) << ", " << int(c->fresnel) << ", m);\n}\n\n";
    }
  }

  void emit_eval(std::ostringstream& s) {
    s << "vec3 " << fn("eval_p") << "(" << params_type() << " p, vec3 wi, vec3 wo) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  return max(" << node_fn(p_.root) << "(p, wi, wo, 1.0f, 0.0f), vec3(0.0f));\n}\n\n";
    s << "// The BRDF f(wi, wo) of \"" << p_.name << "\", without the cosine; 0 below the horizon.\n";
    s << "vec3 " << fn("eval") << "(vec3 wi, vec3 wo, vec2 uv) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  return " << fn("eval_p") << "(" << fn("resolve") << "(uv), wi, wo);\n}\n\n";
  }

  // --- lobes, pdf, sample -------------------------------------------------------------------------

  // The absolute index above each layer of a lobe's path, as GLSL expressions: "1.0f" at the top.
  struct PathLayer {
    int node;
    std::string n_above;  // the index above this layer
  };
  std::vector<PathLayer> path_layers(const Lobe& lobe) const {
    std::vector<PathLayer> layers;
    std::string n_above = "1.0f";
    for (const LobeStep& step : lobe.path) {
      if (!std::holds_alternative<LayerNode>(p_.stack[size_t(step.node)])) continue;
      layers.push_back({step.node, n_above});
      n_above = "p." + stack_names_[size_t(step.node)] + "_ior";
    }
    return layers;
  }
  std::string frame_index(const Lobe& lobe) const {
    auto layers = path_layers(lobe);
    return layers.empty() ? "1.0f" : "p." + stack_names_[size_t(layers.back().node)] + "_ior";
  }
  bool microfacet(const Lobe& lobe) const {
    const StackNode& n = p_.stack[size_t(lobe.node)];
    return std::holds_alternative<LayerNode>(n) || std::holds_alternative<ConductorNode>(n);
  }
  int distribution(const Lobe& lobe) const {
    const StackNode& n = p_.stack[size_t(lobe.node)];
    if (const auto* l = std::get_if<LayerNode>(&n))
      return int(std::get<DielectricInterface>(l->interface).distribution);
    if (const auto* c = std::get_if<ConductorNode>(&n)) return int(c->distribution);
    return 0;
  }
  std::string count() const { return std::to_string(lobes_.size()); }
  std::string lobe_arrays() const {
    return "  float weight[" + count() + "];\n  vec3 v[" + count() + "];\n  float m[" + count() + "];\n  bool valid[" +
           count() + "];\n  " + fn("lobes") + "(p, wo, weight, v, m, valid);\n";
  }
  std::string lobe_comment(size_t j) const {
    return "lobe " + std::to_string(j) + ": " + lobes_[j].name + ", node \"" + node_id(lobes_[j].node) + "\"";
  }

  void emit_lobes(std::ostringstream& s) {
    s << "// Lobe selection at wo (course sec. 3.2.3): each lobe's Fresnel reflectance or albedo, times\n"
         "// (1 - F)^2 and the absorption of every layer above it along the refracted wo, times the mix\n"
         "// weights on its path, plus a floor of 1% of the mean; normalised. v, m: wo and the slope in\n"
         "// the lobe's own frame; valid: wo reaches it.\n";
    s << call("void " + fn("lobes"),
              {params_type() + " p", "vec3 wo", "out float weight[" + count() + "]", "out vec3 v[" + count() + "]",
               "out float m[" + count() + "]", "out bool valid[" + count() + "]"},
              " {");
    s << "  float total = 0.0f;\n";
    for (size_t j = 0; j < lobes_.size(); ++j) {
      const Lobe& lobe = lobes_[j];
      std::string J = "[" + std::to_string(j) + "]";
      s << "  // " << lobe_comment(j) << "\n  {\n";
      s << "    v" << J << " = wo;\n    valid" << J << " = wo.z > 0.0f;\n";
      s << "    float throughput = 1.0f;\n    float m_above = 0.0f;\n    float factor = 0.0f;\n";
      std::string n_above = "1.0f";
      for (const LobeStep& step : lobe.path) {
        const StackNode& node = p_.stack[size_t(step.node)];
        const std::string& sn = stack_names_[size_t(step.node)];
        if (std::holds_alternative<MixNode>(node)) {
          s << "    throughput *= " << (step.side == 0 ? "1.0f - p." + sn + "_weight" : "p." + sn + "_weight") << ";\n";
          continue;
        }
        const auto& layer = std::get<LayerNode>(node);
        bool absorbing = std::holds_alternative<AbsorbingMedium>(layer.medium);
        s << "    if (valid" << J << ") {\n";
        s << call("      vec3 below = lamina_selection_step",
                  {"v" + J, "p." + sn + "_ior / " + n_above,
                   std::to_string(int(std::get<DielectricInterface>(layer.interface).fresnel)),
                   absorbing ? "p." + sn + "_absorption" : "vec3(0.0f)", absorbing ? "p." + sn + "_thickness" : "0.0f",
                   "factor"},
                  ";");
        s << "      if (below.z <= 0.0f) {\n        valid" << J << " = false;\n      } else {\n";
        s << "        throughput *= factor;\n";
        s << "        m_above = " << (p_.clamp_lower_roughness ? "max(p." + sn + "_m, m_above)" : "p." + sn + "_m")
          << ";\n";
        s << "        v" << J << " = below;\n      }\n    }\n";
        n_above = "p." + sn + "_ior";
      }
      const StackNode& node = p_.stack[size_t(lobe.node)];
      const std::string& sn = stack_names_[size_t(lobe.node)];
      std::string estimate;
      if (const auto* l = std::get_if<LayerNode>(&node))
        estimate = "lamina_fresnel_dielectric(" +
                   std::to_string(int(std::get<DielectricInterface>(l->interface).fresnel)) + ", v" + J + ".z, p." +
                   sn + "_ior / " + n_above + ")";
      else if (const auto* c = std::get_if<ConductorNode>(&node))
        estimate = "lamina_luminance(lamina_fresnel_conductor(" + std::to_string(int(c->fresnel)) + ", v" + J +
                   ".z, p." + sn + "_n / " + n_above + ", p." + sn + "_k / " + n_above + "))";
      else
        estimate = "lamina_luminance(p." + sn + "_albedo)";
      s << "    float estimate = 0.0f;\n    if (valid" << J << ") {\n      estimate = " << estimate
        << ";\n      estimate *= throughput;\n    }\n";
      s << "    m" << J << " = lamina_effective_slope(" << (microfacet(lobe) ? "p." + sn + "_m" : "0.0f")
        << ", m_above, " << clamp_flag() << ");\n";
      s << "    weight" << J << " = estimate;\n    total += estimate;\n  }\n";
    }
    s << "  int valid_count = 0;\n";
    s << "  for (int j = 0; j < " << count() << "; ++j) {\n    valid_count += valid[j] ? 1 : 0;\n  }\n";
    s << "  if (valid_count == 0) {\n    for (int j = 0; j < " << count()
      << "; ++j) {\n      weight[j] = 0.0f;\n    }\n    return;\n  }\n";
    s << "  float floor_share = total > 0.0f ? 0.01f * total / float(valid_count) : 1.0f;\n";
    s << "  float sum = 0.0f;\n";
    s << "  for (int j = 0; j < " << count() << "; ++j) {\n    if (valid[j]) {\n      weight[j] += floor_share;\n"
      << "    }\n    sum += weight[j];\n  }\n";
    s << "  for (int j = 0; j < " << count() << "; ++j) {\n    weight[j] /= sum;\n  }\n}\n\n";
  }

  void emit_pdf(std::ostringstream& s) {
    s << "float " << fn("pdf_p") << "(" << params_type() << " p, vec3 wi, vec3 wo) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return 0.0f;\n  }\n" << lobe_arrays();
    s << "  float density = 0.0f;\n";
    for (size_t j = 0; j < lobes_.size(); ++j) {
      const Lobe& lobe = lobes_[j];
      std::string J = "[" + std::to_string(j) + "]";
      s << "  // " << lobe_comment(j) << "\n";
      s << "  if (weight" << J << " > 0.0f && valid" << J << ") {\n";
      s << "    vec3 w = wi;\n    float jacobian = 1.0f;\n";
      for (const PathLayer& layer : path_layers(lobe)) {
        const std::string& sn = stack_names_[size_t(layer.node)];
        s << "    {\n      float eta = p." << sn << "_ior / " << layer.n_above << ";\n";
        s << "      vec3 below = refract_down(w, eta);\n";
        s << "      jacobian *= refraction_jacobian(w.z, below.z, eta);\n      w = below;\n    }\n";
      }
      s << "    if (w.z > 0.0f) {\n";
      if (microfacet(lobe))
        s << call("      density += weight" + J + " * lamina_microfacet_lobe_pdf",
                  {std::to_string(distribution(lobe)), "m" + J, "v" + J, "w", "jacobian", "wi", frame_index(lobe)},
                  ";");
      else
        s << call("      density += weight" + J + " * lamina_diffuse_lobe_pdf", {"w", "jacobian", frame_index(lobe)},
                  ";");
      s << "    }\n  }\n";
    }
    s << "  return density;\n}\n\n";
    s << "// The density (per solid angle) with which " << fn("sample") << " draws wi.\n";
    s << "float " << fn("pdf") << "(vec3 wi, vec3 wo, vec2 uv) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return 0.0f;\n  }\n";
    s << "  return " << fn("pdf_p") << "(" << fn("resolve") << "(uv), wi, wo);\n}\n\n";
  }

  void emit_sample(std::ostringstream& s) {
    s << "// Draws wi for wo: u_layer chooses the lobe, u the direction in it. Returns f(wi, wo); pdf is\n"
         "// the density of wi over all lobes, 0 (with wi = 0) when nothing was drawn.\n";
    s << call("vec3 " + fn("sample"), {"vec3 wo", "vec2 u", "float u_layer", "vec2 uv", "out vec3 wi", "out float pdf"},
              " {");
    s << "  wi = vec3(0.0f);\n  pdf = 0.0f;\n  if (wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  " << params_type() << " p = " << fn("resolve") << "(uv);\n" << lobe_arrays();
    s << "  int chosen = -1;\n  float cumulative = 0.0f;\n";
    s << "  for (int j = 0; j < " << count() << "; ++j) {\n";
    s << "    if (weight[j] <= 0.0f) {\n      continue;\n    }\n";
    s << "    chosen = j;\n    cumulative += weight[j];\n    if (u_layer < cumulative) {\n      break;\n    }\n  }\n";
    s << "  vec3 d = vec3(0.0f);\n  bool inside_cone = true;\n";
    for (size_t j = 0; j < lobes_.size(); ++j) {
      const Lobe& lobe = lobes_[j];
      std::string J = "[" + std::to_string(j) + "]";
      s << (j == 0 ? "  if" : " else if") << " (chosen == " << j << ") {\n";
      s << "    // " << lobe_comment(j) << "\n";
      if (microfacet(lobe))
        s << call("    d = lamina_sample_microfacet_lobe",
                  {std::to_string(distribution(lobe)), "m" + J, "v" + J, "u", frame_index(lobe), "inside_cone"}, ";");
      else
        s << "    d = lamina_sample_diffuse_lobe(u, " << frame_index(lobe) << ");\n";
      auto layers = path_layers(lobe);
      if (!layers.empty()) {
        s << "    // up through the layers above, bottom first\n";
        s << "    if (d.z > 0.0f && inside_cone) {\n";
        for (auto it = layers.rbegin(); it != layers.rend(); ++it) {
          const std::string& sn = stack_names_[size_t(it->node)];
          s << "      if (d.z > 0.0f) {\n        d = refract_up(d, p." << sn << "_ior / " << it->n_above
            << ");\n      }\n";
        }
        s << "    }\n";
      }
      s << "  }";
    }
    s << "\n  if (d.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  wi = normalize(d);\n";
    s << "  pdf = " << fn("pdf_p") << "(p, wi, wo);\n";
    s << "  return " << fn("eval_p") << "(p, wi, wo);\n}\n\n";
  }

  const Program& p_;
  const Options& o_;
  MaterialInterface& mi_;
  std::vector<Lobe> lobes_;
  std::vector<std::string> stack_names_;
  NameTable locals_, block_names_, samplers_;
  std::map<int, std::string> scalar_regs_, color_regs_;
  std::ostringstream fields_, assigns_;
  size_t block_end_ = 0;
};

void validate(const Program& p) {
  auto bad = [&](const std::string& why) {
    throw std::invalid_argument("GLSL back end: material '" + p.name + "': " + why);
  };
  if (p.root < 0 || p.root >= int(p.stack.size())) bad("no surface");
  for (const StackNode& n : p.stack) {
    if (const auto* l = std::get_if<LayerNode>(&n); l && (l->base < 0 || l->base >= int(p.stack.size())))
      bad("a layer without a base");
    if (const auto* m = std::get_if<MixNode>(&n); m && (m->a < 0 || m->b < 0)) bad("a mix without two stacks");
  }
  if (collect_lobes(p).empty()) bad("no lobes");
}

std::string header(std::span<const Program> programs, const Module& module, const Options& o) {
  std::ostringstream s;
  s << "// Generated by lamina " << o.lamina_version << " (lamina glsl): target " << version_line(o.target) + 9
    << ", parameters " << (o.uniforms ? "in uniform blocks" : "inlined as constants") << ".\n";
  for (size_t i = 0; i < programs.size(); ++i)
    s << "// material \"" << programs[i].name << "\" from " << source_name(programs[i]) << "\n";
  s << "//\n"
       "// Per material NAME, in the local shading frame (z the normal; wi towards the light, wo towards\n"
       "// the viewer, both away from the surface and normalised; f excludes the cosine):\n"
       "//   vec3  lamina_NAME_eval(vec3 wi, vec3 wo, vec2 uv)    BRDF f(wi, wo); 0 below the horizon\n"
       "//   float lamina_NAME_pdf(vec3 wi, vec3 wo, vec2 uv)     density of wi under lamina_NAME_sample\n"
       "//   vec3  lamina_NAME_sample(vec3 wo, vec2 u, float u_layer, vec2 uv, out vec3 wi, out float pdf)\n"
       "//         draws wi with u, u_layer uniform in [0, 1); returns f(wi, wo); pdf = 0 if none\n";
  for (const MaterialInterface& m : module.materials) {
    if (!m.block.empty()) {
      s << "//\n// uniform block " << m.block << " (instance " << m.instance << "), std140, " << m.block_size
        << " bytes:\n//   offset  type   member = value in the file\n";
      for (const UniformField& f : m.uniforms) {
        std::string offset = std::to_string(f.offset);
        s << "//   " << std::string(offset.size() < 6 ? 6 - offset.size() : 0, ' ') << offset << "  " << f.type
          << std::string(f.type.size() < 5 ? 5 - f.type.size() : 0, ' ') << "  " << f.name << " =";
        for (float x : f.value) s << " " << float_literal(x).substr(0, float_literal(x).size() - 1);
        s << "\n";
      }
    }
    for (const SamplerBinding& b : m.samplers)
      s << "//\n// uniform sampler2D " << b.name << ": node \"" << b.node << "\", file " << b.file << " (" << b.width
        << " x " << b.height << ").\n"
        << "//   Bind it so that texelFetch returns linear RGBA with the file's top row as row 0: RGBA32F of\n"
        << "//   the texels decoded as lamina decodes them (a GL's own sRGB decoding of SRGB8_ALPHA8 is not\n"
        << "//   exact enough to match the CPU); lamina filters and wraps itself.\n";
  }
  return s.str();
}

const char* kImageGlue =
    R"(// texture/image lookups: bilinear filtering and wrapping done here with texelFetch, exactly as the
// CPU evaluator does them, so results agree whatever sampler state the host sets.
vec4 lamina_image_bilinear(sampler2D image, vec2 uv, int wrap) {
  ivec2 size = textureSize(image, 0);
  ivec4 t;
  vec2 w = lamina_bilinear_texels(uv, size.x, size.y, wrap, t);
  vec4 top = mix(texelFetch(image, t.xy, 0), texelFetch(image, t.zy, 0), w.x);
  vec4 bottom = mix(texelFetch(image, t.xw, 0), texelFetch(image, t.zw, 0), w.x);
  return mix(top, bottom, w.y);
}

)";

}  // namespace

Module generate(std::span<const Program> programs, const Options& options) {
  if (programs.empty()) throw std::invalid_argument("GLSL back end: no material to generate");
  for (const Program& p : programs) validate(p);
  Module module;
  std::vector<std::string> bodies;
  std::set<std::string> prefixes;
  for (const Program& p : programs) {
    module.materials.emplace_back();
    MaterialEmitter emitter(p, options, module.materials.back());
    bodies.push_back(emitter.emit());
    if (!prefixes.insert(module.materials.back().prefix).second)
      throw std::invalid_argument("GLSL back end: materials '" + p.name + "' and another give the same GLSL prefix " +
                                  module.materials.back().prefix);
  }
  std::ostringstream s;
  s << version_line(options.target) << "\n";
  s << header(programs, module, options) << "\n";
  s << "#define LAMINA_FN\n#define LAMINA_OUT(T) out T\n";
  if (options.target == Target::Es300)
    s << "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\n";
  s << "\n";
  std::string code;  // everything after the kernels: what decides which kernels are needed
  bool images = false;
  for (const MaterialInterface& m : module.materials) images = images || !m.samplers.empty();
  if (images) code += kImageGlue;
  for (const std::string& body : bodies) code += body;
  if (options.sphere_shader) code += sphere_shader(module.materials.front().prefix);
  s << needed_kernels(kernel_sources(), code) << code;
  module.source = s.str();
  return module;
}

}  // namespace lamina::glsl
