// Loads a material file with liblamina, prints every problem or each material's class.
// Usage: lamina_api_example FILE.json
#include <lamina/graph/load.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " FILE.json\n";
    return 2;
  }
  try {
    lamina::CheckedFile checked = lamina::check_file(argv[1]);
    for (const auto& d : checked.diagnostics.errors()) std::cerr << lamina::format(d) << "\n";
    for (const auto& d : checked.diagnostics.warnings()) std::cerr << lamina::format(d) << "\n";
    if (!checked.ok()) return 2;
    for (size_t i = 0; i < checked.document.materials.size(); ++i) {
      lamina::Classification c = lamina::classify(*checked.graphs[i]);
      std::cout << checked.document.materials[i].name << ": " << c.letter << ") " << c.name << "\n";
    }
  } catch (const lamina::IoError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
