#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "graph/limits.h"
#include "graph/schema.h"
#include "test_support.h"

using namespace lamina;

TEST_CASE("lamina validate accepts every example and exits 0") {
  auto r = test::run_cli("validate examples/materials", test::source_dir());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  // validate walks the folder recursively (the patina growth stages live in a subfolder).
  size_t files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::source_dir() / "examples/materials"))
    files += entry.path().extension() == ".json" ? 1 : 0;
  const std::string count = std::to_string(files);
  CHECK(r.out.find(count + " of " + count + " files valid") != std::string::npos);
}

TEST_CASE("lamina validate exits 2 on every broken file, prints its pointer and writes nothing") {
  auto manifest = nlohmann::json::parse(test::read_file(test::source_dir() / "tests/data/bad/cases.json"));
  test::TempDir dir;
  std::filesystem::copy(test::source_dir() / "tests/data/bad", dir.path());
  auto before = test::listing(dir.path());
  for (const auto& c : manifest) {
    std::string file = c.at("file");
    std::string pointer = c.at("pointer");
    CAPTURE(file);
    auto r = test::run_cli("validate " + file, dir.path());
    INFO(r.err);
    CHECK(r.exit_code == 2);
    // One line carries both: "file:pointer: message" (an empty pointer is the whole document).
    std::string prefix = file + ":" + pointer + ": ", fragment = c.at("message");
    bool found = false;
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);)
      found = found || (line.rfind(prefix, 0) == 0 && line.find(fragment) != std::string::npos);
    CHECK(found);
  }
  CHECK(test::listing(dir.path()) == before);
}

TEST_CASE("lamina validate reports I/O problems with exit 1 and gives a JSON report on request") {
  auto missing = test::run_cli("validate no/such/file.json", test::source_dir());
  CHECK(missing.exit_code == 1);
  CHECK(missing.err.find("no/such/file.json: no such file or directory") != std::string::npos);

  auto json = test::run_cli("validate --json tests/data/bad/ior_below_one.json examples/materials/car_paint.json",
                            test::source_dir());
  CHECK(json.exit_code == 2);
  auto report = nlohmann::json::parse(json.out);
  REQUIRE(report.size() == 2);
  CHECK(report[0]["valid"] == false);
  CHECK(report[0]["diagnostics"][0]["pointer"] == "/materials/0/nodes/1/ior");
  CHECK(report[1]["valid"] == true);
}

TEST_CASE("lamina classify prints each course example's class") {
  auto r = test::run_cli("classify examples/materials", test::source_dir());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("car_paint                e) metallic paint") != std::string::npos);
  CHECK(r.out.find("house_paint              h) multi-layer") != std::string::npos);
  // Every bundled example carries a class tag, and each agrees.
  size_t tagged = 0;
  for (const auto& file : test::example_files())
    tagged += nlohmann::json::parse(test::read_file(file)).at("materials").at(0).contains("class");
  const std::string agree = std::to_string(tagged) + " of " + std::to_string(tagged) + " class tags agree";
  CHECK(r.out.find(agree) != std::string::npos);
  CHECK(r.out.find("DISAGREES") == std::string::npos);
}

TEST_CASE("lamina nodes lists the types and explains one, and an unknown type exits 2") {
  auto all = test::run_cli("nodes");
  CHECK(all.exit_code == 0);
  CHECK(all.out.find("substrate/conductor") != std::string::npos);
  auto one = test::run_cli("nodes medium/absorbing");
  CHECK(one.exit_code == 0);
  CHECK(one.out.find("thickness: float or link, micrometres") != std::string::npos);
  // A named metal's constants and their source, from the same table the checker uses.
  auto conductor = test::run_cli("nodes substrate/conductor");
  CHECK(conductor.out.find("        gold: n (0.1, 0.42, 1.56), k (3.8, 2.5, 1.9); Weidlich and Wilkie course") !=
        std::string::npos);
  CHECK(conductor.out.find("        chromium: n (3.535, 2.901, 2.145), k (4.348, 4.231, 3.862); Rakic et al.") !=
        std::string::npos);
  auto unknown = test::run_cli("nodes medium/absorbin");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("did you mean 'medium/absorbing'?") != std::string::npos);
}

TEST_CASE("lamina schema writes the generated schema and reference") {
  test::TempDir dir;
  auto r = test::run_cli("schema -o '" + (dir.path() / "out").string() + "'");
  CHECK(r.exit_code == 0);
  CHECK(test::read_file(dir.path() / "out/material.schema.json") == material_schema());
  CHECK(test::read_file(dir.path() / "out/nodes.md") == node_reference_markdown());
  CHECK(test::read_file(dir.path() / "out/scene.schema.json") == scene_schema());
}

