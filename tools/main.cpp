#include <iostream>

#include "tools/commands.h"

int main(int argc, char** argv) {
  using namespace lamina::cli;
  CLI::App app{"lamina: physically plausible layered materials", "lamina"};
  app.set_version_flag("--version", std::string("lamina ") + LAMINA_VERSION);
  app.require_subcommand(1);
  Runner runner;
  add_validate(app, runner);
  add_classify(app, runner);
  add_nodes(app, runner);
  add_schema(app, runner);
  add_eval(app, runner);
  add_albedo(app, runner);
  add_plot(app, runner);
  add_glsl(app, runner);
  add_gltf(app, runner);
  add_import(app, runner);
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
  try {
    return runner ? runner() : kExitInvalid;
  } catch (const std::exception& e) {
    std::cerr << "lamina: internal error: " << e.what() << "\n";
    return kExitIo;
  }
}
