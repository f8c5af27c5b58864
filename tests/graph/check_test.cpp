#include <doctest/doctest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "graph/compile.h"
#include "graph/glsl/generator.h"
#include "graph/kernel_stack.h"
#include "graph/limits.h"
#include "graph/load.h"
#include "graph/lobes.h"
#include "graph/stack_size.h"
#include "random_stacks.h"
#include "test_support.h"

using namespace lamina;

namespace {

struct BadCase {
  std::string file;
  std::string pointer;
  std::string message;
};

std::vector<BadCase> bad_cases() {
  auto manifest = nlohmann::json::parse(test::read_file(test::source_dir() / "tests/data/bad/cases.json"));
  std::vector<BadCase> cases;
  for (const auto& c : manifest) cases.push_back({c.at("file"), c.at("pointer"), c.at("message")});
  return cases;
}

bool has_error(const Diagnostics& d, const std::string& pointer, const std::string& fragment) {
  for (const auto& e : d.errors())
    if (e.pointer == pointer && e.message.find(fragment) != std::string::npos) return true;
  return false;
}

std::string listing(const Diagnostics& d) {
  std::string out;
  for (const auto& e : d.errors()) out += format(e) + "\n";
  return out;
}

CheckedFile check(const std::string& text) { return check_text(text, "inline.json"); }

}  // namespace

TEST_CASE("every bundled example is valid and has no warnings") {
  for (const auto& file : test::example_files()) {
    CAPTURE(file);
    CheckedFile checked = check_file(file);
    INFO(listing(checked.diagnostics));
    CHECK(checked.ok());
    CHECK(checked.diagnostics.warnings().empty());
    for (const auto& g : checked.graphs) CHECK(g.has_value());
  }
}

TEST_CASE("every file of the bad corpus gives its expected error at its expected pointer") {
  auto cases = bad_cases();
  CHECK(cases.size() >= 40);
  for (const auto& c : cases) {
    CAPTURE(c.file);
    CheckedFile checked = check_file(test::source_dir() / "tests/data/bad" / c.file);
    INFO(listing(checked.diagnostics));
    CHECK_FALSE(checked.ok());
    CHECK(has_error(checked.diagnostics, c.pointer, c.message));
    for (const auto& g : checked.graphs) CHECK_FALSE(g.has_value());
    for (const auto& e : checked.diagnostics.errors()) CHECK(e.file.find(c.file) != std::string::npos);
  }
}

TEST_CASE("all problems of a file are reported in one pass") {
  CheckedFile checked = check(R"({"format": 1, "materials": [{"name": "m", "surface": "@coat", "nodes": [
      {"id": "coat", "type": "layer", "interface": "@varnsh", "base": "@paint"},
      {"id": "varnish", "type": "interface/dielectric", "ior": 0.9},
      {"id": "paint", "type": "substrate/lambert", "albedo": [0.5, 1.5, 0.5], "colour": 1}]}]})");
  INFO(listing(checked.diagnostics));
  CHECK(checked.diagnostics.errors().size() == 4);
  CHECK(has_error(checked.diagnostics, "/materials/0/nodes/0/interface", "unknown node 'varnsh'"));
  CHECK(has_error(checked.diagnostics, "/materials/0/nodes/1/ior", "out of range"));
  CHECK(has_error(checked.diagnostics, "/materials/0/nodes/2/albedo/1", "out of range"));
  CHECK(has_error(checked.diagnostics, "/materials/0/nodes/2/colour", "unknown parameter"));
}

TEST_CASE("a misspelt link suggests the closest node id") {
  CheckedFile checked = check(R"({"format": 1, "materials": [{"name": "m", "surface": "@coat", "nodes": [
      {"id": "coat", "type": "layer", "interface": "@varnsh", "base": "@paint"},
      {"id": "varnish", "type": "interface/dielectric", "ior": 1.5},
      {"id": "paint", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]}]}]})");
  REQUIRE(checked.diagnostics.errors().size() == 1);
  CHECK(checked.diagnostics.errors()[0].hint == "did you mean '@varnish'?");
}

