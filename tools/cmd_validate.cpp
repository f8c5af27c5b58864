// lamina validate FILE|DIR...: check material and scene files and print every problem.
#include <iostream>
#include <nlohmann/json.hpp>

#include "graph/load.h"
#include "graph/scene/scene.h"
#include "graph/stack_size.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct ValidateOptions {
  std::vector<std::string> inputs;
  bool json = false;
  bool quiet = false;
  bool werror = false;
  InputOptions input_options;
};

nlohmann::json to_json(const Diagnostic& d) {
  // Bytes that are not UTF-8 become U+FFFD: the report is JSON whatever the input held.
  return {{"severity", d.severity == Severity::Error ? "error" : "warning"},
          {"file", d.file},
          {"pointer", d.pointer},
          {"message", d.message},
          {"hint", d.hint}};
}

std::string plural(size_t n, const std::string& word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); }

// One checked input: a material file or a scene (with its material files' problems).
struct Checked {
  Diagnostics diagnostics;
  std::string summary;  // what the file holds, for the "ok" line
  size_t materials = 0;
};

Checked check_input(const std::filesystem::path& file, const AssetPolicy& policy) {
  Checked out;
  std::string text;
  try {
    text = read_input_file(file, kMaxJsonFileBytes);
  } catch (const Error& e) {  // too large
    for (const auto& d : e.diagnostics()) out.diagnostics.error(d.file, d.pointer, d.message, d.hint);
    return out;
  }
  if (looks_like_scene(text)) {
    Scene scene = read_scene(text, file.string(), out.diagnostics, policy);
    size_t materials = 0;
    for (const auto& f : scene.material_files) materials += f.document.materials.size();
    out.materials = materials;
    out.summary = "scene: " + plural(scene.objects.size(), "object") + ", " + plural(materials, "material") + ", " +
                  plural(scene.lights.size(), "light") + ", " + plural(scene.cameras.size(), "camera");
    return out;
  }
  CheckedFile checked = check_text(text, file.string(), policy);
  for (size_t i = 0; i < checked.graphs.size(); ++i)
    if (checked.graphs[i])
      warn_glsl_unrolling(glsl_loop_entries(measure_stack(*checked.graphs[i])), file.string(),
                          "/materials/" + std::to_string(i), checked.diagnostics);
  out.diagnostics = std::move(checked.diagnostics);
  out.materials = checked.document.materials.size();
  out.summary = plural(out.materials, "material");
  return out;
}

int run_validate(const ValidateOptions& o) {
  Inputs inputs = expand_inputs(o.inputs);
  int code = inputs.code;
  size_t files = 0, valid = 0, materials = 0, warnings = 0;
  nlohmann::json report = nlohmann::json::array();
  for (size_t i = 0; i < inputs.files.size(); ++i) {
    const auto& file = inputs.files[i];
    Checked checked;
    try {
      checked = check_input(file, o.input_options.policy_for(file, inputs.directories[i]));
    } catch (const IoError& e) {
      print_problem(e.what());
      code = kExitIo;
      continue;
    }
    ++files;
    const Diagnostics& d = checked.diagnostics;
    bool file_ok = d.ok() && !(o.werror && !d.warnings().empty());
    warnings += d.warnings().size();
    if (o.json) {
      nlohmann::json entry{{"file", file.string()}, {"valid", file_ok}, {"diagnostics", nlohmann::json::array()}};
      for (const auto& e : d.errors()) entry["diagnostics"].push_back(to_json(e));
      for (const auto& w : d.warnings()) entry["diagnostics"].push_back(to_json(w));
      report.push_back(entry);
    } else {
      print_diagnostics(d);
      if (file_ok && !o.quiet) std::cout << printable(file.string()) << ": ok (" << checked.summary << ")\n";
    }
    if (file_ok) {
      ++valid;
      materials += checked.materials;
    } else if (code == kExitOk) {
      code = kExitInvalid;
    }
  }
  if (files == 0) return code;
  if (o.json) {
    std::cout << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else if (!o.quiet) {
    std::cout << valid << " of " << files << " file" << (files == 1 ? "" : "s") << " valid, " << materials
              << " material" << (materials == 1 ? "" : "s") << ", " << warnings << " warning"
              << (warnings == 1 ? "" : "s") << "\n";
  }
  return code;
}

}  // namespace

void add_validate(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<ValidateOptions>();
  auto* cmd = app.add_subcommand("validate", "Check material and scene files; exit 0 valid, 2 invalid, 1 I/O error");
  cmd->add_option("inputs", o->inputs, "material or scene files, or directories searched for *.json")->required();
  cmd->add_flag("--json", o->json, "print a JSON report instead of 'file:pointer: message' lines");
  cmd->add_flag("-q,--quiet", o->quiet, "print only problems");
  cmd->add_flag("--warnings-as-errors", o->werror, "treat warnings (unused nodes, class mismatch) as errors");
  add_input_options(*cmd, o->input_options);
  cmd->callback([o, &runner] { runner = [o] { return run_validate(*o); }; });
}

}  // namespace lamina::cli