TEST_CASE("lamina validate checks a scene and its material files and prints a one-line summary") {
  auto r = test::run_cli("validate examples/showcase.json", test::source_dir());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  // A sphere per example material and the floor.
  const std::string materials = std::to_string(test::example_files().size());
  const std::string objects = std::to_string(test::example_files().size() + 1);
  CHECK(r.out.find("examples/showcase.json: ok (scene: " + objects + " objects, " + materials +
                   " materials, 2 lights, 1 camera)") != std::string::npos);
  CHECK(r.out.find("1 of 1 file valid, " + materials + " materials, 0 warnings") != std::string::npos);
}

TEST_CASE(
    "lamina validate and lamina glsl warn about a chain of layers longer than GLSL compilers unroll, and still "
    "succeed") {
  test::TempDir dir;
  const int layers = kGlslUnrolledEntries;  // with its base, one entry too many
  { std::ofstream(dir.path() / "coats.json") << test::chain_of_layers(layers); }
  const std::string warning =
      "coats.json:/materials/0/surface: warning: a chain of layers down to a substrate "
      "compiles to " +
      std::to_string(layers + 1) + " entries";
  auto v = test::run_cli("validate coats.json", dir.path());
  CHECK(v.exit_code == 0);
  CHECK(v.err.find(warning) != std::string::npos);
  CHECK(v.out.find("1 warning") != std::string::npos);
  auto g = test::run_cli("glsl coats.json -o coats.glsl", dir.path());
  CHECK(g.exit_code == 0);
  CHECK(g.err.find(warning) != std::string::npos);
  CHECK(std::filesystem::exists(dir.path() / "coats.glsl"));
  // The CPU evaluator does not care: eval says nothing.
  auto e = test::run_cli("eval coats.json --wi 0,0,1 --wo 0,0,1", dir.path());
  CHECK(e.exit_code == 0);
  CHECK(e.err.empty());
}

TEST_CASE("a select of more stacks than GLSL compilers unroll is evaluated by parts in GLSL, without a warning") {
  test::TempDir dir;
  const int stacks = (kGlslUnrolledEntries + 1) / 3 + 1;  // the fewest whose 3 stacks - 1 entries are too many
  { std::ofstream(dir.path() / "tiles.json") << test::select_of_layers(stacks); }
  auto v = test::run_cli("validate tiles.json", dir.path());
  CHECK(v.exit_code == 0);
  CHECK(v.out.find("0 warnings") != std::string::npos);
  auto g = test::run_cli("glsl tiles.json -o tiles.glsl", dir.path());
  CHECK(g.exit_code == 0);
  CHECK(g.err.empty());
  const std::string module = test::read_file(dir.path() / "tiles.glsl");
  CHECK(module.find("#define LAMINA_STACK 2\n") != std::string::npos);
  CHECK(module.find("#define LAMINA_PARTS " + std::to_string(stacks) + "\n") != std::string::npos);
  CHECK(module.find("lamina_blend_eval(") != std::string::npos);
}

TEST_CASE("lamina glsl warns about each material shorter than its module's longest stack, and only then") {
  test::TempDir dir;
  // Two materials of 2 and 3 stacks (5 and 8 entries), and a file of the longer alone.
  nlohmann::json both = nlohmann::json::parse(test::select_of_layers(2));
  nlohmann::json longer = nlohmann::json::parse(test::select_of_layers(3));
  longer["materials"][0]["name"] = "more_tiles";
  both["materials"].push_back(longer["materials"][0]);
  {
    std::ofstream(dir.path() / "both.json") << both.dump();
    std::ofstream(dir.path() / "longer.json") << longer.dump();
  }
  auto r = test::run_cli("glsl both.json -o both.glsl", dir.path());
  CHECK(r.exit_code == 0);
  // A select of N stacks compiles to 3 N - 1 entries (test::select_of_layers).
  CHECK(r.err.find("both.json:/materials/0/surface: warning: the stack compiles to " + std::to_string(3 * 2 - 1) +
                   " entries in a module whose longest has " + std::to_string(3 * 3 - 1)) != std::string::npos);
  CHECK(r.err.find("/materials/1/") == std::string::npos);
  auto alone = test::run_cli("glsl longer.json -o longer.glsl", dir.path());
  CHECK(alone.exit_code == 0);
  CHECK(alone.err.empty());
  auto chosen = test::run_cli("glsl both.json --material tiles -o tiles.glsl", dir.path());
  CHECK(chosen.exit_code == 0);
  CHECK(chosen.err.empty());
}

