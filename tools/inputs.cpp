#include <algorithm>
#include <iostream>

#include "graph/json_read.h"
#include "tools/commands.h"

namespace lamina::cli {

std::vector<std::filesystem::path> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::filesystem::path> files;
  for (const auto& input : inputs) {
    std::filesystem::path path(input);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path, ec))
        if (entry.is_regular_file() && entry.path().extension() == ".json") found.push_back(entry.path());
      if (ec) throw IoError(input + ": cannot list directory: " + ec.message());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (std::filesystem::exists(path, ec)) {
      files.push_back(path);
    } else {
      throw IoError(input + ": no such file or directory");
    }
  }
  return files;
}

int for_each_checked_file(const std::vector<std::string>& inputs,
                          const std::function<bool(const std::filesystem::path&, CheckedFile&)>& visit) {
  std::vector<std::filesystem::path> files;
  try {
    files = expand_inputs(inputs);
  } catch (const IoError& e) {
    std::cerr << "lamina: " << e.what() << "\n";
    return kExitIo;
  }
  int code = kExitOk;
  for (const auto& file : files) {
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
