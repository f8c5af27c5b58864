// lamina render from the command line: what it writes, and what it refuses.
#include <doctest/doctest.h>

#include <fstream>

#include "graph/cpu/image.h"
#include "graph/load.h"
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
  // A time budget: as many samples as fit, at least one, said on standard output and in the image.
  auto timed = test::run_cli("render scene.json -o timed.exr --width 32 --time 0.5", dir.path());
  INFO(timed.err);
  CHECK(timed.exit_code == 0);
  CHECK(timed.out.find(" samples per pixel in ") != std::string::npos);
  const std::string samples = timed.out.substr(0, timed.out.find(' '));
  CHECK(test::read_file(dir.path() / "timed.exr").find(samples + " spp") != std::string::npos);
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
      {scene_with(kCamera, ""), "", "/lights", "no light, no environment and no emitting object"},
      {scene_with(kCamera, std::string(kSky) + ", " + R"({"name": "sky2", "type": "environment"})"), "", "/lights/1",
       "second environment"},
      {scene_with(kCamera, R"({"name": "sky", "type": "environment", "file": "missing.hdr"})"), "", "/lights/0/file",
       "missing.hdr"},
      {scene_with(R"({"name": "main", "aperture_radius": -0.1})", kSky), "", "/cameras/0/aperture_radius", "-0.1"},
      {scene_with(R"({"name": "main", "focus_distance": 0})", kSky), "", "/cameras/0/focus_distance", "0"},
      {scene_with(kCamera, R"({"name": "sky", "type": "environment", "rotation": 400})"), "", "/lights/0/rotation",
       "400"},
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
                                 "-o out.png --estimator nee", "-o out.png --time -1"}) {
    CAPTURE(args);
    auto r = test::run_cli("render scene.json " + args, dir.path());
    CHECK(r.exit_code == 2);
    CHECK(!std::filesystem::exists(dir.path() / "out.png"));
  }
}

TEST_CASE("the camera's exposure and --exposure scale the rendered radiance by powers of two") {
  test::TempDir dir;
  std::filesystem::copy(test::source_dir() / "tests/data/render/lambert.json", dir.path() / "lambert.json");
  write_text(dir.path() / "plain.json", scene_with(kCamera, kSky));
  write_text(dir.path() / "bright.json", scene_with(R"({"name": "main", "position": [0, 0, 4], "exposure": 1})", kSky));
  for (const auto& [scene, args] :
       {std::pair{"plain", ""}, std::pair{"bright", ""}, std::pair{"bright", "--exposure -3"}}) {
    auto r = test::run_cli(std::string("render ") + scene + ".json -o " + scene + (args[0] ? "_less" : "") +
                               ".exr --width 8 --spp 1 " + args,
                           dir.path());
    INFO(r.err);
    CHECK(r.exit_code == 0);
  }
  const auto plain = load_image_file(dir.path() / "plain.exr", false);
  const auto bright = load_image_file(dir.path() / "bright.exr", false);
  const auto less = load_image_file(dir.path() / "bright_less.exr", false);
  REQUIRE(plain->texels.size() == bright->texels.size());
  double worst = 0.0;
  for (size_t i = 0; i < plain->texels.size(); ++i) {
    worst = std::max(worst, std::abs(double(bright->texels[i].r) / double(plain->texels[i].r) - 2.0));
    worst = std::max(worst, std::abs(double(less->texels[i].r) / double(plain->texels[i].r) - 0.25));
  }
  CHECK(worst < 2e-3);  // half floats
}

TEST_CASE("lamina preview shows one material, or several side by side with --compare, and refuses the ambiguous") {
  test::TempDir dir;
  std::filesystem::copy(test::source_dir() / "tests/data/render/lambert.json", dir.path() / "lambert.json");
  auto one = test::run_cli("preview lambert.json --material grey -o grey.png --size 32 --spp 2", dir.path());
  INFO(one.err);
  CHECK(one.exit_code == 0);
  const auto single = load_image_file(dir.path() / "grey.png", true);
  CHECK(single->width == 32);
  CHECK(single->height == 32);

  // The studio turned half a turn lights the ball from the other side: another image.
  auto turned = test::run_cli(
      "preview lambert.json --material grey -o turned.png --size 32 --spp 2 --environment-rotation 180", dir.path());
  INFO(turned.err);
  CHECK(turned.exit_code == 0);
  CHECK(load_image_file(dir.path() / "turned.png", true)->texels != single->texels);

  auto all = test::run_cli("preview lambert.json --compare --columns 2 -o all.png --size 32 --spp 1", dir.path());
  INFO(all.err);
  CHECK(all.exit_code == 0);
  // Every material of the file in rows of two, each preview with a label strip under it.
  const auto sheet = load_image_file(dir.path() / "all.png", true);
  const Document materials = load(dir.path() / "lambert.json");
  const int rows = int((materials.materials.size() + 1) / 2);
  CHECK(sheet->width == 64);
  CHECK(sheet->height > rows * 32);

  for (const std::string args : {"preview lambert.json -o x.png", "preview lambert.json --material gray -o x.png",
                                 "preview lambert.json --material grey -o x.png --size 4",
                                 "preview lambert.json --material grey -o x.png --environment-rotation 400"}) {
    CAPTURE(args);
    auto r = test::run_cli(args, dir.path());
    CHECK(r.exit_code == 2);
    CHECK(!std::filesystem::exists(dir.path() / "x.png"));
  }
}
