#include <embree3/rtcore_config.h>

#include <csignal>
#include <iostream>
#include <nlohmann/json.hpp>

#include "graph/diagnostics.h"
#include "graph/file_access.h"
#include "graph/image_codec.h"
#include "tools/commands.h"

namespace {

// What --version prints: lamina's version and the libraries this build was compiled against, with
// OpenImageIO as the image module runs it (loaded for this alone: no other command pays for it).
std::string version_text() {
  std::string oiio;
  try {
    oiio = "OpenImageIO " + lamina::image_codec().version();
  } catch (const lamina::IoError& e) {
    oiio = std::string("no OpenImageIO: ") + e.what();
  }
  return std::string("lamina ") + LAMINA_VERSION + "\nbuilt with Embree " RTC_VERSION_STRING ", " + oiio +
         ", nlohmann-json " + std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
         std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." + std::to_string(NLOHMANN_JSON_VERSION_PATCH) +
         ", CLI11 " CLI11_VERSION;
}

// CLI11 reports a word that names no command as "A subcommand is required"; name it instead,
// with the closest command.
bool unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  std::string word = argv[1];
  if (std::find(names.begin(), names.end(), word) != names.end()) return false;
  std::string hint = lamina::closest_match(word, names);
  lamina::cli::print_problem("unknown command '" + word + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
  std::cerr << "commands:";
  for (const auto& n : names) std::cerr << " " << n;
  std::cerr << "\nRun lamina --help for more information.\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lamina::cli;
  // A file size limit (ulimit -f) makes writes fail with EFBIG, reported like any write error,
  // rather than kill the process half way through an output.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"lamina: physically plausible layered materials", "lamina"};
  app.set_version_flag("--version", version_text);
  app.require_subcommand(1);
  Runner runner;
  add_validate(app, runner);
  add_classify(app, runner);
  add_nodes(app, runner);
  add_schema(app, runner);
  add_eval(app, runner);
  add_albedo(app, runner);
  add_reference(app, runner);
  add_compare(app, runner);
  add_plot(app, runner);
  add_glsl(app, runner);
  add_gltf(app, runner);
  add_import(app, runner);
  add_render(app, runner);
  add_preview(app, runner);
  if (unknown_command(app, argc, argv)) return kExitInvalid;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitInvalid;  // a wrong command line is a user mistake
  }
  int code = kExitInvalid;
  try {
    if (runner) code = runner();
  } catch (const std::exception& e) {
    print_problem(std::string("internal error: ") + e.what());
    code = kExitIo;
  }
  // What was printed must have arrived: a full disk or a closed pipe is an I/O error.
  if (const int output = finish_standard_output(); output != kExitOk && code == kExitOk) code = output;
  return code;
}
