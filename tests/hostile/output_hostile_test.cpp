// Outputs under attack or accident, made at test time: an output that is an input (by name, side
// file, hard link or texture), symbolic links and devices as targets, a user's OUT.tmp, a full disk
// (a small tmpfs, and a file size limit), a read-only folder, standard output on /dev/full. Every
// output is complete or absent, nothing else changes, and the exit code and message say why.
#include <doctest/doctest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "hostile_support.h"
#include "test_support.h"

using namespace lamina;
using test::write;

namespace {

namespace fs = std::filesystem;

// Every file under `dir` with its content, to compare before and after.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(e.path(), dir).string();
    if (e.is_symlink())
      files[name] = "-> " + fs::read_symlink(e.path()).string();
    else if (e.is_regular_file())
      files[name] = test::read_file(e.path());
    else
      files[name] = "(folder)";
  }
  return files;
}

// A folder with the car paint material and a textured material with its texture.
fs::path project(const test::TempDir& dir) {
  fs::copy_file(test::source_dir() / "examples/materials/car_paint.json", dir.path() / "car.json");
  fs::copy_file(test::source_dir() / "examples/materials/patina_map_copper.json", dir.path() / "patina.json");
  fs::create_directories(dir.path() / "textures");
  fs::copy_file(test::source_dir() / "examples/materials/textures/patina_mask.png",
                dir.path() / "textures" / "patina_mask.png");
  return dir.path();
}

void expect_unchanged(const test::RunResult& r, int code, const std::string& message,
                      const std::map<std::string, std::string>& before, const fs::path& dir) {
  INFO(r.err);
  CHECK(r.exit_code == code);
  CHECK(r.err.find(message) != std::string::npos);
  CHECK(snapshot(dir) == before);
}

}  // namespace

TEST_CASE("an output that is also an input is refused before anything is written, however it is named") {
  test::TempDir dir;
  const fs::path p = project(dir);
  fs::create_hard_link(p / "car.json", p / "hard_link.json");
  fs::create_directories(p / "meshes");
  const auto before = snapshot(p);
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"glsl car.json -o car.json", "car.json is also an input of this command"},
      {"glsl car.json -o out.glsl --interface car.json", "car.json is also an input"},
      {"glsl car.json -o car.glsl --uniforms --interface ./car.json", "./car.json is also an input"},
      {"glsl car.json -o hard_link.json", "hard_link.json is also an input"},
      {"plot patina.json -o textures/patina_mask.png", "textures/patina_mask.png is also an input"},
      {"compare patina.json --albedo-walks 4 --slice-walks 1 --plot textures/patina_mask.png",
       "textures/patina_mask.png is also an input"},
      {"glsl car.json -o /dev/null --interface car.json", "car.json is also an input"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.args);
    expect_unchanged(test::run_cli(c.args, p), 2, c.message, before, p);
  }
  // The implied side file of --uniforms, car.uniforms.json, when it is the input.
  fs::copy_file(p / "car.json", p / "car.uniforms.json");
  const auto with_side = snapshot(p);
  expect_unchanged(test::run_cli("glsl car.uniforms.json -o car.glsl --uniforms", p), 2,
                   "car.uniforms.json is also an input", with_side, p);
}

TEST_CASE("lamina import never replaces an input, and leaves the glTF file's own images as they are") {
  test::TempDir dir;
  const fs::path p = dir.path();
  fs::copy_file(test::source_dir() / "examples/materials/textures/patina_mask.png", p / "texture.png");
  write(p / "m.gltf", R"({"asset": {"version": "2.0"}, "materials": [{"name": "painted",
    "pbrMetallicRoughness": {"metallicFactor": 0, "baseColorTexture": {"index": 0}}}], "textures": [{"source": 0}],
    "images": [{"uri": "texture.png"}]})");
  const auto before = snapshot(p);
  expect_unchanged(test::run_cli("import m.gltf -o m.gltf --force", p), 2, "m.gltf is also an input", before, p);
  // Next to the glTF file: its image is already there, byte for byte, and stays untouched.
  const auto r = test::run_cli("import m.gltf -o m.json", p);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(test::read_file(p / "texture.png") == before.at("texture.png"));
  CHECK(test::read_file(p / "m.json").find("\"file\": \"texture.png\"") != std::string::npos);
}

TEST_CASE("a symbolic link as output is written through and stays a link, and /dev/null is written in place") {
  test::TempDir dir;
  const fs::path p = project(dir);
  fs::create_directories(p / "real");
  fs::create_symlink("real/target.glsl", p / "link.glsl");
  const auto r = test::run_cli("glsl car.json -o link.glsl", p);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::is_symlink(p / "link.glsl"));
  CHECK(fs::is_regular_file(p / "real" / "target.glsl"));
  CHECK(test::read_file(p / "real" / "target.glsl").find("lamina_car_paint_eval") != std::string::npos);
  // Written again through the link: the target's content is replaced, the link kept.
  CHECK(test::run_cli("glsl car.json -o link.glsl --target es300", p).exit_code == 0);
  CHECK(fs::is_symlink(p / "link.glsl"));
  CHECK(test::read_file(p / "real" / "target.glsl").find("#version 300 es") != std::string::npos);

  const auto before = snapshot(p);
  const auto n = test::run_cli("glsl car.json -o /dev/null", p);
  INFO(n.err);
  CHECK(n.exit_code == 0);
  CHECK(snapshot(p) == before);
  struct stat st {};
  REQUIRE(stat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));  // still the device
}

