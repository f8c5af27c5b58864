// A deterministic fuzz pass: damaged versions of every example must give diagnostics, never a
// crash, and a damaged file the reader accepts must still write and read back exactly. Under the
// ASan+UBSan build this also checks memory safety of the reader and checker.
#include <doctest/doctest.h>

#include <random>

#include "graph/json_write.h"
#include "graph/load.h"
#include "test_support.h"

using namespace lamina;

namespace {

std::string mutate(std::string text, std::mt19937& rng) {
  static const std::string pieces[] = {"{",   "}",         "[",         "]",          ",",       ":",
                                       "\"",  "@",         "-1",        "1e999",      "null",    "true",
                                       "0.5", "\"@coat\"", "\"layer\"", "[0.5, 0.5]", "\\u0000", "\xff"};
  std::uniform_int_distribution<int> action(0, 3);
  int edits = std::uniform_int_distribution<int>(1, 4)(rng);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    std::uniform_int_distribution<size_t> at(0, text.size() - 1);
    const std::string& piece = pieces[std::uniform_int_distribution<size_t>(0, std::size(pieces) - 1)(rng)];
    switch (action(rng)) {
      case 0: text.erase(at(rng), std::uniform_int_distribution<size_t>(1, 8)(rng)); break;
      case 1: text.insert(at(rng), piece); break;
      case 2: text[at(rng)] = static_cast<char>(std::uniform_int_distribution<int>(32, 126)(rng)); break;
      default: text = text.substr(0, at(rng)); break;
    }
  }
  return text;
}

}  // namespace

TEST_CASE("damaged example files give diagnostics and never crash") {
  std::mt19937 rng(20261122);
  size_t rejected = 0, total = 0;
  for (const auto& file : test::example_files()) {
    std::string original = test::read_file(file);
    for (int i = 0; i < 150; ++i) {
      std::string text = mutate(original, rng);
      CheckedFile checked = check_text(text, file.string());
      ++total;
      if (!checked.ok()) {
        ++rejected;
        for (const auto& d : checked.diagnostics.errors()) {
          CHECK_FALSE(d.message.empty());
          CHECK((d.pointer.empty() || d.pointer[0] == '/'));
        }
        continue;
      }
      Diagnostics again;
      std::string written = write_document(checked.document);
      CHECK(read_document(written, file.string(), again).same_content(checked.document));
      CHECK(again.ok());
    }
  }
  // Most damage must be caught; a few edits (inside notes, say) leave a valid file.
  CHECK(rejected > total / 2);
}
