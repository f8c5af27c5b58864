#include "graph/glsl/generator.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "graph/cpu/image.h"
#include "graph/glsl/glsl_text.h"
#include "graph/glsl/kernel_items.h"
#include "graph/glsl/op_writer.h"
#include "graph/glsl/plane_shader.h"
#include "graph/glsl/sphere_shader.h"
#include "graph/kernel_stack.h"
#include "graph/node_decl.h"
#include "nodes/kernels/kernels.h"

namespace lamina::glsl {

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

// std140: float aligns to 4, vec2 to 8, vec3 to 16 (and takes 12 bytes).
size_t std140_align(const std::string& type) { return type == "float" ? 4 : type == "vec2" ? 8 : 16; }
size_t std140_size(const std::string& type) { return type == "float" ? 4 : type == "vec2" ? 8 : 12; }

const char* type_of_size(int size) { return size == 1 ? "float" : size == 2 ? "vec2" : "vec3"; }

std::string literal(glm::vec3 v, int size) {
  return size == 1 ? float_literal(v.x) : size == 2 ? vec2_literal(glm::vec2(v)) : vec3_literal(v);
}

// `expression` clamped to [lo, hi] where those are finite, as InputRef reads registers.
std::string clamped(const std::string& expression, const InputRef& r) {
  const bool low = std::isfinite(r.lo), high = std::isfinite(r.hi);
  auto bound = [&](float x) {
    return r.size == 1 ? float_literal(x) : std::string(type_of_size(r.size)) + "(" + float_literal(x) + ")";
  };
  if (low && high) return "clamp(" + expression + ", " + bound(r.lo) + ", " + bound(r.hi) + ")";
  if (low) return "max(" + expression + ", " + bound(r.lo) + ")";
  if (high) return "min(" + expression + ", " + bound(r.hi) + ")";
  return expression;
}

// An entry's nodes as the user wrote them: "id" (type), the interface and medium of a layer too.
std::string what_entry(const StackEntry& e) {
  std::string text = "\"" + e.node + "\" (" + (e.decl ? e.decl->type : std::string("entry"));
  text += e.note.empty() ? ")" : ", " + e.note + ")";
  if (!e.interface_node.empty() && e.interface_decl)
    text += " with \"" + e.interface_node + "\" (" + e.interface_decl->type + ")";
  if (!e.medium_node.empty() && e.medium_decl) text += " over \"" + e.medium_node + "\" (" + e.medium_decl->type + ")";
  return text;
}

// Emits the GLSL of one material: its stack as a constant array of LaminaEntry, a resolve function
// (the texture nodes' code, each entry's inputs, lamina_stack_resolve) and the three functions that
// call the kernels' composition. Every value is a literal, a uniform block member or a register.
class MaterialEmitter final : public OpWriter {
 public:
  MaterialEmitter(const Program& program, const Options& options, MaterialInterface& out,
                  std::map<std::string, std::string>& module_code)
      : p_(program), o_(options), mi_(out), module_code_(module_code) {
    mi_.material = p_.name;
    mi_.prefix = "lamina_" + name_part(p_.name);
    by_parts_ = evaluates_by_parts(p_);
    if (by_parts_) blend_ = split_blend(p_, !o_.uniforms);
    if (o_.uniforms) {
      mi_.block = mi_.prefix + "_block";
      mi_.instance = mi_.prefix + "_u";
    }
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
    emit_entries(s);
    s << resolve;
    emit_functions(s);
    return s.str();
  }

  // --- OpWriter: what texture and math nodes write their code with -------------------------------

  std::string input(const TextureOp& op, size_t i) override { return input(op.inputs.at(i)); }
  std::string context(const std::string& member) override { return "ctx." + member; }
  std::string output(const TextureOp& op, size_t k, const std::string& expression) override {
    const OutputDecl& o = op.decl->outputs.at(k);
    const int size = o.type == ValueType::Float ? 1 : o.type == ValueType::Vec2 ? 2 : 3;
    const std::string name = locals_.unique("t_" + name_part(op.node) + "_" + o.name);
    ops_ << "  " << type_of_size(size) << " " << name << " = " << expression << ";\n";
    registers_[op.outputs.at(k)] = name;
    return name;
  }
  std::string local(const TextureOp& op, const std::string& what, const std::string& type,
                    const std::string& expression) override {
    const std::string name = locals_.unique("t_" + name_part(op.node) + "_" + what);
    ops_ << "  " << type << " " << name << " = " << expression << ";\n";
    return name;
  }
  std::string sampler(const TextureOp& op) override {
    SamplerBinding b;
    b.name = samplers_.unique(mi_.prefix + "_image_" + name_part(op.node));
    b.node = op.node;
    b.file = op.file;
    b.width = op.image ? op.image->width : 0;
    b.height = op.image ? op.image->height : 0;
    mi_.samplers.push_back(b);
    return b.name;
  }
  void module_code(const std::string& name, const std::string& text) override { module_code_.emplace(name, text); }
  void comment(const std::string& text) override { ops_ << "  // " << text << "\n"; }

