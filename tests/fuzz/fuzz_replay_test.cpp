// The fuzz targets in the ordinary test suite: every seed and every input that ever failed
// (tests/fuzz/regressions/<target>/) passes through its target without a finding, in every build;
// the dictionaries say what the registry says; the mutator makes inputs that get past the parser.
#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fuzz_targets.h"
#include "graph/load.h"
#include "json_mutator.h"
#include "test_support.h"

using namespace lamina;
namespace fs = std::filesystem;

namespace {

fs::path fuzz_dir() { return test::source_dir() / "tests" / "fuzz"; }

std::vector<fs::path> regression_files(const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fuzz_dir() / "regressions" / target;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Runs `input` through the target; a finding or an escaping exception fails with the file's name.
void replay(const fuzz::Target& target, const fs::path& file) {
  const std::string input = test::read_file(file);
  std::string failure;
  try {
    target.run(input);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  INFO(target.name << " on " << file.string() << ": " << failure);
  CHECK(failure.empty());
}

std::set<std::string> split_list(const std::string& list) {
  std::set<std::string> names;
  std::istringstream in(list);
  for (std::string name; std::getline(in, name, ',');) names.insert(name);
  return names;
}

}  // namespace

TEST_CASE("every fuzz target the build makes is one the test suite replays, and each has seeds") {
  std::set<std::string> names;
  for (const auto& t : fuzz::targets()) {
    names.insert(t.name);
    INFO(t.name);
    CHECK(!fuzz::seed_files(test::source_dir(), t.name).empty());
    if (!t.dictionary.empty()) CHECK(fs::is_regular_file(fuzz_dir() / "dictionaries" / t.dictionary));
  }
  CHECK(names == split_list(LAMINA_FUZZ_TARGET_NAMES));
}

TEST_CASE("the seed corpora pass through their fuzz targets without a finding") {
  for (const auto& t : fuzz::targets())
    for (const auto& file : fuzz::seed_files(test::source_dir(), t.name)) replay(t, file);
}

TEST_CASE("every input the fuzzers ever failed on passes through its target now") {
  for (const auto& t : fuzz::targets())
    for (const auto& file : regression_files(t.name)) replay(t, file);
  // A folder named after no target would never be replayed.
  if (fs::is_directory(fuzz_dir() / "regressions"))
    for (const auto& e : fs::directory_iterator(fuzz_dir() / "regressions")) {
      INFO(e.path().string());
      CHECK(fuzz::find_target(e.path().filename().string()) != nullptr);
    }
}

TEST_CASE("the fuzz dictionaries hold exactly the words of lamina's registry and field tables") {
  // LAMINA_UPDATE_FUZZ_DICTIONARIES=1 rewrites them after a node type or field was added.
  const bool update = std::getenv("LAMINA_UPDATE_FUZZ_DICTIONARIES") != nullptr;
  std::set<std::string> checked;
  for (const auto& t : fuzz::targets()) {
    const fuzz::Vocabulary* vocabulary = fuzz::vocabulary_for(t.name);
    if (t.dictionary.empty() || !vocabulary || !checked.insert(t.dictionary).second) continue;
    const fs::path file = fuzz_dir() / "dictionaries" / t.dictionary;
    const std::string expected = "# " + t.dictionary + ": written by the test suite from lamina's own tables (" +
                                 "LAMINA_UPDATE_FUZZ_DICTIONARIES=1 lamina_tests -tc='the fuzz dictionaries*').\n" +
                                 fuzz::dictionary_text(*vocabulary);
    if (update) {
      std::ofstream(file, std::ios::binary) << expected;
      continue;
    }
    INFO(file.string() << " is out of date: rerun with LAMINA_UPDATE_FUZZ_DICTIONARIES=1");
    CHECK(fs::is_regular_file(file));
    if (fs::is_regular_file(file)) CHECK(test::read_file(file) == expected);
  }
}

TEST_CASE("the structure-aware mutator turns examples into different material files that still parse") {
  const fuzz::Vocabulary& vocabulary = *fuzz::vocabulary_for("material");
  std::mt19937 rng(20261124);
  size_t mutants = 0, parsed = 0, valid = 0, changed = 0;
  for (const auto& file : test::example_files()) {
    const std::string original = test::read_file(file);
    for (int i = 0; i < 40; ++i) {
      std::string text = original;
      REQUIRE(fuzz::mutate_json(text, vocabulary, rng, 1 << 20));
      ++mutants;
      changed += text != original;
      parsed += nlohmann::json::accept(text);
      valid += check_text(text, file.string(), test::repository_policy()).ok();
    }
  }
  // Tree edits never break the syntax; most make a difference, and many reach the checker's
  // semantics while some still pass it.
  CHECK(parsed == mutants);
  CHECK(changed > mutants * 9 / 10);
  CHECK(valid > 0);
  CHECK(valid < mutants);
}

TEST_CASE("the mutator keeps a GLB a well-formed container while it changes the JSON chunk") {
  const std::string glb = test::read_file(test::source_dir() / "tests/data/gltf/base_color_texture.glb");
  const fuzz::Vocabulary& vocabulary = *fuzz::vocabulary_for("gltf_import");
  std::mt19937 rng(7);
  for (int i = 0; i < 50; ++i) {
    std::string text = glb;
    REQUIRE(fuzz::mutate_json(text, vocabulary, rng, 1 << 20));
    REQUIRE(text.size() >= 20);
    std::uint32_t total = 0, json = 0;
    std::memcpy(&total, text.data() + 8, 4);
    std::memcpy(&json, text.data() + 12, 4);
    CHECK(text.compare(0, 4, "glTF") == 0);
    CHECK(total == text.size());
    CHECK(json % 4 == 0);
  }
}

TEST_CASE("the mutator declines what it cannot parse and what would exceed the size it is given") {
  const fuzz::Vocabulary& vocabulary = *fuzz::vocabulary_for("material");
  std::mt19937 rng(1);
  std::string broken = "{\"format\": 1, \"materials\": [";
  CHECK_FALSE(fuzz::mutate_json(broken, vocabulary, rng, 1 << 20));
  CHECK(broken == "{\"format\": 1, \"materials\": [");
  std::string deep = std::string(200, '[') + std::string(200, ']');
  CHECK_FALSE(fuzz::mutate_json(deep, vocabulary, rng, 1 << 20));
  std::string small = test::read_file(test::example_files().front());
  CHECK_FALSE(fuzz::mutate_json(small, vocabulary, rng, 8));
}
