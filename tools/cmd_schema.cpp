// lamina schema -o DIR: writes the generated JSON Schema and node reference.
#include <fstream>
#include <iostream>

#include "graph/schema.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct SchemaOptions {
  std::string out_dir;
};

// Writes through a temporary file and a rename, so that a failure never leaves half a file.
bool write_file(const std::filesystem::path& path, const std::string& text) {
  auto temporary = path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!(out << text) || !out.flush()) {
      std::cerr << "lamina: cannot write " << temporary.string() << "\n";
      std::error_code ec;
      std::filesystem::remove(temporary, ec);
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::cerr << "lamina: cannot write " << path.string() << ": " << ec.message() << "\n";
    return false;
  }
  return true;
}

int run_schema(const SchemaOptions& o) {
  std::filesystem::path dir(o.out_dir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    std::cerr << "lamina: cannot create " << dir.string() << ": " << ec.message() << "\n";
    return kExitIo;
  }
  if (!write_file(dir / "material.schema.json", material_schema())) return kExitIo;
  if (!write_file(dir / "nodes.md", node_reference_markdown())) return kExitIo;
  std::cout << "wrote " << (dir / "material.schema.json").string() << " and " << (dir / "nodes.md").string() << "\n";
  return kExitOk;
}

}  // namespace

void add_schema(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<SchemaOptions>();
  auto* cmd = app.add_subcommand("schema", "Write the material JSON Schema and the node reference to a directory");
  cmd->add_option("-o,--output", o->out_dir, "output directory (created if missing)")->required();
  cmd->callback([o, &runner] { runner = [o] { return run_schema(*o); }; });
}

}  // namespace lamina::cli