TEST_CASE("a cycle is printed node by node") {
  CheckedFile checked = check(R"({"format": 1, "materials": [{"name": "m", "surface": "@a", "nodes": [
      {"id": "a", "type": "layer", "interface": "@i", "base": "@b"},
      {"id": "b", "type": "layer", "interface": "@i", "base": "@a"},
      {"id": "i", "type": "interface/dielectric", "ior": 1.5}]}]})");
  REQUIRE(checked.diagnostics.errors().size() == 1);
  const auto& e = checked.diagnostics.errors()[0];
  CHECK(e.message.find("cycle: a -> b -> a") != std::string::npos);
  CHECK(e.pointer == "/materials/0/nodes/1/base");
}

TEST_CASE("unused nodes and a class tag that disagrees with the structure are warnings, not errors") {
  CheckedFile checked = check(R"({"format": 1, "materials": [{"name": "m", "class": "e", "surface": "@coat", "nodes": [
      {"id": "coat", "type": "layer", "interface": "@top", "base": "@paint"},
      {"id": "top", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 1.0},
      {"id": "paint", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
      {"id": "spare", "type": "medium/clear"}]}]})");
  CHECK(checked.ok());
  REQUIRE(checked.diagnostics.warnings().size() == 2);
  CHECK(checked.diagnostics.warnings()[0].pointer == "/materials/0/nodes/3");
  CHECK(checked.diagnostics.warnings()[0].message.find("'spare' does not feed the surface") != std::string::npos);
  CHECK(checked.diagnostics.warnings()[1].pointer == "/materials/0/class");
  CHECK(checked.diagnostics.warnings()[1].message.find("a) glossy paint") != std::string::npos);
}

TEST_CASE("a missing texture file names the path searched, and an existing one passes") {
  test::TempDir dir;
  auto material = dir.path() / "m.json";
  auto write = [&](const std::string& file) {
    std::ofstream out(material);
    out << R"({"format": 1, "materials": [{"name": "m", "surface": "@mx", "nodes": [
        {"id": "mx", "type": "mix", "weight": "@tex.value", "a": "@p", "b": "@q"},
        {"id": "tex", "type": "texture/image", "file": ")"
        << file << R"("},
        {"id": "p", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
        {"id": "q", "type": "substrate/lambert", "albedo": [0.1, 0.1, 0.1]}]}]})";
  };
  write("missing.png");
  CheckedFile missing = check_file(material);
  REQUIRE(missing.diagnostics.errors().size() == 1);
  CHECK(missing.diagnostics.errors()[0].pointer == "/materials/0/nodes/1/file");
  CHECK(missing.diagnostics.errors()[0].message.find((dir.path() / "missing.png").string()) != std::string::npos);

  std::filesystem::copy_file(test::source_dir() / "examples/materials/textures/patina_mask.png",
                             dir.path() / "mask.png");
  write("mask.png");
  CHECK(check_file(material).ok());
}

TEST_CASE("graph links resolve in topological order with defaults applied") {
  CheckedFile checked = check_file(test::source_dir() / "examples/materials/patina_map_copper.json");
  REQUIRE(checked.ok());
  const Graph& g = *checked.graphs[0];
  std::vector<size_t> position(g.size());
  for (size_t k = 0; k < g.topological_order().size(); ++k) position[g.topological_order()[k]] = k;
  CHECK(g.topological_order().size() == g.size());
  for (const auto& e : g.edges()) CHECK(position[e.from] < position[e.to]);
  CHECK(g.node(g.surface()).id == "patina_mix");
  auto weight = g.linked(g.surface(), "weight");
  REQUIRE(weight);
  CHECK(g.node(*weight).id == "coverage");
  // copper_coat has no medium input: its default is "no link", which means a clear medium.
  size_t copper_coat = 3;
  REQUIRE(g.node(copper_coat).id == "copper_coat");
  CHECK_FALSE(g.linked(copper_coat, "medium"));
  const Value* distribution = g.value(4, "distribution");
  REQUIRE(distribution);
  CHECK(std::get<std::string>(*distribution) == "beckmann");
}

