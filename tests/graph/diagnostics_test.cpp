// Messages stay short and their help costs bounded work, whatever a file holds.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "graph/diagnostics.h"

using namespace lamina;

TEST_CASE("alternatives are listed in full up to a limit, then cut with the number left out") {
  CHECK(join_alternatives({}) == "");
  CHECK(join_alternatives({"a"}) == "a");
  CHECK(join_alternatives({"a", "b", "c"}) == "a, b or c");
  std::vector<std::string> words;
  for (size_t i = 0; i < kListedAlternatives; ++i) words.push_back("w" + std::to_string(i));
  CHECK(join_alternatives(words).find(" or w" + std::to_string(kListedAlternatives - 1)) != std::string::npos);
  for (size_t i = kListedAlternatives; i < 5000; ++i) words.push_back("w" + std::to_string(i));
  const std::string cut = join_alternatives(words);
  CHECK(cut.find("w0, w1, ") == 0);
  CHECK(cut.find(", ... and " + std::to_string(5000 - (kListedAlternatives - 1)) + " more") != std::string::npos);
  CHECK(cut.find(" or ") == std::string::npos);
  CHECK(cut.size() < 300);
}

TEST_CASE("a suggestion is the closest name within a third of the word's length, else none") {
  CHECK(closest_match("varnsh", {"coat", "varnish", "tint"}) == "varnish");
  CHECK(closest_match("substrate/lamber", {"substrate/lambert", "substrate/conductor"}) == "substrate/lambert");
  CHECK(closest_match("xyz", {"coat", "varnish"}) == "");
  // A word far longer than every candidate is no candidate's typo.
  CHECK(closest_match(std::string(100000, 'a'), {"a", "aa"}) == "");
}

TEST_CASE("suggestions for one file share a budget of comparisons, so that a hostile file's search is bounded") {
  const std::vector<std::string> ids = {"alpha", "beta", "gamma", "delta"};
  Suggester few(6);
  CHECK(few.closest("gama", ids) == "gamma");  // 4 comparisons
  CHECK(few.closest("delt", ids) == "");       // the last 2: "alpha" and "beta" only
  CHECK(few.closest("alph", ids) == "");       // nothing left
  Diagnostics diagnostics;
  std::vector<std::string> many;
  for (int i = 0; i < 1000; ++i) many.push_back("node" + std::to_string(i));
  size_t suggested = 0;
  for (int i = 0; i < 1000; ++i) suggested += !diagnostics.suggest("nod" + std::to_string(i), many).empty();
  // The budget covers the first Suggester::kSuggestionComparisons / 1000 searches, and no more.
  CHECK(suggested == Suggester::kSuggestionComparisons / many.size());
}
