// lamina glsl FILE [--material NAME] [--target 330|450|es300] [--uniforms] [--shader sphere] -o OUT:
// the material(s) as one GLSL module (graph/glsl/generator.h), plus with --uniforms a JSON side
// file describing the uniform blocks.
#include <iostream>

#include "graph/glsl/generator.h"
#include "tools/commands.h"
#include "tools/material_arg.h"

namespace lamina::cli {

namespace {

struct GlslOptions {
  MaterialArg material;
  std::string target = "330";
  bool uniforms = false;
  std::string shader;
  std::string output;
  std::string interface_file;
};

// OUT with its extension replaced: shader.glsl -> shader.uniforms.json.
std::filesystem::path side_file(const std::string& output) {
  std::filesystem::path path(output);
  return path.replace_extension(".uniforms.json");
}

int run_glsl(const GlslOptions& o) {
  glsl::Options options;
  if (!glsl::parse_target(o.target, options.target)) {
    std::cerr << "lamina: --target: '" << o.target << "' is not a target (330, 450 or es300)\n";
    return kExitInvalid;
  }
  options.uniforms = o.uniforms;
  options.sphere_shader = o.shader == "sphere";
  std::vector<Program> programs;
  if (int code = load_programs(o.material, true, programs); code != kExitOk) return code;
  glsl::Module module;
  try {
    module = glsl::generate(programs, options);
  } catch (const std::invalid_argument& e) {
    std::cerr << "lamina: " << o.material.file << ": " << e.what() << "\n";
    return kExitInvalid;
  }
  if (o.output == "-") {
    std::cout << module.source;
  } else if (!write_file(o.output, module.source)) {
    return kExitIo;
  }
  if (o.uniforms || !o.interface_file.empty()) {
    std::filesystem::path side =
        o.interface_file.empty() ? side_file(o.output) : std::filesystem::path(o.interface_file);
    if (o.output == "-" && o.interface_file.empty()) return kExitOk;  // nowhere to put it: stdout holds the module
    if (!write_file(side, glsl::interface_json(module, options))) return kExitIo;
  }
  return kExitOk;
}

}  // namespace

void add_glsl(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<GlslOptions>();
  auto* cmd = app.add_subcommand("glsl", "Compile materials to a GLSL module (eval, pdf and sample per material)");
  cmd->add_option("file", o->material.file, "a material file")->required();
  cmd->add_option("-m,--material", o->material.material, "only this material (default: every material in the file)");
  cmd->add_option("-t,--target", o->target, "GLSL flavour: 330 (3.30 core), 450 (4.50 core), es300 (ES 3.00, WebGL2)")
      ->check(CLI::IsMember({"330", "450", "es300"}))
      ->capture_default_str();
  cmd->add_flag("--uniforms", o->uniforms,
                "keep constant parameters in a std140 uniform block per material for live editing, and write the "
                "block layout to OUT's .uniforms.json side file");
  cmd->add_option("--shader", o->shader, "append a ready-to-use fragment shader: sphere (an analytic lit sphere)")
      ->check(CLI::IsMember({"sphere"}));
  cmd->add_option("-o,--output", o->output, "the GLSL file to write, - for standard output")->required();
  cmd->add_option("--interface", o->interface_file,
                  "where to write the JSON side file (uniform blocks and samplers); default OUT.uniforms.json with "
                  "--uniforms");
  cmd->footer(
      "Nothing is written when the file is invalid. With several materials and --shader sphere, the sphere shows "
      "the first one.");
  cmd->callback([o, &runner] { runner = [o] { return run_glsl(*o); }; });
}

}  // namespace lamina::cli
