// A libFuzzer program for the target named by LAMINA_FUZZ_TARGET (tests/fuzz/CMakeLists.txt builds
// one per target). JSON targets mutate by structure most of the time (json_mutator.h) and by bytes
// otherwise, so that both the checker's semantics and the parser's syntax handling get exercised.
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_targets.h"
#include "json_mutator.h"

namespace {

const lamina::fuzz::Target& target() {
  static const lamina::fuzz::Target* const t = lamina::fuzz::find_target(LAMINA_FUZZ_TARGET);
  return *t;
}

}  // namespace

// The target's dictionary (tests/fuzz/dictionaries) joins the command line unless one is given.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  if (target().dictionary.empty()) return 0;
  for (int i = 1; i < *argc; ++i)
    if (std::string_view((*argv)[i]).rfind("-dict=", 0) == 0) return 0;
  static std::string option =
      std::string("-dict=") + LAMINA_SOURCE_DIR + "/tests/fuzz/dictionaries/" + target().dictionary;
  static std::vector<char*> arguments((*argv), (*argv) + *argc);
  arguments.insert(arguments.begin() + 1, option.data());
  arguments.push_back(nullptr);
  *argc += 1;
  *argv = arguments.data();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A Finding or any other exception escapes: libFuzzer reports the abort and keeps the input.
  target().run(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  std::mt19937 rng(seed);
  const lamina::fuzz::Vocabulary* vocabulary = lamina::fuzz::vocabulary_for(target().name);
  // Targets with a vocabulary (the JSON ones): three times in four by structure; the rest (and
  // whatever does not parse) byte by byte.
  if (vocabulary && rng() % 4 != 0) {
    std::string text(reinterpret_cast<const char*>(data), size);
    if (lamina::fuzz::mutate_json(text, *vocabulary, rng, max_size)) {
      std::memcpy(data, text.data(), text.size());
      return text.size();
    }
  }
  return LLVMFuzzerMutate(data, size, max_size);
}
