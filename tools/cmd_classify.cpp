// lamina classify FILE|DIR...: the course's class a)-h) of each material, with the reason.
#include <iomanip>
#include <iostream>

#include "graph/load.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct ClassifyOptions {
  std::vector<std::string> inputs;
  InputOptions input_options;
};

int run_classify(const ClassifyOptions& o) {
  size_t agree = 0, tagged = 0;
  // With several files, each file's materials follow a line naming it.
  const bool several = o.inputs.size() > 1 || std::filesystem::is_directory(o.inputs.front());
  int code =
      for_each_checked_file(o.inputs, o.input_options, [&](const std::filesystem::path& file, CheckedFile& checked) {
        if (!checked.ok()) return print_diagnostics(checked.diagnostics);
        if (several) std::cout << file.string() << ":\n";
        for (size_t i = 0; i < checked.document.materials.size(); ++i) {
          const Material& m = checked.document.materials[i];
          Classification c = classify(*checked.graphs[i]);
          std::string label = c.letter.empty() ? c.name : c.letter + ") " + c.name;
          std::string tag = "untagged";
          if (m.class_tag) {
            ++tagged;
            bool ok = std::find(c.accepted.begin(), c.accepted.end(), *m.class_tag) != c.accepted.end();
            agree += ok ? 1 : 0;
            tag = "tag " + *m.class_tag + (ok ? " agrees" : " DISAGREES");
          }
          std::cout << std::left << std::setw(24) << m.name << " " << std::setw(20) << label << " " << std::setw(16)
                    << tag << " " << c.reason << "\n";
        }
        return true;
      });
  if (tagged > 0) std::cout << agree << " of " << tagged << " class tags agree with the structure\n";
  return code;
}

}  // namespace

void add_classify(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<ClassifyOptions>();
  auto* cmd = app.add_subcommand("classify", "Print each material's course class a)-h) and the reason");
  cmd->add_option("inputs", o->inputs, "material files, or directories searched for *.json")->required();
  add_input_options(*cmd, o->input_options);
  cmd->footer(
      "Tops and bases are smooth below 5 degrees RMS slope; a varnish is tinted when it absorbs more "
      "than 1% at normal incidence.");
  cmd->callback([o, &runner] { runner = [o] { return run_classify(*o); }; });
}

}  // namespace lamina::cli