 private:
  std::string fn(const std::string& what) const { return mi_.prefix + "_" + what; }
  std::string count() const { return fn("count"); }
  std::string entries() const { return fn("entries"); }
  // By parts: the number of parts, their counts and entries (LAMINA_STACK apart), and the blend.
  std::string parts() const { return fn("parts") + ", " + fn("part_counts") + ", " + fn("part_entries"); }
  std::string clamp_flag() const { return p_.clamp_lower_roughness ? "true" : "false"; }
  // An untextured material in an inlined module: its parameters are constants, resolved here by
  // the kernels the CPU runs (to the bit), so the module holds them instead of their inputs.
  bool fixed() const { return !p_.textured() && !o_.uniforms; }
  const char* composition() const { return composition_function(p_.model); }

  // A member of the uniform block holding `value`, named after the node and parameter that gave it;
  // a node shared by several entries keeps one member.
  std::string uniform(const InputRef& r, glm::vec3 value) {
    for (const UniformField& f : mi_.uniforms)
      if (f.node == r.node && f.parameter == r.parameter) return mi_.instance + "." + f.name;
    const std::string type = type_of_size(r.size);
    const std::string name = block_names_.unique(name_part(r.node) + "_" + r.parameter);
    size_t align = std140_align(type);
    block_end_ = (block_end_ + align - 1) / align * align;
    std::vector<float> v{value.x, value.y, value.z};
    v.resize(size_t(r.size));
    mi_.uniforms.push_back({name, type, block_end_, std::move(v), r.node, r.parameter});
    block_end_ += std140_size(type);
    mi_.block_size = (block_end_ + 15) / 16 * 16;
    return mi_.instance + "." + name;
  }

  // An input: the register's variable (clamped), a uniform member, or the literal `folded` (the
  // constant as the kernels read it).
  std::string input(const InputRef& r, glm::vec3 folded) {
    if (r.linked()) return clamped(registers_.at(r.slot), r);
    if (o_.uniforms && !r.parameter.empty()) return uniform(r, r.constant);
    return literal(folded, r.size);
  }
  std::string input(const InputRef& r) { return input(r, r.constant); }

  // --- the stack ------------------------------------------------------------------------------------

  static void entry_literal(std::ostringstream& s, const kernels::LaminaEntry& e) {
    s << "LaminaEntry(" << e.kind << ", " << e.model << ", " << e.medium << ", " << e.distribution << ", " << e.fresnel
      << ", " << e.degrees << ", " << e.parent << ", " << e.side << ", " << e.first << ", " << e.second << ")";
  }

  // A material evaluated by parts: its blend, and its parts' entries, part k from k LAMINA_STACK on.
  void emit_parts(std::ostringstream& s) {
    const kernels::LaminaEntry unused{kernels::LAMINA_MIX, 0, 0, 0, 0, 0, -1, 0, -1, -1};
    s << "// The stack, " << p_.stack.size() << " entries, as the blend of its " << blend_.parts.size()
      << " parts (nodes/kernels/stack.glsl): LaminaEntry(kind,\n// model, medium, distribution, fresnel, degrees, "
         "parent, side, first, second), as stack.glsl defines them.\n";
    s << "const int " << fn("blend_count") << " = " << blend_.entries.size() << ";\n";
    s << "const LaminaEntry " << fn("blend") << "[LAMINA_BLEND] = LaminaEntry[LAMINA_BLEND](\n";
    for (size_t i = 0; i < blend_length_; ++i) {
      const bool used = i < blend_.entries.size();
      s << "    ";
      entry_literal(s, used ? blend_.entries[i] : unused);
      s << (i + 1 < blend_length_ ? "," : "") << "  // "
        << (used ? std::to_string(i) + ": " + what_entry(p_.stack[size_t(blend_.whole[i])]) : std::string("unused"))
        << "\n";
    }
    s << ");\n";
    s << "const int " << fn("parts") << " = " << blend_.parts.size() << ";\n";
    s << "const int " << fn("part_counts") << "[LAMINA_PARTS] = int[LAMINA_PARTS](";
    for (size_t k = 0; k < parts_length_; ++k)
      s << (k ? ", " : "") << (k < blend_.parts.size() ? blend_.parts[k].count : 0);
    s << ");\n";
    s << "const LaminaEntry " << fn("part_entries")
      << "[LAMINA_PARTS * LAMINA_STACK] = LaminaEntry[LAMINA_PARTS * LAMINA_STACK](\n";
    for (size_t k = 0; k < parts_length_; ++k) {
      std::vector<kernels::LaminaEntry> part;
      if (k < blend_.parts.size()) part = blend_.part_entries(p_, k, !o_.uniforms);
      for (size_t j = 0; j < stack_length_; ++j) {
        const bool used = j < part.size();
        s << "    ";
        entry_literal(s, used ? part[j] : unused);
        const bool last = k + 1 == parts_length_ && j + 1 == stack_length_;
        s << (last ? "" : ",") << "  // part " << k << ", "
          << (used ? std::to_string(j) + ": " + what_entry(p_.stack[size_t(blend_.parts[k].first) + j])
                   : std::string("unused"))
          << "\n";
      }
    }
    s << ");\n\n";
  }

