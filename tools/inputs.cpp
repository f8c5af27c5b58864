#include <algorithm>
#include <iostream>

#include "graph/json_read.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

// An I/O problem outranks an invalid input, as in for_each_checked_file.
void raise_code(int& code, int problem) {
  if (code != kExitIo) code = problem;
}

}  // namespace

void print_problem(std::string_view text) { std::cerr << "lamina: " << printable(text) << "\n"; }

AssetPolicy InputOptions::policy_for(const std::filesystem::path& file, const std::filesystem::path& directory) const {
  AssetPolicy policy;
  policy.max_image_pixels = max_image_pixels;
  for (const auto& root : asset_roots) policy.roots.emplace_back(root);
  if (policy.roots.empty() && !directory.empty()) policy.roots.push_back(directory);
  return policy.with_default_root(file);
}

void add_input_options(CLI::App& cmd, InputOptions& options) {
  cmd.add_option("--asset-root", options.asset_roots,
                 "a folder that files named by the input (textures, material files, meshes) may come from; "
                 "repeatable (default: the input file's folder, or the directory given)")
      ->check(CLI::ExistingDirectory);
  cmd.add_option("--max-image-pixels", options.max_image_pixels,
                 "largest image (width x height) to decode; larger ones are refused before decoding")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40))
      ->capture_default_str();
}

bool print_diagnostics(const Diagnostics& diagnostics) {
  for (const auto& d : diagnostics.errors()) std::cerr << format(d) << "\n";
  for (const auto& d : diagnostics.warnings()) std::cerr << format(d) << "\n";
  return diagnostics.ok();
}

Inputs expand_inputs(const std::vector<std::string>& inputs) {
  Inputs out;
  for (const auto& input : inputs) {
    std::filesystem::path path(input);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path, ec))
        if (entry.is_regular_file() && entry.path().extension() == ".json") found.push_back(entry.path());
      if (ec) {
        print_problem(input + ": cannot list directory: " + ec.message());
        raise_code(out.code, kExitIo);
      } else if (found.empty()) {
        print_problem(input + ": no .json file in this directory, nothing to check");
        raise_code(out.code, kExitInvalid);
      }
      std::sort(found.begin(), found.end());
      out.files.insert(out.files.end(), found.begin(), found.end());
      out.directories.insert(out.directories.end(), found.size(), path);
    } else if (std::filesystem::exists(path, ec)) {
      out.files.push_back(path);
      out.directories.emplace_back();
    } else {
      print_problem(input + ": no such file or directory");
      raise_code(out.code, kExitIo);
    }
  }
  return out;
}

void add_sheet_columns_option(CLI::App& cmd, int& columns) {
  cmd.add_option("--columns", columns, "spheres per row of a material file's sample sheet")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
}

int read_scene_input(const std::string& input, const InputOptions& options, int columns, Scene& scene,
                     Diagnostics& diagnostics) {
  try {
    const std::filesystem::path path(input);
    const AssetPolicy policy = options.policy_for(path);
    std::string text;
    try {
      text = read_input_file(path, kMaxJsonFileBytes);
    } catch (const Error& e) {  // too large
      for (const auto& d : e.diagnostics()) diagnostics.error(d.file, d.pointer, d.message, d.hint);
    }
    if (!diagnostics.ok()) {
    } else if (looks_like_scene(text)) {
      scene = read_scene(text, path.string(), diagnostics, policy);
    } else {
      CheckedFile checked = check_text(text, path.string(), policy);
      diagnostics = checked.diagnostics;
      if (checked.ok()) scene = sample_sheet(checked.document, path, columns);
    }
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  }
  return kExitOk;
}

int for_each_checked_file(const std::vector<std::string>& inputs, const InputOptions& options,
                          const std::function<bool(const std::filesystem::path&, CheckedFile&)>& visit) {
  Inputs expanded = expand_inputs(inputs);
  int code = expanded.code;
  for (size_t i = 0; i < expanded.files.size(); ++i) {
    const auto& file = expanded.files[i];
    CheckedFile checked;
    try {
      checked = check_file(file, options.policy_for(file, expanded.directories[i]));
    } catch (const IoError& e) {
      print_problem(e.what());
      code = kExitIo;
      continue;
    }
    if (!visit(file, checked) && code == kExitOk) code = kExitInvalid;
  }
  return code;
}

}  // namespace lamina::cli
