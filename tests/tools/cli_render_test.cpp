// lamina render from the command line: what it writes, and what it refuses.
#include <doctest/doctest.h>

#include <fstream>

#include "test_support.h"

using namespace lamina;

namespace {

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string scene_with(const std::string& cameras, const std::string& lights) {
  return R"({"format": 1, "materials": ["lambert.json"], "cameras": [)" + cameras + R"(], "lights": [)" + lights +
         R"(], "objects": [{"name": "ball", "shape": "sphere", "material": "white"}]})";
}

const char* kCamera = R"({"name": "main", "position": [0, 0, 4]})";
const char* kSky = R"({"name": "sky", "type": "environment"})";

}  // namespace

TEST_CASE("lamina render writes a PNG of a scene and an EXR with albedo and normal layers") {
  test::TempDir dir;
  std::filesystem::copy(test::source_dir() / "tests/data/render/lambert.json", dir.path() / "lambert.json");
  write_text(dir.path() / "scene.json", scene_with(kCamera, kSky));
  auto png = test::run_cli("render scene.json -o ball.png --width 32 --spp 2 --stats", dir.path());
  INFO(png.err);
  CHECK(png.exit_code == 0);
  CHECK(png.out.find("rays/s") != std::string::npos);
  CHECK(std::filesystem::file_size(dir.path() / "ball.png") > 0);
  auto exr = test::run_cli("render scene.json -o ball.exr --width 32 --height 16 --spp 2 --aovs", dir.path());
  INFO(exr.err);
  CHECK(exr.exit_code == 0);
  const std::string bytes = test::read_file(dir.path() / "ball.exr");
  CHECK(bytes.rfind("\x76\x2f\x31\x01", 0) == 0);  // OpenEXR's magic number
  for (const char* channel : {"albedo.R", "N.Z"}) CHECK(bytes.find(channel) != std::string::npos);
  // A material file renders as its sample sheet.
  auto sheet = test::run_cli("render lambert.json -o sheet.png --width 32 --spp 1", dir.path());
  INFO(sheet.err);
  CHECK(sheet.exit_code == 0);
}

TEST_CASE("lamina render refuses a scene it cannot render, with the pointer, and writes nothing") {
  test::TempDir dir;
  std::filesystem::copy(test::source_dir() / "tests/data/render/lambert.json", dir.path() / "lambert.json");
  struct Case {
    std::string scene, args, pointer, fragment;
  };
  const std::vector<Case> cases{
      {scene_with("", kSky), "", "/cameras", "no camera"},
      {scene_with(kCamera, kSky), "--camera mian", "/cameras", "did you mean \"main\""},
      {scene_with(kCamera, ""), "", "/lights", "no light and no environment"},
      {scene_with(kCamera, std::string(kSky) + ", " + R"({"name": "sky2", "type": "environment"})"), "", "/lights/1",
       "second environment"},
      {scene_with(kCamera, R"({"name": "sky", "type": "environment", "file": "missing.hdr"})"), "", "/lights/0/file",
       "missing.hdr"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.scene);
    write_text(dir.path() / "scene.json", c.scene);
    auto r = test::run_cli("render scene.json -o out.png --width 8 " + c.args, dir.path());
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("scene.json:" + c.pointer + ": ") != std::string::npos);
    CHECK(r.err.find(c.fragment) != std::string::npos);
    CHECK(!std::filesystem::exists(dir.path() / "out.png"));
  }
  write_text(dir.path() / "scene.json", scene_with(kCamera, kSky));
  for (const std::string args : {"-o out.png --spp 0", "-o out.png --width 0", "-o out.txt", "-o out.png --aovs",
                                 "-o out.png --estimator nee"}) {
    CAPTURE(args);
    auto r = test::run_cli("render scene.json " + args, dir.path());
    CHECK(r.exit_code == 2);
    CHECK(!std::filesystem::exists(dir.path() / "out.png"));
  }
}
