#include <doctest/doctest.h>

#include <map>

#include "graph/classify.h"
#include "graph/load.h"
#include "test_support.h"

using namespace lamina;

namespace {

Classification classify_text(const std::string& text) {
  CheckedFile checked = check_text(text, "inline.json");
  REQUIRE(checked.ok());
  return classify(*checked.graphs[0]);
}

// One layer of `top_deg` over a base, as a file.
std::string one_layer(const std::string& top, const std::string& medium, const std::string& base) {
  return R"({"format": 1, "materials": [{"name": "m", "surface": "@coat", "nodes": [
      {"id": "coat", "type": "layer", "interface": "@top", )" +
         (medium.empty() ? std::string() : R"("medium": "@tint", )") + R"("base": "@base"},
      {"id": "top", "type": "interface/dielectric", "ior": 1.5, )" +
         top + "}," +
         (medium.empty() ? std::string() : R"({"id": "tint", "type": "medium/absorbing", )" + medium + "},") +
         R"({"id": "base", )" + base + "}]}]}";
}

const std::string kDiffuse = R"("type": "substrate/oren_nayar", "albedo": [0.5, 0.5, 0.5])";

std::string metal(const std::string& roughness) {
  return R"("type": "substrate/conductor", "metal": "gold", )" + roughness;
}

}  // namespace

TEST_CASE("the course examples fall into the course's classes") {
  // Classes as the course files them (slides 62-80, ch. 4 and 5), independent of the files' tags.
  const std::map<std::string, std::string> expected = {{"acrylic_lacquer", "a"},
                                                       {"red_lacquer", "b"},
                                                       {"ceramic_glaze", "a"},
                                                       {"frosted_acrylic_paint", "c"},
                                                       {"sugar", "c"},
                                                       {"latex", "c"},
                                                       {"brass", "d"},
                                                       {"car_paint", "e"},
                                                       {"gold_metallic_paint", "e"},
                                                       {"gold_paint", "f"},
                                                       {"blue_metallic", "f"},
                                                       {"silver_paint", "g"},
                                                       {"house_paint", "h"},
                                                       {"christmas_orb", "d"},
                                                       {"concrete_ball", "b"},
                                                       {"fabric", "h"}};
  size_t seen = 0;
  for (const auto& [name, letter] : expected) {
    const std::string& material = name;  // clang 14 cannot capture a structured binding
    CAPTURE(material);
    CheckedFile checked = check_file(test::source_dir() / "examples/materials" / (name + ".json"));
    REQUIRE(checked.ok());
    Classification c = classify(*checked.graphs[0]);
    CHECK(c.letter == letter);
    CHECK(c.name == class_name(letter));
    ++seen;
  }
  CHECK(seen == 16);
}

TEST_CASE("smooth means an RMS slope below 5 degrees, for tops and metal bases alike") {
  CHECK(classify_text(one_layer(R"("roughness_deg": 4.99)", "", kDiffuse)).letter == "a");
  CHECK(classify_text(one_layer(R"("roughness_deg": 5.0)", "", kDiffuse)).letter == "c");
  CHECK(classify_text(one_layer(R"("roughness_deg": 1.0)", "", metal(R"("roughness_deg": 4.99)"))).letter == "d");
  CHECK(classify_text(one_layer(R"("roughness_deg": 1.0)", "", metal(R"("roughness_deg": 5.0)"))).letter == "e");
  CHECK(classify_text(one_layer(R"("roughness_deg": 5.0)", "", metal(R"("roughness_deg": 1.0)"))).letter == "f");
  CHECK(classify_text(one_layer(R"("roughness_deg": 5.0)", "", metal(R"("roughness_deg": 5.0)"))).letter == "g");
}

TEST_CASE("roughness given as alpha is compared as the angle atan(alpha)") {
  // tan(5 deg) = 0.0874887; just below and above it.
  CHECK(classify_text(one_layer(R"("alpha": 0.0874)", "", kDiffuse)).letter == "a");
  CHECK(classify_text(one_layer(R"("alpha": 0.0875)", "", kDiffuse)).letter == "c");
}

TEST_CASE("a varnish is tinted when its normal-incidence round trip absorbs more than 1 percent") {
  // 1 - exp(-2 a d) = 0.01 at a d = 0.0050252; below and above.
  CHECK(classify_text(
            one_layer(R"("roughness_deg": 1.0)", R"("thickness": 1.0, "absorption": [0.005, 0.0, 0.0])", kDiffuse))
            .letter == "a");
  CHECK(classify_text(
            one_layer(R"("roughness_deg": 1.0)", R"("thickness": 1.0, "absorption": [0.0, 0.0051, 0.0])", kDiffuse))
            .letter == "b");
  CHECK(classify_text(
            one_layer(R"("roughness_deg": 1.0)", R"("thickness": 0.0, "absorption": [9.0, 9.0, 9.0])", kDiffuse))
            .letter == "a");
}

TEST_CASE("textured roughness counts as rough and says so") {
  Classification c = classify_text(R"({"format": 1, "materials": [{"name": "m", "surface": "@coat", "nodes": [
      {"id": "coat", "type": "layer", "interface": "@top", "base": "@base"},
      {"id": "top", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": "@r"},
      {"id": "r", "type": "math/remap", "value": "@tiles.value", "out_max": 10.0},
      {"id": "tiles", "type": "texture/checker"},
      {"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]}]}]})");
  CHECK(c.letter == "c");
  CHECK(c.reason.find("textured roughness") != std::string::npos);
}

TEST_CASE("two or more layers are class h, a bare substrate has no class, and a mix agrees with its parts") {
  CHECK(classify_text(test::read_file(test::source_dir() / "examples/materials/house_paint.json")).letter == "h");
  Classification bare = classify_text(R"({"format": 1, "materials": [{"name": "m", "surface": "@s", "nodes": [
      {"id": "s", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]}]}]})");
  CHECK(bare.letter.empty());
  CHECK(bare.accepted.empty());
  Classification mixed = classify_text(test::read_file(test::source_dir() / "examples/materials/checker_tiles.json"));
  CHECK(mixed.letter.empty());
  CHECK(mixed.name == "mix of b) and d)");
  CHECK(mixed.accepted == std::vector<std::string>{"b", "d"});
}
