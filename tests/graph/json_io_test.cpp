#include <doctest/doctest.h>

#include "graph/json_read.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "graph/number_text.h"
#include "test_support.h"

#include <fstream>

using namespace lamina;

TEST_CASE("every example reads back exactly from its canonical writing") {
  for (const auto& file : test::example_files()) {
    CAPTURE(file);
    std::string text = test::read_file(file);
    Diagnostics d1;
    Document first = read_document(text, file.string(), d1);
    REQUIRE(d1.ok());
    std::string written = write_document(first);
    Diagnostics d2;
    Document second = read_document(written, file.string(), d2);
    REQUIRE(d2.ok());
    CHECK(first.same_content(second));
    // The bundled examples are kept in canonical form, so the writer reproduces them byte for byte.
    CHECK(written == text);
    CHECK(write_document(second) == written);
  }
}

TEST_CASE("the writer puts keys in canonical order whatever order the file uses") {
  const char* shuffled = R"({"materials": [{"nodes": [
      {"albedo": [0.5, 0.25, 0.125], "type": "substrate/oren_nayar", "sigma": 0.3, "id": "base"}],
      "surface": "@base", "class": "a", "name": "plain"}], "format": 1})";
  Diagnostics d;
  Document doc = read_document(shuffled, "shuffled.json", d);
  REQUIRE(d.ok());
  std::string expected = R"({
  "format": 1,
  "materials": [
    {
      "name": "plain",
      "class": "a",
      "surface": "@base",
      "nodes": [
        {"id": "base", "type": "substrate/oren_nayar", "albedo": [0.5, 0.25, 0.125], "sigma": 0.3}
      ]
    }
  ]
}
)";
  CHECK(write_document(doc) == expected);
}

TEST_CASE("numbers are written in the shortest form that reads back to the same double") {
  CHECK(number_text(1.0) == "1.0");
  CHECK(number_text(0.1) == "0.1");
  CHECK(number_text(1.5) == "1.5");
  CHECK(number_text(1e-7) == "1e-07");
  CHECK(number_text(0.157) == "0.157");
  CHECK(number_text(1.0 / 3.0) == "0.3333333333333333");
  for (double v : {0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, 123456.789, 0.30000000000000004}) {
    CHECK(std::stod(number_text(v)) == v);
  }
}

TEST_CASE("integers in the file are floats after a round trip, with the same value") {
  const char* text = R"({"format": 1, "materials": [{"name": "m", "surface": "@s", "nodes": [
      {"id": "s", "type": "substrate/lambert", "albedo": [1, 0, 0]}]}]})";
  Diagnostics d;
  Document doc = read_document(text, "int.json", d);
  REQUIRE(d.ok());
  std::string written = write_document(doc);
  CHECK(written.find("[1.0, 0.0, 0.0]") != std::string::npos);
  Diagnostics d2;
  CHECK(read_document(written, "int.json", d2).same_content(doc));
}

TEST_CASE("strings with quotes and unicode survive the round trip") {
  const char* text =
      R"({"format": 1, "materials": [{"name": "m", "notes": "a \"quoted\" note, 5\u00b0 and a\\backslash",
      "surface": "@s", "nodes": [{"id": "s", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]}]}]})";
  Diagnostics d;
  Document doc = read_document(text, "s.json", d);
  REQUIRE(d.ok());
  REQUIRE(doc.materials[0].notes);
  CHECK(*doc.materials[0].notes == "a \"quoted\" note, 5\xc2\xb0 and a\\backslash");
  Diagnostics d2;
  CHECK(read_document(write_document(doc), "s.json", d2).same_content(doc));
}

TEST_CASE("links parse as node and optional output") {
  Link link;
  CHECK(parse_link("@coat", link));
  CHECK(link == Link{"coat", ""});
  CHECK(parse_link("@tex.value", link));
  CHECK(link == Link{"tex", "value"});
  CHECK_FALSE(parse_link("coat", link));
  CHECK_FALSE(parse_link("@", link));
  CHECK_FALSE(parse_link("@@x", link));
  CHECK_FALSE(parse_link("@1abc", link));
  CHECK_FALSE(parse_link("@a.", link));
  CHECK_FALSE(parse_link("@a.b.c", link));
  CHECK(to_string(Link{"tex", "value"}) == "@tex.value");
}

TEST_CASE("load returns the document of a valid file and throws lamina::Error with every problem otherwise") {
  Document doc = load(test::source_dir() / "examples/materials/car_paint.json");
  REQUIRE(doc.materials.size() == 1);
  CHECK(doc.materials[0].name == "car_paint");

  test::TempDir dir;
  auto bad = dir.path() / "bad.json";
  {
    std::ofstream out(bad);
    out << R"({"format": 1, "materials": [{"name": "m", "surface": "@s", "nodes": [
        {"id": "s", "type": "substrate/lambert", "albedo": [2, 0, -1]}]}]})";
  }
  try {
    load(bad);
    FAIL("load accepted an invalid file");
  } catch (const Error& e) {
    REQUIRE(e.diagnostics().size() == 2);
    CHECK(e.diagnostics()[0].pointer == "/materials/0/nodes/0/albedo/0");
    CHECK(e.diagnostics()[1].pointer == "/materials/0/nodes/0/albedo/2");
    CHECK(std::string(e.what()).find("bad.json:/materials/0/nodes/0/albedo/0:") != std::string::npos);
  }
  CHECK_THROWS_AS(load(dir.path() / "missing.json"), IoError);
  CHECK_THROWS_AS(load(dir.path()), IoError);
}