TEST_CASE("a folder as output is a command-line mistake, and a user's OUT.tmp is never touched") {
  test::TempDir dir;
  const fs::path p = project(dir);
  fs::create_directories(p / "folder.glsl");
  write(p / "out.glsl.tmp", "the user's own notes");
  write(p / ".out.glsl.tmp", "hidden notes");
  const auto before = snapshot(p);
  expect_unchanged(test::run_cli("glsl car.json -o folder.glsl", p), 2, "folder.glsl is a directory", before, p);
  const auto r = test::run_cli("glsl car.json -o out.glsl", p);
  CHECK(r.exit_code == 0);
  CHECK(test::read_file(p / "out.glsl.tmp") == "the user's own notes");
  CHECK(test::read_file(p / ".out.glsl.tmp") == "hidden notes");
  // And no temporary file is left beside it.
  for (const auto& name : test::listing(p)) CHECK(name.find(".lamina-") == std::string::npos);
}

TEST_CASE("standard output that cannot be written is an I/O error with the system's reason") {
  test::TempDir dir;
  const fs::path p = project(dir);
  for (const std::string args : {"validate car.json", "eval car.json --wi 0,0,1 --wo 0,0,1",
                                 "glsl car.json --model weidlich_wilkie -o -", "nodes", "classify car.json"}) {
    CAPTURE(args);
    const auto r = test::run_cli_wrapped("", args, p, "/dev/full");
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("cannot write standard output: No space left on device") != std::string::npos);
  }
}

TEST_CASE("a file size limit fails the write with its reason and leaves the previous output as it was") {
  test::TempDir dir;
  const fs::path p = project(dir);
  // Every command writes through the same writer; render stands for the images (a 400-pixel sample
  // sheet at one sample is some 18 KB, and quick under the sanitisers, where a plot takes half a minute).
  REQUIRE(test::run_cli("render car.json -o car.png --width 400 --spp 1", p).exit_code == 0);
  REQUIRE(test::run_cli("glsl car.json -o car.glsl --uniforms", p).exit_code == 0);
  const auto before = snapshot(p);
  // 4 KiB: less than any of these outputs.
  for (const std::string args : {"render car.json -o car.png --width 400 --spp 2",
                                 "glsl car.json -o car.glsl --uniforms", "gltf car.json -o car.gltf", "schema -o ."}) {
    CAPTURE(args);
    const auto r = test::run_cli_wrapped("prlimit --fsize=4096", args, p);
    expect_unchanged(r, 1, "File too large", before, p);
  }
}

TEST_CASE("a full disk fails the write with its reason and leaves the previous output as it was") {
  test::TempDir dir;
  const fs::path p = project(dir);
  const fs::path disk = p / "disk";
  fs::create_directories(disk);
  // A disk a quarter larger than the first output (the module and its table's side file).
  REQUIRE(test::run_cli("glsl car.json -o sized.glsl", p).exit_code == 0);
  const auto first = fs::file_size(p / "sized.glsl") + fs::file_size(p / "sized.uniforms.json");
  fs::remove(p / "sized.glsl");
  fs::remove(p / "sized.uniforms.json");
  const std::string size = "size=" + std::to_string((first * 5 / 4 / 4096 + 1) * 4096);
  if (getuid() != 0 || mount("tmpfs", disk.c_str(), "tmpfs", 0, size.c_str()) != 0) {
    MESSAGE(
        "a small tmpfs cannot be mounted here (not root, or no permission): the full-disk case is covered "
        "by the file size limit test only");
    return;
  }
  struct Unmount {
    fs::path path;
    ~Unmount() { umount(path.c_str()); }
  } unmount{disk};
  REQUIRE(test::run_cli("glsl car.json -o disk/car.glsl", p).exit_code == 0);
  const auto before = snapshot(p);
  // The next output needs room for its temporary beside the first one: the disk is full.
  // The image: a linear EXR of 1000 pixels at one sample is some 380 KB, more than the room left.
  for (const std::string args :
       {"glsl patina.json -o disk/car.glsl", "render car.json -o disk/car.exr --width 1000 --spp 1"}) {
    CAPTURE(args);
    expect_unchanged(test::run_cli(args, p), 1, "No space left on device", before, p);
  }
}

TEST_CASE("a read-only folder fails the write with its reason and writes nothing, even in another folder") {
  test::TempDir dir;
  const fs::path p = project(dir);
  fs::create_directories(p / "locked");
  fs::create_directories(p / "open");
  fs::permissions(p, fs::perms::all, fs::perm_options::add);  // the unprivileged user reads the inputs
  fs::permissions(p / "open", fs::perms::all, fs::perm_options::add);
  fs::permissions(p / "locked", fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  // As root, permission bits do not stop a write: run lamina as nobody when the test runs as root.
  const std::string as = getuid() == 0 ? "setpriv --reuid=nobody --regid=nogroup --clear-groups" : "";
  const auto before = snapshot(p);
  for (const std::string args :
       {"glsl car.json -o locked/car.glsl", "glsl car.json -o open/car.glsl --interface locked/car.json"}) {
    CAPTURE(args);
    expect_unchanged(test::run_cli_wrapped(as, args, p), 1, "Permission denied", before, p);
  }
}