TEST_CASE("lamina gltf --fit-states bounds the fits of a textured material, and refuses a count out of range") {
  test::TempDir dir;
  const std::string sunstone = (test::source_dir() / "examples/materials/sunstone.json").string();
  auto two = test::run_cli("gltf '" + sunstone + "' -o two.glb --bake-size 32 --fit-states 2 --report", dir.path());
  CHECK(two.exit_code == 0);
  CHECK(two.out.find("  sunstone                     2~") != std::string::npos);
  for (const char* count : {"0", "65"}) {
    CAPTURE(count);
    auto bad = test::run_cli("gltf '" + sunstone + "' -o bad.glb --fit-states " + count, dir.path());
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--fit-states") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.path() / "bad.glb"));
  }
}

TEST_CASE("lamina validate exits 2 on a broken scene, naming the scene or the material file at fault") {
  auto scene = test::run_cli("validate tests/data/bad_scenes/radius_zero.json", test::source_dir());
  CHECK(scene.exit_code == 2);
  CHECK(scene.err.find("tests/data/bad_scenes/radius_zero.json:/objects/0/radius: radius = 0.0 is out of range") !=
        std::string::npos);
  CHECK(scene.out.find("0 of 1 file valid") != std::string::npos);
  auto material = test::run_cli("validate tests/data/bad_scenes/broken_material_file.json", test::source_dir());
  CHECK(material.exit_code == 2);
  CHECK(material.err.find("tests/data/bad_scenes/materials/ior_below_one.json:/materials/0/nodes/1/ior: ") !=
        std::string::npos);
}

TEST_CASE("every command has --help, the tool has --version, and a bad command line exits 2") {
  for (const char* command :
       {"", "validate ", "classify ", "nodes ", "schema ", "eval ", "albedo ", "plot ", "glsl ", "gltf ", "import "}) {
    CAPTURE(command);
    auto r = test::run_cli(std::string(command) + "--help");
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("Usage:") != std::string::npos);
  }
  auto version = test::run_cli("--version");
  CHECK(version.exit_code == 0);
  CHECK(version.out.rfind(std::string("lamina ") + LAMINA_VERSION + "\n", 0) == 0);
  CHECK(version.out.find("Embree 3.") != std::string::npos);
  CHECK(test::run_cli("").exit_code == 2);
  auto unknown = test::run_cli("valdate examples");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("unknown command 'valdate'; did you mean 'validate'?") != std::string::npos);
  CHECK(test::run_cli("frobnicate").exit_code == 2);
  CHECK(test::run_cli("validate").exit_code == 2);
  CHECK(test::run_cli("schema").exit_code == 2);
}

TEST_CASE("lamina validate and classify check every argument, and an empty directory is an error") {
  test::TempDir empty;
  auto r = test::run_cli("validate " + empty.path().string());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("no .json file in this directory") != std::string::npos);
  // A missing path is reported, and the files after it are still checked.
  auto missing = test::run_cli("validate no/such.json tests/data/bad/ior_below_one.json", test::source_dir());
  CHECK(missing.exit_code == 1);
  CHECK(missing.err.find("no/such.json: no such file or directory") != std::string::npos);
  CHECK(missing.err.find("tests/data/bad/ior_below_one.json:/materials/0/nodes/1/ior: ") != std::string::npos);
  auto classify =
      test::run_cli("classify " + empty.path().string() + " examples/materials/car_paint.json", test::source_dir());
  CHECK(classify.exit_code == 2);
  CHECK(classify.out.find("examples/materials/car_paint.json:\ncar_paint ") != std::string::npos);
}

TEST_CASE("lamina eval reads the shading point's uv, position and footprint, and refuses a negative footprint") {
  // every_node.json has textures over uv and over position, and filters them over the footprint.
  const std::string base = "eval tests/data/glsl/every_node.json --wi 0.3,0,1 --wo -0.2,0.1,1 --uv 0.3,0.4";
  auto at_origin = test::run_cli(base, test::source_dir());
  auto moved = test::run_cli(base + " --position 0.7,-1.3,2.1", test::source_dir());
  auto filtered = test::run_cli(base + " --footprint 0.5", test::source_dir());
  REQUIRE(at_origin.exit_code == 0);
  REQUIRE(moved.exit_code == 0);
  REQUIRE(filtered.exit_code == 0);
  CHECK(moved.out != at_origin.out);
  CHECK(filtered.out != at_origin.out);
  for (const char* bad : {" --footprint -1", " --position 1,2", " --footprint nan"}) {
    CAPTURE(bad);
    auto r = test::run_cli(base + bad, test::source_dir());
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK_FALSE(r.err.empty());
  }
}
