// lamina schema -o DIR: writes the generated JSON Schemas (materials, scenes) and node reference.
#include <fstream>
#include <iostream>

#include "graph/schema.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct SchemaOptions {
  std::string out_dir;
};

int run_schema(const SchemaOptions& o) {
  std::filesystem::path dir(o.out_dir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    print_problem("cannot create " + dir.string() + ": " + ec.message());
    return kExitIo;
  }
  if (int code = write_outputs({{dir / "material.schema.json", material_schema()},
                                {dir / "scene.schema.json", scene_schema()},
                                {dir / "nodes.md", node_reference_markdown()}});
      code != kExitOk)
    return code;
  std::cout << "wrote " << (dir / "material.schema.json").string() << ", " << (dir / "scene.schema.json").string()
            << " and " << (dir / "nodes.md").string() << "\n";
  return kExitOk;
}

}  // namespace

void add_schema(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<SchemaOptions>();
  auto* cmd =
      app.add_subcommand("schema", "Write the material and scene JSON Schemas and the node reference to a directory");
  cmd->add_option("-o,--output", o->out_dir, "output directory (created if missing)")->required();
  cmd->callback([o, &runner] { runner = [o] { return run_schema(*o); }; });
}

}  // namespace lamina::cli