TEST_CASE("the checker's count of a stack's size is what compiling it takes, for every bundled and test material") {
  std::vector<std::filesystem::path> files = test::example_files();
  for (const char* folder : {"tests/data/glsl", "tests/data/physics"})
    for (const auto& e : std::filesystem::directory_iterator(test::source_dir() / folder))
      if (e.path().extension() == ".json") files.push_back(e.path());
  size_t materials = 0;
  for (const auto& file : files) {
    CAPTURE(file.string());
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    for (const auto& graph : checked.graphs) {
      const StackSize size = measure_stack(*graph);
      const Program program = compile(*graph, file.string(), checked.document.policy);
      CHECK(size.entries == int(program.stack.size()));
      CHECK(size.stack_nodes <= size.entries);
      CHECK(size.registers == program.slot_count);
      CHECK(size.lobes == int(collect_lobes(program).size()));
      ++materials;
    }
  }
  CHECK(materials > files.size() / 2);
}

TEST_CASE("a chain of layers longer than GLSL compilers unroll is a warning at its surface, and one that fits is not") {
  // kGlslUnrolledEntries - 1 layers over a base fit; one more does not.
  for (int layers : {kGlslUnrolledEntries - 1, kGlslUnrolledEntries}) {
    CAPTURE(layers);
    CheckedFile checked = check_text(test::chain_of_layers(layers), "coats.json");
    REQUIRE(checked.ok());
    REQUIRE(checked.graphs.front());
    const StackSize size = measure_stack(*checked.graphs.front());
    CHECK(size.parts == 1);
    CHECK(size.longest_part == layers + 1);
    const int entries = glsl_loop_entries(size);
    CHECK(entries == layers + 1);
    Diagnostics advice;
    warn_glsl_unrolling(entries, "coats.json", "/materials/0", advice);
    if (entries <= kGlslUnrolledEntries) {
      CHECK(advice.warnings().empty());
    } else {
      REQUIRE(advice.warnings().size() == 1);
      CHECK(advice.warnings().front().pointer == "/materials/0/surface");
      CHECK(advice.warnings().front().message.find(std::to_string(entries) + " entries") != std::string::npos);
    }
  }
}

TEST_CASE("a select of more stacks than GLSL compilers unroll loops over its parts, and is no warning") {
  // 3 stacks - 1 entries: the fewest stacks that are too many for one loop.
  const int stacks = (kGlslUnrolledEntries + 1) / 3 + 1;
  CheckedFile checked = check_text(test::select_of_layers(stacks), "tiles.json");
  REQUIRE(checked.ok());
  const StackSize size = measure_stack(*checked.graphs.front());
  CHECK(size.entries == 3 * stacks - 1);
  CHECK(size.parts == stacks);
  CHECK(size.longest_part == 2);
  CHECK(glsl_loop_entries(size) == 2);
  Diagnostics advice;
  warn_glsl_unrolling(glsl_loop_entries(size), "tiles.json", "/materials/0", advice);
  CHECK(advice.warnings().empty());
}

TEST_CASE("the graph's count of GLSL loop entries is the compiled Program's, for every example and random stacks") {
  auto check_all = [](const CheckedFile& checked, const std::string& file) {
    REQUIRE_MESSAGE(checked.ok(), file);
    for (const auto& graph : checked.graphs) {
      const Program program = compile(*graph, file, test::repository_policy());
      CAPTURE(program.name);
      const StackSize size = measure_stack(*graph);
      const StackBlend blend = split_blend(program, true);
      CHECK(size.entries == int(program.stack.size()));
      CHECK(size.parts == int(blend.parts.size()));
      CHECK(size.longest_part == blend.longest_part());
      CHECK(glsl_loop_entries(size) == glsl::unrolled_entries(program));
    }
  };
  for (const auto& file : test::example_files()) check_all(check_file(file, test::repository_policy()), file.string());
  check_all(check_text(test::RandomStacks(7).file(24), "random.json"), "random.json");
  check_all(check_text(test::select_of_layers(12), "tiles.json"), "tiles.json");
}

TEST_CASE("no bundled example's GLSL loops over more entries than GLSL compilers unroll") {
  for (const auto& file : test::example_files()) {
    CAPTURE(file.string());
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    for (const auto& graph : checked.graphs) CHECK(glsl_loop_entries(measure_stack(*graph)) <= kGlslUnrolledEntries);
  }
}
