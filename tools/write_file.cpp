#include <fstream>
#include <iostream>

#include "tools/commands.h"

namespace lamina::cli {

namespace fs = std::filesystem;

namespace {

void remove_each(const std::vector<fs::path>& paths) {
  std::error_code ec;
  for (const fs::path& p : paths) fs::remove(p, ec);
}

}  // namespace

bool write_files(const std::vector<OutputFile>& files) {
  // Every text goes to a temporary file beside its destination first: a failure there leaves the
  // destinations as they were.
  std::vector<fs::path> temporaries;
  for (const OutputFile& f : files) {
    fs::path temporary = f.path;
    temporary += ".tmp";
    temporaries.push_back(temporary);
    std::ofstream out(temporary, std::ios::binary);
    if (!(out << f.text) || !out.flush()) {
      std::cerr << "lamina: cannot write " << f.path.string() << "\n";
      out.close();
      remove_each(temporaries);
      return false;
    }
  }
  // Then the renames, in order; a failing one takes back those before it.
  std::vector<fs::path> renamed;
  for (size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    fs::rename(temporaries[i], files[i].path, ec);
    if (ec) {
      std::cerr << "lamina: cannot write " << files[i].path.string() << ": " << ec.message() << "\n";
      remove_each(renamed);
      remove_each(std::vector<fs::path>(temporaries.begin() + std::ptrdiff_t(i), temporaries.end()));
      return false;
    }
    renamed.push_back(files[i].path);
  }
  return true;
}

bool write_file(const fs::path& path, const std::string& text) { return write_files({{path, text}}); }

}  // namespace lamina::cli
