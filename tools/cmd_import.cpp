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
  InputOptions input_options;
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
    result = gltf::import_gltf(o.input, diagnostics, o.input_options.policy_for(o.input));
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  }
  if (!print_diagnostics(diagnostics)) return kExitInvalid;

  // Refuse to replace files unless asked; a texture identical to the one there is no conflict.
  const std::filesystem::path directory = output.parent_path().empty() ? "." : output.parent_path();
  std::error_code ec;
  if (!o.force) {
    std::vector<std::string> existing;
    if (std::filesystem::exists(output, ec)) existing.push_back(output.string());
    for (const auto& t : result.textures)
      if (std::filesystem::exists(directory / t.file_name, ec) && !same_bytes(directory / t.file_name, t.bytes))
        existing.push_back((directory / t.file_name).string());
    if (!existing.empty()) {
      for (const auto& f : existing) print_problem(f + " exists; use --force to replace it");
      return kExitInvalid;
    }
  }
  // A missing output folder is made now, the input checked; taken back if the write fails.
  std::filesystem::path made;  // the outermost folder made
  for (std::filesystem::path p = directory; !p.empty() && !std::filesystem::exists(p, ec); p = p.parent_path()) {
    made = p;
    if (p == p.parent_path()) break;
  }
  if (!made.empty() && !std::filesystem::create_directories(directory, ec)) {
    print_problem("cannot write " + o.output + ": cannot make the folder " + directory.string() + ": " + ec.message());
    return kExitIo;
  }
  // The textures first, so that the material file never names one that is not there; all of them
  // together or none.
  // A texture already there with the same bytes (importing next to the glTF file's own images)
  // is left as it is.
  std::vector<OutputFile> files;
  for (const auto& t : result.textures)
    if (!same_bytes(directory / t.file_name, t.bytes))
      files.push_back({directory / t.file_name, std::string(t.bytes.begin(), t.bytes.end())});
  files.push_back({output, write_document(result.document)});
  if (int code = write_outputs(files); code != kExitOk) {
    // Only the folders this call made, and only if they are empty (remove() leaves others alone).
    for (std::filesystem::path p = directory; !made.empty(); p = p.parent_path()) {
      std::filesystem::remove(p, ec);
      if (p == made || p == p.parent_path()) break;
    }
    return code;
  }

  for (const auto& note : result.notes) std::cout << "note: " << printable(note) << "\n";
  const size_t m = result.document.materials.size(), t = result.textures.size(), w = diagnostics.warnings().size();
  std::cout << printable(o.output) << ": " << m << " material" << (m == 1 ? "" : "s") << ", " << t << " texture"
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
  add_input_options(*cmd, o->input_options);
  cmd->footer(
      "Materials with LAMINA_materials_layered come back exactly; others are approximated from core "
      "metallic-roughness, KHR_materials_ior, _specular and _clearcoat (the approximations are printed as notes); "
      "object labels that lamina gltf added are left out. Exit 0 written, 2 invalid glTF, no material to import or "
      "existing output (nothing written), 1 I/O error.");
  cmd->callback([o, &runner] { runner = [o] { return run_import(*o); }; });
}

}  // namespace lamina::cli
