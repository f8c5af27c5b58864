#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>

#include "graph/load.h"
#include "test_support.h"

using namespace lamina;

namespace {

std::string data(const std::string& name) { return (test::source_dir() / "tests/data/gltf" / name).string(); }

}  // namespace

TEST_CASE("lamina import writes a valid material file with the textures next to it") {
  test::TempDir dir;
  // A file where the output directory should be is an I/O error; a missing directory is made.
  std::ofstream(dir.path() / "blocked") << "a file";
  auto r = test::run_cli("import " + data("lamina_layered.gltf") + " -o blocked/imported.json", dir.path());
  CHECK(r.exit_code == 1);
  r = test::run_cli("import " + data("lamina_layered.gltf") + " -o out/imported.json", dir.path());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("out/imported.json: 2 materials, 1 texture extracted, 0 warnings") != std::string::npos);
  CHECK(test::listing(dir.path() / "out") == std::vector<std::string>{"imported.json", "patina_mask.png"});
  CHECK(test::read_file(dir.path() / "out/patina_mask.png") ==
        test::read_file(test::source_dir() / "examples/materials/textures/patina_mask.png"));
  auto valid = test::run_cli("validate out/imported.json", dir.path());
  INFO(valid.err);
  CHECK(valid.exit_code == 0);
}

TEST_CASE("lamina import refuses to replace files without --force and prints warnings and notes") {
  test::TempDir dir;
  auto first = test::run_cli("import " + data("unknown_extension.gltf") + " -o m.json", dir.path());
  CHECK(first.exit_code == 0);
  CHECK(first.err.find(":/materials/0/extensions/VENDOR_materials_sparkle: ") != std::string::npos);
  CHECK(first.err.find(":/extensionsUsed/0: ") != std::string::npos);
  const std::string before = test::read_file(dir.path() / "m.json");

  auto again = test::run_cli("import " + data("clearcoat.gltf") + " -o m.json", dir.path());
  CHECK(again.exit_code == 2);
  CHECK(again.err.find("use --force") != std::string::npos);
  CHECK(test::read_file(dir.path() / "m.json") == before);

  auto forced = test::run_cli("import " + data("clearcoat.gltf") + " -o m.json --force", dir.path());
  CHECK(forced.exit_code == 0);
  CHECK(test::read_file(dir.path() / "m.json") != before);
}

TEST_CASE("lamina import exits 2 on a broken glTF and 1 on a missing file, writing nothing") {
  test::TempDir dir;
  for (const char* bad : {"bad/extension_not_object.gltf", "bad/invalid_graph.gltf", "bad/texture_out_of_range.gltf",
                          "bad/truncated.glb"}) {
    const std::string file = bad;
    CAPTURE(file);
    auto r = test::run_cli("import " + data(bad) + " -o out.json", dir.path());
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(data(bad) + ":") != std::string::npos);
  }
  auto missing = test::run_cli("import no_such.gltf -o out.json", dir.path());
  CHECK(missing.exit_code == 1);
  CHECK(test::listing(dir.path()).empty());
}
