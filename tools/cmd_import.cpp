// lamina import IN.gltf|IN.glb -o OUT.json [--force]: the glTF's materials as a lamina material
// file, with the images they use extracted next to it (graph/gltf/import.h).
#include <fstream>
#include <iostream>

#include "graph/gltf/import.h"
#include "graph/json_write.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct ImportOptions {
  std::string input;
  std::string output;
  bool force = false;
};

// Read directly, not through file_access.h: a file about to be replaced is no input.
bool same_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || std::filesystem::file_size(path, ec) != bytes.size()) return false;
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> existing(bytes.size());
  in.read(reinterpret_cast<char*>(existing.data()), static_cast<std::streamsize>(existing.size()));
  return in && existing == bytes;
}

int run_import(const ImportOptions& o) {
  const std::filesystem::path output(o.output);
  Diagnostics diagnostics;
  gltf::ImportResult result;
  try {
    result = gltf::import_gltf(o.input, diagnostics);
  } catch (const IoError& e) {
    std::cerr << "lamina: " << e.what() << "\n";
    return kExitIo;
  }
  if (!print_diagnostics(diagnostics)) return kExitInvalid;

  // Refuse to replace files unless asked; a texture identical to the one there is no conflict.
  const std::filesystem::path directory = output.parent_path().empty() ? "." : output.parent_path();
  std::error_code ec;
  // A missing output directory is made (the input checked, so nothing is written for bad input).
  if (!std::filesystem::exists(directory, ec)) std::filesystem::create_directories(directory, ec);
  if (!std::filesystem::is_directory(directory, ec)) {
    std::cerr << "lamina: cannot write " << o.output << ": " << directory.string() << " is not a directory\n";
    return kExitIo;
  }
  if (!o.force) {
    std::vector<std::string> existing;
    if (std::filesystem::exists(output, ec)) existing.push_back(output.string());
    for (const auto& t : result.textures)
      if (std::filesystem::exists(directory / t.file_name, ec) && !same_bytes(directory / t.file_name, t.bytes))
        existing.push_back((directory / t.file_name).string());
    if (!existing.empty()) {
      for (const auto& f : existing) std::cerr << "lamina: " << f << " exists; use --force to replace it\n";
      return kExitInvalid;
    }
  }
  for (const auto& t : result.textures)
    if (!write_file(directory / t.file_name, std::string(t.bytes.begin(), t.bytes.end()))) return kExitIo;
  if (!write_file(output, write_document(result.document))) return kExitIo;

  for (const auto& note : result.notes) std::cout << "note: " << note << "\n";
  const size_t m = result.document.materials.size(), t = result.textures.size(), w = diagnostics.warnings().size();
  std::cout << o.output << ": " << m << " material" << (m == 1 ? "" : "s") << ", " << t << " texture"
            << (t == 1 ? "" : "s") << " extracted, " << w << " warning" << (w == 1 ? "" : "s") << "\n";
  return kExitOk;
}

}  // namespace

void add_import(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<ImportOptions>();
  auto* cmd = app.add_subcommand("import", "Convert a glTF file's materials to a lamina material file");
  cmd->add_option("input", o->input, "a .gltf (with its buffers and images) or .glb file")->required();
  cmd->add_option("-o,--output", o->output, "the lamina material file to write; textures go next to it")->required();
  cmd->add_flag("--force", o->force, "replace OUT and textures that already exist");
  cmd->footer(
      "Materials with LAMINA_materials_layered come back exactly; others are approximated from core "
      "metallic-roughness, KHR_materials_ior, _specular and _clearcoat (the approximations are printed as notes); "
      "object labels that lamina gltf added are left out. Exit 0 written, 2 invalid glTF, no material to import or "
      "existing output (nothing written), 1 I/O error.");
  cmd->callback([o, &runner] { runner = [o] { return run_import(*o); }; });
}

}  // namespace lamina::cli
