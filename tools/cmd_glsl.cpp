// lamina glsl FILE [--material NAME] [--model NAME] [--target 330|450|es300] [--uniforms]
//             [--shader sphere|plane] [--interface FILE] -o OUT
// The material(s) as one GLSL module (graph/glsl/generator.h), plus a JSON side file describing
// the uniform blocks, samplers and tables: with --uniforms, or when a material's model reads a
// table, it is OUT with its extension replaced by .uniforms.json (car.glsl -> car.uniforms.json),
// or --interface FILE names it.
#include <algorithm>
#include <iostream>
#include <vector>

#include "graph/glsl/generator.h"
#include "graph/stack_size.h"
#include "tools/commands.h"
#include "tools/material_arg.h"

namespace lamina::cli {

namespace {

namespace fs = std::filesystem;

struct GlslOptions {
  MaterialArg material;
  std::string target = "330";
  bool uniforms = false;
  std::string shader;
  std::string output;
  std::string interface_file;
};

// The side file's default place: OUT with its extension replaced, car.glsl -> car.uniforms.json
// (an OUT without an extension gets one: car -> car.uniforms.json).
fs::path default_side_file(const std::string& output) { return fs::path(output).replace_extension(".uniforms.json"); }

// What makes the module's loops stay loops in GLSL compilers (graph/limits.h,
// kGlslUnrolledEntries): a part longer than they unroll (glsl::unrolled_entries), and a stack
// evaluated whole but shorter than the module's arrays (the longest stack or part), as Mesa forces
// a loop open only when its trip count is the length of the array it indexes (a stack evaluated by
// parts loops over its parts anyway). indices[i]: program i's material in the file.
void warn_about_unrolling(const std::string& file, const std::vector<Program>& programs,
                          const std::vector<size_t>& indices) {
  int longest = 0;
  for (const Program& p : programs) longest = std::max(longest, glsl::unrolled_entries(p));
  Diagnostics advice;
  for (size_t i = 0; i < programs.size(); ++i) {
    const std::string material = "/materials/" + std::to_string(indices[i]);
    warn_glsl_unrolling(glsl::unrolled_entries(programs[i]), file, material, advice);
    if (!glsl::evaluates_by_parts(programs[i]) && int(programs[i].stack.size()) < longest)
      advice.warning(file, material + "/surface",
                     "the stack compiles to " + std::to_string(programs[i].stack.size()) +
                         " entries in a module whose longest has " + std::to_string(longest) +
                         ": GLSL compilers unroll the composition's loops only for the longest, and this material's "
                         "stay loops (Aventurine glass compiled 11 times slower so on llvmpipe)",
                     "generate a module per material (--material NAME)");
  }
  print_diagnostics(advice);
}

int run_glsl(const GlslOptions& o) {
  glsl::Options options;
  // The generator's table of targets is the only list of them: no second one in the parser.
  if (!glsl::parse_target(o.target, options.target)) {
    print_problem("glsl: --target: '" + o.target + "' is not a target (330, 450 or es300)");
    return kExitInvalid;
  }
  const bool to_stdout = o.output == "-";
  options.uniforms = o.uniforms;
  options.shader = o.shader == "sphere"  ? glsl::Options::Shader::Sphere
                   : o.shader == "plane" ? glsl::Options::Shader::Plane
                                         : glsl::Options::Shader::None;
  std::vector<Program> programs;
  std::vector<size_t> indices;
  if (int code = load_programs(o.material, true, programs, &indices); code != kExitOk) return code;
  warn_about_unrolling(o.material.file, programs, indices);
  glsl::Module module;
  try {
    module = glsl::generate(programs, options);
  } catch (const std::invalid_argument& e) {
    print_problem(o.material.file + ": " + e.what());
    return kExitInvalid;
  }

  // The side file: named by --interface, or next to OUT when the host needs it (the uniform
  // blocks' layout, a table's texels).
  const bool needs_side = o.uniforms || !module.tables.empty();
  fs::path side;
  if (!o.interface_file.empty())
    side = o.interface_file;
  else if (needs_side && !to_stdout)
    side = default_side_file(o.output);
  if (needs_side && side.empty()) {
    print_problem(
        "glsl: " + o.material.file + ": with -o -, " +
        (o.uniforms ? std::string("--uniforms") : "the dielectric albedo table the energy_conserving model reads") +
        " needs --interface FILE for the JSON side file the host binds from (the module goes to standard "
        "output)" +
        (o.uniforms ? "" : "; the weidlich_wilkie model (--model weidlich_wilkie) reads no table"));
    return kExitInvalid;
  }
  if (!side.empty() && !to_stdout && side.lexically_normal() == fs::path(o.output).lexically_normal()) {
    print_problem("glsl: --interface names the GLSL output " + o.output + "; give the side file its own name");
    return kExitInvalid;
  }

  std::vector<OutputFile> files;
  if (!to_stdout) files.push_back({o.output, module.source});
  if (!side.empty()) files.push_back({side, glsl::interface_json(module, options)});
  if (int code = write_outputs(files); code != kExitOk) return code;
  if (to_stdout) write_standard_output(module.source);
  return kExitOk;
}

}  // namespace

void add_glsl(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<GlslOptions>();
  auto* cmd = app.add_subcommand("glsl", "Compile materials to a GLSL module (eval, pdf and sample per material)");
  cmd->add_option("file", o->material.file, "a material file")->required();
  cmd->add_option("-m,--material", o->material.material, "only this material (default: every material in the file)");
  add_model_option(*cmd, o->material);
  add_input_options(*cmd, o->material.input_options);
  cmd->add_option("-t,--target", o->target, "GLSL flavour: 330 (3.30 core), 450 (4.50 core), es300 (ES 3.00, WebGL2)")
      ->capture_default_str();
  cmd->add_flag("--uniforms", o->uniforms,
                "keep constant parameters in a std140 uniform block per material for live editing, and write the "
                "block layout to a JSON side file: OUT with its extension replaced by .uniforms.json (car.glsl -> "
                "car.uniforms.json), or --interface FILE");
  cmd->add_option("--shader", o->shader,
                  "append a ready-to-use fragment shader: sphere (an analytic lit sphere, as lamina plot draws it) "
                  "or plane (a ground plane receding to the horizon, textures filtered over each pixel's footprint)")
      ->check(CLI::IsMember({"sphere", "plane"}));
  cmd->add_option("-o,--output", o->output, "the GLSL file to write, - for standard output")->required();
  cmd->add_option("--interface", o->interface_file,
                  "write the JSON side file (uniform blocks, samplers, tables) here, with or without --uniforms; "
                  "needed with -o - for --uniforms or a module that reads a table");
  cmd->footer(
      "Nothing is written when the file is invalid, and the module and its side file are written together or not "
      "at all. Energy-conserving materials read a table the host binds as a texture: its texels are in the side "
      "file, written next to OUT unless --interface names it. With several materials and --shader, the sphere or plane "
      "shows the first one.");
  cmd->callback([o, &runner] { runner = [o] { return run_glsl(*o); }; });
}

}  // namespace lamina::cli
