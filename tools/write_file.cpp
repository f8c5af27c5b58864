#include <fstream>
#include <iostream>

#include "tools/commands.h"

namespace lamina::cli {

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

}  // namespace lamina::cli
