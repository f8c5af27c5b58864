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
        std::cerr << "lamina: " << input << ": cannot list directory: " << ec.message() << "\n";
        raise_code(out.code, kExitIo);
      } else if (found.empty()) {
        std::cerr << "lamina: " << input << ": no .json file in this directory, nothing to check\n";
        raise_code(out.code, kExitInvalid);
      }
      std::sort(found.begin(), found.end());
      out.files.insert(out.files.end(), found.begin(), found.end());
    } else if (std::filesystem::exists(path, ec)) {
      out.files.push_back(path);
    } else {
      std::cerr << "lamina: " << input << ": no such file or directory\n";
      raise_code(out.code, kExitIo);
    }
  }
  return out;
}

int for_each_checked_file(const std::vector<std::string>& inputs,
                          const std::function<bool(const std::filesystem::path&, CheckedFile&)>& visit) {
  Inputs expanded = expand_inputs(inputs);
  int code = expanded.code;
  for (const auto& file : expanded.files) {
    CheckedFile checked;
    try {
      checked = check_file(file);
    } catch (const IoError& e) {
      std::cerr << "lamina: " << e.what() << "\n";
      code = kExitIo;
      continue;
    }
    if (!visit(file, checked) && code == kExitOk) code = kExitInvalid;
  }
  return code;
}

}  // namespace lamina::cli
