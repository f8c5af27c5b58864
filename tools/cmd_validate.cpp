// lamina validate FILE|DIR...: check material files and print every problem.
#include <iostream>
#include <nlohmann/json.hpp>

#include "graph/load.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct ValidateOptions {
  std::vector<std::string> inputs;
  bool json = false;
  bool quiet = false;
  bool werror = false;
};

nlohmann::json to_json(const Diagnostic& d) {
  return {{"severity", d.severity == Severity::Error ? "error" : "warning"},
          {"file", d.file},
          {"pointer", d.pointer},
          {"message", d.message},
          {"hint", d.hint}};
}

int run_validate(const ValidateOptions& o) {
  size_t files = 0, valid = 0, materials = 0, warnings = 0;
  nlohmann::json report = nlohmann::json::array();
  int code = for_each_checked_file(o.inputs, [&](const std::filesystem::path& file, CheckedFile& checked) {
    ++files;
    bool file_ok = checked.ok() && !(o.werror && !checked.diagnostics.warnings().empty());
    warnings += checked.diagnostics.warnings().size();
    if (o.json) {
      nlohmann::json entry{{"file", file.string()}, {"valid", file_ok}, {"diagnostics", nlohmann::json::array()}};
      for (const auto& d : checked.diagnostics.errors()) entry["diagnostics"].push_back(to_json(d));
      for (const auto& d : checked.diagnostics.warnings()) entry["diagnostics"].push_back(to_json(d));
      report.push_back(entry);
    } else {
      for (const auto& d : checked.diagnostics.errors()) std::cerr << format(d) << "\n";
      for (const auto& d : checked.diagnostics.warnings()) std::cerr << format(d) << "\n";
      if (file_ok && !o.quiet)
        std::cout << file.string() << ": ok (" << checked.document.materials.size() << " material"
                  << (checked.document.materials.size() == 1 ? "" : "s") << ")\n";
    }
    if (file_ok) {
      ++valid;
      materials += checked.document.materials.size();
    }
    return file_ok;
  });
  if (code == kExitIo && files == 0) return code;
  if (o.json) {
    std::cout << report.dump(2) << "\n";
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
  auto* cmd = app.add_subcommand("validate", "Check material files; exit 0 valid, 2 invalid, 1 I/O error");
  cmd->add_option("inputs", o->inputs, "material files, or directories searched for *.json")->required();
  cmd->add_flag("--json", o->json, "print a JSON report instead of 'file:pointer: message' lines");
  cmd->add_flag("-q,--quiet", o->quiet, "print only problems");
  cmd->add_flag("--warnings-as-errors", o->werror, "treat warnings (unused nodes, class mismatch) as errors");
  cmd->callback([o, &runner] { runner = [o] { return run_validate(*o); }; });
}

}  // namespace lamina::cli