  void emit_entries(std::ostringstream& s) {
    if (by_parts_) return emit_parts(s);
    const size_t n = p_.stack.size();
    s << "// The stack, depth first from the surface: LaminaEntry(kind, model, medium, distribution,\n"
         "// fresnel, degrees, parent, side, first, second), as nodes/kernels/stack.glsl defines them.\n";
    s << "const int " << count() << " = " << n << ";\n";
    s << "const LaminaEntry " << entries() << "[LAMINA_STACK] = LaminaEntry[LAMINA_STACK](\n";
    for (size_t i = 0; i < stack_length_; ++i) {
      const bool used = i < n;
      const kernels::LaminaEntry e = used ? kernel_entry(p_.stack[i], !o_.uniforms)
                                          : kernels::LaminaEntry{kernels::LAMINA_MIX, 0, 0, 0, 0, 0, -1, 0, -1, -1};
      s << "    LaminaEntry(" << e.kind << ", " << e.model << ", " << e.medium << ", " << e.distribution << ", "
        << e.fresnel << ", " << e.degrees << ", " << e.parent << ", " << e.side << ", " << e.first << ", " << e.second
        << ")" << (i + 1 < stack_length_ ? "," : "");
      s << "  // " << (used ? std::to_string(i) + ": " + what_entry(p_.stack[i]) : std::string("unused")) << "\n";
    }
    s << ");\n\n";
  }

  // Every member of resolved parameters q as assignments to `at` + member.
  static void params_literal(std::ostringstream& s, const std::string& at, const kernels::LaminaParams& q) {
    s << at << "n_above = " << float_literal(q.n_above) << ";\n"
      << at << "m_above = " << float_literal(q.m_above) << ";\n"
      << at << "ior = " << float_literal(q.ior) << ";\n"
      << at << "eta = " << float_literal(q.eta) << ";\n"
      << at << "m = " << float_literal(q.m) << ";\n"
      << at << "thickness = " << float_literal(q.thickness) << ";\n"
      << at << "weight = " << float_literal(q.weight) << ";\n"
      << at << "share = " << float_literal(q.share) << ";\n"
      << at << "sigma = " << float_literal(q.sigma) << ";\n"
      << at << "absorption = " << vec3_literal(q.absorption) << ";\n"
      << at << "albedo = " << vec3_literal(q.albedo) << ";\n"
      << at << "flake = " << vec3_literal(q.flake) << ";\n"
      << at << "flake_paint = " << vec2_literal(q.flake_paint) << ";\n"
      << at << "flake_depth = " << vec3_literal(q.flake_depth) << ";\n"
      << at << "flake_base = " << vec3_literal(q.flake_base) << ";\n"
      << at << "n = " << vec3_literal(q.n) << ";\n"
      << at << "k = " << vec3_literal(q.k) << ";\n"
      << at << "film_eta = " << vec3_literal(q.film_eta) << ";\n"
      << at << "film_depth = " << float_literal(q.film_depth) << ";\n"
      << at << "normal = " << vec3_literal(q.normal) << ";\n"
      << at << "frame_x = " << vec3_literal(q.frame_x) << ";\n"
      << at << "frame_y = " << vec3_literal(q.frame_y) << ";\n"
      << at << "diffuse = " << vec3_literal(q.diffuse) << ";\n"
      << at << "glowing = " << (q.glowing ? "true" : "false") << ";\n"
      << at << "glow = " << mat3_literal(q.glow) << ";\n"
      << at << "forward = " << vec3_literal(q.forward) << ";\n"
      << at << "grid = " << vec2_literal(q.grid) << ";\n"
      << at << "cone_grid = " << vec2_literal(q.cone_grid) << ";\n"
      << at << "cone_etas = " << vec3_literal(q.cone_etas) << ";\n"
      << at << "exit_cut = " << vec2_literal(q.exit_cut) << ";\n"
      << at << "trap_ramp = " << vec3_literal(q.trap_ramp) << ";\n"
      << at << "trap_angles = " << vec2_literal(q.trap_angles) << ";\n"
      << at << "trap_near = " << vec3_literal(q.trap_near) << ";\n"
      << at << "trap_far = " << vec3_literal(q.trap_far) << ";\n"
      << at << "spread_own = " << float_literal(q.spread_own) << ";\n"
      << at << "arrival_y = " << float_literal(q.arrival_y) << ";\n";
  }

  // Where entry i's inputs go: an array of the whole stack, or by parts the blend's (a mix of it)
  // or its part's, from k LAMINA_STACK on; empty for none (a part's first entry in the blend).
  std::vector<std::string> input_targets() const {
    std::vector<std::string> at(p_.stack.size());
    if (!by_parts_) {
      for (size_t i = 0; i < at.size(); ++i) at[i] = "inputs[" + std::to_string(i) + "]";
      return at;
    }
    for (size_t b = 0; b < blend_.entries.size(); ++b)
      if (blend_.entries[b].kind == kernels::LAMINA_MIX)
        at[size_t(blend_.whole[b])] = "blend_inputs[" + std::to_string(b) + "]";
    for (size_t k = 0; k < blend_.parts.size(); ++k)
      for (int j = 0; j < blend_.parts[k].count; ++j)
        at[size_t(blend_.parts[k].first + j)] = "inputs[" + std::to_string(k * stack_length_ + size_t(j)) + "]";
    return at;
  }

  // An untextured material evaluated by parts: its shares and parts' parameters, resolved by the
  // C++ kernels (whose arrays hold LAMINA_STACK = kMaxStackEntries entries per part).
  void fixed_parts_literal(std::ostringstream& s) {
    const size_t stride = size_t(kMaxStackEntries), most_parts = size_t(kMaxLobes);
    std::vector<kernels::LaminaInputs> blend_inputs(stride);
    for (size_t b = 0; b < blend_.entries.size(); ++b)
      blend_inputs[b] = kernel_constants(p_.stack[size_t(blend_.whole[b])], true);
    std::vector<float> shares(stride, 0.0f);
    kernels::lamina_blend_shares(int(blend_.entries.size()), blend_.entries.data(), blend_inputs.data(), shares.data());
    std::vector<kernels::LaminaEntry> entries(most_parts * stride);
    std::vector<kernels::LaminaInputs> inputs(entries.size());
    std::vector<int> counts(most_parts, 0);
    std::vector<float> share(most_parts, 0.0f);
    for (size_t k = 0; k < blend_.parts.size(); ++k) {
      const std::vector<kernels::LaminaEntry> part = blend_.part_entries(p_, k, true);
      counts[k] = int(part.size());
      share[k] = shares[size_t(blend_.parts[k].blend)];
      for (size_t j = 0; j < part.size(); ++j) {
        entries[k * stride + j] = part[j];
        inputs[k * stride + j] = kernel_constants(p_.stack[size_t(blend_.parts[k].first) + j], true);
      }
    }
    auto resolved = std::make_unique<kernels::LaminaPoint>();
    kernels::lamina_blend_resolve(int(blend_.parts.size()), counts.data(), entries.data(), inputs.data(), share.data(),
                                  p_.clamp_lower_roughness, p_.model, *resolved);
    for (size_t k = 0; k < blend_.parts.size(); ++k) {
      s << "  point.share[" << k << "] = " << float_literal(share[k]) << ";\n";
      for (int j = 0; j < blend_.parts[k].count; ++j) {
        s << "  // part " << k << ", " << j << ": " << what_entry(p_.stack[size_t(blend_.parts[k].first + j)]) << "\n";
        params_literal(s, "  point.parts[" + std::to_string(k * stack_length_ + size_t(j)) + "].",
                       resolved->parts[k * stride + size_t(j)]);
      }
    }
  }

  std::string emit_resolve() {
    std::ostringstream s;
    s << "// Every entry's parameters at the shading point ctx.\n";
    if (by_parts_)
      s << "void " << fn("resolve") << "(LaminaContext ctx, out LaminaPoint point) {\n";
    else
      s << "void " << fn("resolve") << "(LaminaContext ctx, out LaminaParams params[LAMINA_STACK]) {\n";
    if (fixed()) {
      // Resolved once, by the C++ kernels, into constants.
      if (by_parts_) {
        fixed_parts_literal(s);
        s << "}\n\n";
        return s.str();
      }
      std::vector<kernels::LaminaEntry> e;
      std::vector<kernels::LaminaInputs> x;
      for (const StackEntry& entry : p_.stack) {
        e.push_back(kernel_entry(entry, true));
        x.push_back(kernel_constants(entry, true));
      }
      std::vector<kernels::LaminaParams> params(p_.stack.size());
      kernels::lamina_stack_resolve(int(e.size()), e.data(), x.data(), 1.0f, p_.clamp_lower_roughness, p_.model,
                                    params.data());
      for (size_t i = 0; i < params.size(); ++i) {
        s << "  // " << i << ": " << what_entry(p_.stack[i]) << "\n";
        params_literal(s, "  params[" + std::to_string(i) + "].", params[i]);
      }
      s << "}\n\n";
      return s.str();
    }
    for (const TextureOp& op : p_.ops) {
      ops_ << "  // node \"" << op.node << "\" (" << op.decl->type << ")\n";
      op.decl->emit_glsl(op, *this);
    }
    std::ostringstream inputs;
    if (by_parts_)
      inputs << "  LaminaInputs blend_inputs[LAMINA_BLEND];\n  LaminaInputs inputs[LAMINA_PARTS * LAMINA_STACK];\n";
    else
      inputs << "  LaminaInputs inputs[LAMINA_STACK];\n";
    const std::vector<std::string> targets = input_targets();
    for (size_t i = 0; i < p_.stack.size(); ++i) {
      if (targets[i].empty()) continue;
      const StackEntry& e = p_.stack[i];
      const kernels::LaminaInputs folded = kernel_constants(e, !o_.uniforms);
      const std::string at = "  " + targets[i] + ".";
      inputs << "  // " << i << ": " << what_entry(e) << "\n";
      inputs << at << "colour0 = " << input(e.colour0, folded.colour0) << ";\n";
      inputs << at << "colour1 = " << input(e.colour1, folded.colour1) << ";\n";
      inputs << at << "colour2 = " << input(e.colour2, folded.colour2) << ";\n";
      inputs << at << "scalars = vec4(" << input(e.scalar_x, glm::vec3(folded.scalars.x)) << ", "
             << input(e.scalar_y, glm::vec3(folded.scalars.y)) << ", " << input(e.scalar_z, glm::vec3(folded.scalars.z))
             << ", " << input(e.scalar_w, glm::vec3(folded.scalars.w)) << ");\n";
      inputs << at << "normal = " << input(e.normal, folded.normal) << ";\n";
    }
    s << ops_.str() << inputs.str();
    if (by_parts_) {
      s << "  float shares[LAMINA_BLEND];\n  lamina_blend_shares(" << fn("blend_count") << ", " << fn("blend")
        << ", blend_inputs, shares);\n  float share[LAMINA_PARTS];\n";
      for (size_t k = 0; k < blend_.parts.size(); ++k)
        s << "  share[" << k << "] = shares[" << blend_.parts[k].blend << "];\n";
      s << "  lamina_blend_resolve(" << parts() << ", inputs, share, " << clamp_flag() << ", " << p_.model
        << ", point);\n}\n\n";
      return s.str();
    }
    s << "  lamina_stack_resolve(" << count() << ", " << entries() << ", inputs, 1.0f, " << clamp_flag() << ", "
      << p_.model << ", params);\n}\n\n";
    return s.str();
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

  // --- the functions: the kernels' composition on the resolved parameters ---------------------------

  // Whether the material has a fluorescent base (lamina_stack_glows): its f is a matrix.
  bool glows() const {
    return std::any_of(p_.stack.begin(), p_.stack.end(), [](const StackEntry& e) {
      return e.kind == kernels::LAMINA_SUBSTRATE && e.model == kernels::LAMINA_SUBSTRATE_FLUORESCENT;
    });
  }

  // Under fluorescence, what is reflected of a coloured light and the transpose a path traced from
  // the viewer carries (the kernels' *_response functions; eval is their white light).
  void emit_light_functions(std::ostringstream& s, const std::string& stack) {
    const std::string model = p_.model == kernels::LAMINA_MODEL_ENERGY_CONSERVING ? "_conserving" : "";
    auto response = [&](const char* from, const char* to, const char* light, bool adjoint) {
      const std::string tail = std::string(from) + ", " + to + ", " + light + ", " + (adjoint ? "true" : "false");
      return by_parts_ ? "lamina_blend_response(" + stack + ", " + std::to_string(p_.model) + ", " + tail + ")"
                       : "lamina_stack_response" + model + "(" + stack + ", " + tail + ", true)";
    };
    s << "// What \"" << p_.name << "\" reflects toward wo of light of colour `light` from wi. Its fluorescent\n"
      << "// base moves light between channels, so this is not " << fn("eval") << " times the light.\n";
    s << "vec3 " << fn("eval_light") << "(vec3 wi, vec3 wo, vec3 light, LaminaPoint point) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  return " << response("wi", "wo", "light", false) << ";\n}\n\n";
    s << "// The transpose, F^T(wi, wo) weight: what a path traced from the viewer carries on past this\n"
      << "// bounce (dot(weight, " << fn("eval_light") << "(wi, wo, L, point)) = dot(" << fn("eval_adjoint")
      << "(wi, wo, weight, point), L)).\n";
    s << "vec3 " << fn("eval_adjoint") << "(vec3 wi, vec3 wo, vec3 weight, LaminaPoint point) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  return " << response("wo", "wi", "weight", true) << ";\n}\n\n";
  }

  void emit_functions(std::ostringstream& s) {
    // The kernels' composition over the whole stack, or by parts over its blend.
    const std::string stack = by_parts_ ? parts() + ", point" : count() + ", " + entries() + ", point.params";
    const std::string select =
        by_parts_ ? "  LaminaPartsSelection selection;\n  lamina_blend_select(" + stack + ", wo, selection);\n"
                  : "  float weight[LAMINA_STACK];\n  vec3 v[LAMINA_STACK];\n  bool valid[LAMINA_STACK];\n"
                    "  lamina_stack_select(" +
                        stack + ", wo, weight, v, valid);\n";
    const std::string eval = by_parts_ ? "lamina_blend_eval(" + stack + ", " + std::to_string(p_.model) + ", wi, wo)"
                                       : std::string(composition()) + "(" + stack + ", wi, wo)";
    const std::string pdf = by_parts_ ? "lamina_blend_pdf(" + stack + ", selection, wi, wo)"
                                      : "lamina_stack_pdf(" + stack + ", weight, v, valid, wi, wo)";
    s << "// \"" << p_.name
      << "\" at one shading context: its stack's parameters, resolved once (textures read,\n"
         "// tables looked up) for any number of directions.\n";
    s << "LaminaPoint " << fn("point") << "(LaminaContext ctx) {\n  LaminaPoint point;\n  " << fn("resolve")
      << (by_parts_ ? "(ctx, point)" : "(ctx, point.params)") << ";\n  return point;\n}\n\n";
    s << "// The BRDF f(wi, wo) of \"" << p_.name << "\", without the cosine; 0 below the horizon.\n";
    s << "vec3 " << fn("eval") << "(vec3 wi, vec3 wo, LaminaPoint point) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n";
    s << "  return " << eval << ";\n}\n\n";
    if (glows()) emit_light_functions(s, stack);
    s << "// The density (per solid angle) with which " << fn("sample") << " draws wi.\n";
    s << "float " << fn("pdf") << "(vec3 wi, vec3 wo, LaminaPoint point) {\n";
    s << "  if (wi.z <= 0.0f || wo.z <= 0.0f) {\n    return 0.0f;\n  }\n" << select;
    s << "  return " << pdf << ";\n}\n\n";
    s << "// Draws wi for wo: u_layer chooses the lobe, u the direction in it. Returns f(wi, wo); pdf is\n"
         "// the density of wi over all lobes, 0 (with wi = 0) when nothing was drawn.\n";
    s << call("vec3 " + fn("sample"),
              {"vec3 wo", "vec2 u", "float u_layer", "LaminaPoint point", "out vec3 wi", "out float pdf"}, " {");
    s << "  wi = vec3(0.0f);\n  pdf = 0.0f;\n  if (wo.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n" << select;
    if (by_parts_) {
      s << "  int chosen = lamina_blend_choose(" << fn("parts") << ", " << fn("part_counts")
        << ", selection, u_layer);\n";
      s << "  vec3 d = lamina_blend_sample(" << fn("part_counts") << ", " << fn("part_entries")
        << ", point, selection, chosen, u);\n";
    } else {
      s << "  int chosen = lamina_stack_choose(" << count() << ", weight, u_layer);\n";
      s << "  vec3 d = lamina_stack_sample(" << count() << ", " << entries() << ", point.params, v, chosen, u);\n";
    }
    s << "  if (d.z <= 0.0f) {\n    return vec3(0.0f);\n  }\n  wi = d;\n";
    s << "  pdf = " << pdf << ";\n";
    s << "  return " << eval << ";\n}\n\n";
    // The same at a context, through the point, and at a texture coordinate, through the context.
    for (const char* where : {"LaminaContext ctx", "vec2 uv"}) {
      const bool uv = where[0] == 'v';
      const std::string at = uv ? std::string("lamina_context(uv)") : fn("point") + "(ctx)";
      s << (uv ? "// The same at a texture coordinate alone (the other members of the context at their defaults).\n"
               : "// The same at a shading context: each call resolves the point again.\n");
      if (uv)
        s << "LaminaPoint " << fn("point") << "(vec2 uv) {\n  return " << fn("point") << "(lamina_context(uv));\n}\n\n";
      s << "vec3 " << fn("eval") << "(vec3 wi, vec3 wo, " << where << ") {\n  return " << fn("eval") << "(wi, wo, "
        << at << ");\n}\n\n";
      s << "float " << fn("pdf") << "(vec3 wi, vec3 wo, " << where << ") {\n  return " << fn("pdf") << "(wi, wo, " << at
        << ");\n}\n\n";
      s << call("vec3 " + fn("sample"), {"vec3 wo", "vec2 u", "float u_layer", where, "out vec3 wi", "out float pdf"},
                " {");
      s << "  return " << fn("sample") << "(wo, u, u_layer, " << at << ", wi, pdf);\n}\n\n";
    }
  }

 public:
  size_t stack_length_ = 1;  // LAMINA_STACK of the module
  size_t parts_length_ = 1;  // LAMINA_PARTS
  size_t blend_length_ = 1;  // LAMINA_BLEND

 private:
  bool by_parts_ = false;  // evaluates_by_parts
  StackBlend blend_;       // its blend, by parts
  const Program& p_;
  const Options& o_;
  MaterialInterface& mi_;
  std::map<std::string, std::string>& module_code_;
  NameTable locals_, block_names_, samplers_;
  std::map<int, std::string> registers_;
  std::ostringstream ops_;
  size_t block_end_ = 0;
};

void validate(const Program& p) {
  auto bad = [&](const std::string& why) {
    throw std::invalid_argument("GLSL back end: material '" + p.name + "': " + why);
  };
  if (p.stack.empty()) bad("no surface");
  if (int(p.stack.size()) > kMaxStackEntries) bad("more stack entries than the kernels hold");
  for (const StackEntry& e : p.stack) {
    if (e.kind == kernels::LAMINA_LAYER && (e.first <= 0 || e.first >= int(p.stack.size())))
      bad("a layer without a base");
    if (e.kind == kernels::LAMINA_MIX && (e.first <= 0 || e.second <= 0)) bad("a mix without two stacks");
  }
  for (const TextureOp& op : p.ops)
    if (!op.decl || !op.decl->emit_glsl) bad("node \"" + op.node + "\" has no GLSL");
}

std::string header(std::span<const Program> programs, const Module& module, const Options& o) {
  std::ostringstream s;
  s << "// Generated by lamina " << o.lamina_version << " (lamina glsl): target " << version_line(o.target) + 9
    << ", parameters " << (o.uniforms ? "in uniform blocks" : "inlined as constants") << ".\n";
  for (size_t i = 0; i < programs.size(); ++i)
    s << "// material \"" << programs[i].name << "\" from " << source_name(programs[i]) << "\n";
  s << "//\n"
       "// Per material NAME, in the local shading frame (z the normal; wi towards the light, wo towards\n"
       "// the viewer, both away from the surface and normalised; f excludes the cosine), at a shading\n"
       "// context ctx (a LaminaContext: uv, position, normal, tangent, view_distance, footprint; make one\n"
       "// with lamina_context(uv) and set what you have):\n"
       "//   vec3  lamina_NAME_eval(vec3 wi, vec3 wo, LaminaContext ctx)  BRDF f(wi, wo); 0 below the horizon\n"
       "//   float lamina_NAME_pdf(vec3 wi, vec3 wo, LaminaContext ctx)   density of wi under lamina_NAME_sample\n"
       "//   vec3  lamina_NAME_sample(vec3 wo, vec2 u, float u_layer, LaminaContext ctx, out vec3 wi, out float pdf)\n"
       "//         draws wi with u, u_layer uniform in [0, 1); returns f(wi, wo); pdf = 0 if none\n"
       "// and the same three with a vec2 uv in place of ctx. Each resolves the material's parameters at\n"
       "// ctx first (textures, tables); for several directions at one point, resolve once:\n"
       "//   LaminaPoint lamina_NAME_point(LaminaContext ctx)  (or vec2 uv)\n"
       "// and pass the point in place of ctx to the same three.\n";
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
  for (const TableBinding& t : module.tables)
    s << "//\n// uniform highp usampler2D " << t.name << ": " << t.contents << ".\n"
      << "//   Bind an " << t.format << " texture of " << t.width << " x " << t.height
      << " texels, the side file's \"tables\" entry, row 0 first;\n//   lamina reads it with texelFetch.\n";
  return s.str();
}

// The dielectric albedo table (nodes/kernels/energy.glsl) for the combinations of distribution and
// Fresnel term that the boundaries of energy-conserving materials use, as a texture of the integers
// C++ compiles in, and the kernels' reader of it. Without such a boundary the reader returns 0 and
// every combination is absent (the Weidlich-Wilkie composition never reads it), and the module
// declares no texture. Returns the GLSL; adds the texture to `module`.
std::string albedo_table(std::span<const Program> programs, Module& module) {
  std::vector<bool> used(size_t(kernels::LAMINA_ALBEDO_COMBOS), false);
  for (const Program& p : programs)
    for (const StackEntry& e : p.stack) {
      if (p.model != kernels::LAMINA_MODEL_ENERGY_CONSERVING) continue;
      const kernels::LaminaEntry k = kernel_entry(e, true);
      // A layer's boundary reads its own combination, and the shares of its reflection lobe beyond a
      // guide's edge (block C: lamina_guide, lamina_guide_entry_keep) from the exact-Fresnel one of
      // its distribution, whatever its Fresnel term.
      if (k.kind == kernels::LAMINA_LAYER) {
        used[size_t(kernels::lamina_albedo_combo(k.distribution, k.fresnel))] = true;
        used[size_t(kernels::lamina_albedo_combo(k.distribution, 0))] = true;
      }
      // A conductor under a layer (lamina_on_conductor): the share of its lobe inside the layer's exit
      // cone (block C), read from the exact-Fresnel combination of its distribution.
      const bool under_layer = e.parent >= 0 && p.stack[size_t(e.parent)].kind == kernels::LAMINA_LAYER;
      if (under_layer && k.kind == kernels::LAMINA_SUBSTRATE && k.model == kernels::LAMINA_SUBSTRATE_CONDUCTOR)
        used[size_t(kernels::lamina_albedo_combo(k.distribution, 0))] = true;
    }
  TableBinding table;
  table.name = "lamina_dielectric_albedo_table";
  table.format = "R16UI";
  table.width = kernels::LAMINA_ALBEDO_TABLE_WIDTH;
  std::ostringstream rows;
  for (int c = 0; c < kernels::LAMINA_ALBEDO_COMBOS; ++c) {
    rows << (c ? ", " : "") << (used[size_t(c)] ? table.height : -1);
    if (!used[size_t(c)]) continue;
    const int first = kernels::LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[c] * kernels::LAMINA_ALBEDO_TABLE_WIDTH;
    for (int i = 0; i < kernels::LAMINA_ALBEDO_COMBO_SIZE; ++i)
      table.texels.push_back(uint16_t(kernels::LAMINA_DIELECTRIC_ALBEDO[first + i]));
    table.height += kernels::LAMINA_ALBEDO_ETAS;
  }
  std::ostringstream s;
  s << "// The energy a rough dielectric boundary reflects, round(65535 E) (nodes/kernels/energy.glsl): the first\n"
       "// row of each combination of distribution and Fresnel term in the table, -1 if absent.\n";
  s << "const int LAMINA_DIELECTRIC_ALBEDO_FIRST_ROW[" << kernels::LAMINA_ALBEDO_COMBOS << "] = int["
    << kernels::LAMINA_ALBEDO_COMBOS << "](" << rows.str() << ");\n";
  if (table.height == 0) {
    s << "float lamina_albedo_texel(int x, int y) {\n  return 0.0f;\n}\n\n";
    return s.str();
  }
  table.contents = "round(65535 E), the energy a rough dielectric boundary reflects, for " +
                   std::to_string(table.height / kernels::LAMINA_ALBEDO_ETAS) +
                   " combinations of distribution and Fresnel term (nodes/kernels/energy.glsl)";
  s << "// The table: an R16UI texture of " << table.width << " x " << table.height
    << " texels, bound by the host (the side file's \"tables\").\n";
  s << "uniform highp usampler2D " << table.name << ";\n";
  s << "float lamina_albedo_texel(int x, int y) {\n  return float(texelFetch(" << table.name
    << ", ivec2(x, y), 0).r);\n}\n\n";
  module.tables.push_back(std::move(table));
  return s.str();
}

}  // namespace

const char* composition_function(int model) {
  return model == kernels::LAMINA_MODEL_ENERGY_CONSERVING ? "lamina_stack_eval_conserving" : "lamina_stack_eval";
}

bool evaluates_by_parts(const Program& program) {
  return int(program.stack.size()) > kGlslUnrolledEntries && split_blend(program, true).parts.size() > 1;
}

int unrolled_entries(const Program& program) {
  return evaluates_by_parts(program) ? split_blend(program, true).longest_part() : int(program.stack.size());
}

Module generate(std::span<const Program> programs, const Options& options) {
  if (programs.empty()) throw std::invalid_argument("GLSL back end: no material to generate");
  for (const Program& p : programs) validate(p);
  Module module;
  std::vector<std::string> bodies;
  std::set<std::string> prefixes;
  std::map<std::string, std::string> module_code;  // what texture nodes need once per module
  // The arrays' lengths: the longest stack's or part's, the most parts and the longest blend.
  size_t stack_length = 1, parts_length = 1, blend_length = 1;
  for (const Program& p : programs) {
    stack_length = std::max(stack_length, size_t(unrolled_entries(p)));
    if (!evaluates_by_parts(p)) continue;
    const StackBlend blend = split_blend(p, true);
    parts_length = std::max(parts_length, blend.parts.size());
    blend_length = std::max(blend_length, blend.entries.size());
  }
  for (const Program& p : programs) {
    module.materials.emplace_back();
    MaterialEmitter emitter(p, options, module.materials.back(), module_code);
    emitter.stack_length_ = stack_length;
    emitter.parts_length_ = parts_length;
    emitter.blend_length_ = blend_length;
    bodies.push_back(emitter.emit());
    if (!prefixes.insert(module.materials.back().prefix).second)
      throw std::invalid_argument("GLSL back end: materials '" + p.name + "' and another give the same GLSL prefix " +
                                  module.materials.back().prefix);
  }
  std::ostringstream s;
  s << version_line(options.target) << "\n";
  std::string code;  // everything after the kernels: what decides which kernels are needed
  for (const auto& [name, text] : module_code) code += text;
  for (const std::string& body : bodies) code += body;
  if (options.shader == Options::Shader::Sphere) code += sphere_shader(module.materials.front().prefix);
  if (options.shader == Options::Shader::Plane) code += plane_shader(module.materials.front().prefix);
  // A thin film's Fresnel term only in a module with a film (film.glsl, lamina_fresnel_base), and
  // apart for coated flakes (flakes.glsl, lamina_flake_optics): a module whose only film coats its
  // flakes keeps its conductors' Fresnel terms free of the film's kernel (a random stack's
  // conductor under a layer took it at each of its many Fresnel terms: 52 s of llvmpipe's
  // compiling instead of 24).
  bool films = false, flake_films = false;
  for (const Program& p : programs)
    for (const StackEntry& e : p.stack) {
      const bool film = kernels::lamina_is_film(e.fresnel);
      films = films || (film && e.model != kernels::LAMINA_SUBSTRATE_FLAKE_PAINT);
      flake_films = flake_films || (film && e.model == kernels::LAMINA_SUBSTRATE_FLAKE_PAINT);
    }
  const std::string film_macro =
      std::string(films ? "#define LAMINA_FILM_FRESNEL lamina_fresnel_film\n"
                        : "#define LAMINA_FILM_FRESNEL(mode, cos_i, film_eta, eta, k, depth) vec3(1.0)\n") +
      (flake_films ? "#define LAMINA_FLAKE_FILM lamina_fresnel_film\n"
                   : "#define LAMINA_FLAKE_FILM(mode, cos_i, film_eta, eta, k, depth) vec3(1.0)\n");
  // A fluorescent base's light of a colour only in a module with one (stack.glsl, lamina_stack_glows).
  bool fluorescence = false;
  for (const Program& p : programs)
    for (const StackEntry& e : p.stack)
      fluorescence =
          fluorescence || (e.kind == kernels::LAMINA_SUBSTRATE && e.model == kernels::LAMINA_SUBSTRATE_FLUORESCENT);
  const std::string macros = film_macro + "#define LAMINA_FLUORESCENCE " + (fluorescence ? "true" : "false") + "\n";
  const std::string kernels = needed_kernels(kernel_sources(), macros + code);
  std::string table;
  if (kernels.find("lamina_albedo_texel") != std::string::npos) table = albedo_table(programs, module);
  s << header(programs, module, options) << "\n";
  if (options.target == Target::Es300)
    s << "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp usampler2D;\n";
  // The arrays of the kernels' composition hold the largest material's stack (or part), those of a
  // blend the most parts and the longest blend; a point (LaminaPoint) holds them.
  s << "#define LAMINA_STACK " << stack_length << "\n#define LAMINA_PARTS " << parts_length << "\n#define LAMINA_BLEND "
    << blend_length << "\n"
    << macros << "\n";
  s << table << kernels;
  s << code;
  module.source = s.str();
  return module;
}

}  // namespace lamina::glsl
