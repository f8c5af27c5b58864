// Hostile glTF files, made at test time, through lamina import and through a scene's mesh file:
// nesting that would exhaust the stack, GLB containers and buffer lengths that lie, ranges that
// overflow, URIs that lead out of the glTF file's folder or into FIFOs, devices and non-images.
// Each must give exit code 2 with the glTF pointer, quickly, and write nothing.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "graph/gltf/png_encode.h"
#include "graph/limits.h"
#include "hostile_support.h"
#include "test_support.h"

using namespace lamina;
using test::expect_refused;
using test::Outcome;
using test::run_in;
using test::write;

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string le32(uint32_t v) {
  return {char(v & 0xff), char((v >> 8) & 0xff), char((v >> 16) & 0xff), char((v >> 24) & 0xff)};
}

// A quad: four float positions and six 16-bit indices, 60 bytes in one buffer.
std::string quad_bytes() {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  return std::string(reinterpret_cast<const char*>(positions), 48) +
         std::string(reinterpret_cast<const char*>(indices), 12);
}

// The glTF JSON of the quad; its buffer `uri` (none: the BIN chunk of a .glb) and byteLength.
Json quad_json(const std::string& uri, size_t byte_length) {
  Json buffer{{"byteLength", byte_length}};
  if (!uri.empty()) buffer["uri"] = uri;
  return Json{
      {"asset", {{"version", "2.0"}}},
      {"buffers", Json::array({buffer})},
      {"bufferViews", Json::array({Json{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                                   Json{{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}})},
      {"accessors", Json::array({Json{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                                 Json{{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}})},
      {"meshes",
       Json::array({Json{{"primitives", Json::array({Json{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}})}}})},
      {"nodes", Json::array({Json{{"mesh", 0}}})},
      {"scenes", Json::array({Json{{"nodes", Json::array({0})}}})},
      {"scene", 0}};
}

// A .glb of `json` and `bin`, each chunk padded to 4 bytes, the header's length true unless given.
std::string glb(const std::string& json, const std::string& bin, int64_t header_length = -1) {
  std::string j = json, b = bin;
  while (j.size() % 4) j += ' ';
  while (b.size() % 4) b += '\0';
  std::string chunks = le32(uint32_t(j.size())) + le32(0x4E4F534Au) + j;
  if (!b.empty()) chunks += le32(uint32_t(b.size())) + le32(0x004E4942u) + b;
  const uint32_t length = header_length >= 0 ? uint32_t(header_length) : uint32_t(12 + chunks.size());
  return le32(0x46546C67u) + le32(2) + le32(length) + chunks;
}

// A material with a base colour texture whose image is `uri`, plus an unused image `unused`.
Json textured_json(const std::string& uri, const std::string& unused = "") {
  Json images = Json::array({Json{{"uri", uri}}});
  if (!unused.empty()) images.push_back(Json{{"uri", unused}});
  return Json{
      {"asset", {{"version", "2.0"}}},
      {"materials",
       Json::array({Json{{"name", "painted"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}})},
      {"textures", Json::array({Json{{"source", 0}}})},
      {"images", images}};
}

std::string png(int size) {
  std::vector<uint8_t> pixels(size_t(size * size * 3), 128);
  const auto bytes = gltf::encode_png(size, size, 3, pixels);
  return std::string(bytes.begin(), bytes.end());
}

// `name` as a scene's mesh file, checked by lamina validate; the scene lies next to it.
Outcome validate_as_mesh(const fs::path& dir, const std::string& name) {
  fs::copy_file(test::source_dir() / "examples/materials/brass.json", dir / "brass.json",
                fs::copy_options::skip_existing);
  write(dir / "scene.json", R"({"format": 1, "materials": ["brass.json"], "objects": [{"name": "quad",
    "shape": "mesh", "file": ")" +
                                name + R"(", "material": "brass"}]})");
  return run_in(dir, "validate scene.json");
}

}  // namespace

TEST_CASE("glTF extras nested 47,000 deep are refused in a .gltf and in a .glb's JSON chunk, at their pointer") {
  test::TempDir dir;
  std::string deep(47000, '[');
  deep += std::string(47000, ']');
  Json quad = quad_json("", quad_bytes().size());
  std::string json = quad.dump();
  json.insert(json.size() - 1, ",\"extras\":" + deep);
  write(dir.path() / "deep.glb", glb(json, quad_bytes()));
  std::string textured = textured_json("texture.png").dump();
  textured.insert(textured.size() - 1, ",\"extras\":" + deep);
  write(dir.path() / "deep.gltf", textured);
  write(dir.path() / "texture.png", png(4));
  const std::string limit = "nest deeper than " + std::to_string(kMaxJsonDepth) + " levels";
  expect_refused(run_in(dir.path(), "import deep.gltf -o out/m.json"), "deep.gltf:/extras/0/0/0/", limit);
  expect_refused(run_in(dir.path(), "import deep.glb -o out/m.json"), "deep.glb:/extras/0/0/0/", limit);
  expect_refused(validate_as_mesh(dir.path(), "deep.glb"), "deep.glb:/extras/0/0/0/", limit);
}

TEST_CASE("a .glb whose buffer length disagrees with its BIN chunk is refused before any byte is read") {
  test::TempDir dir;
  const std::string bin = quad_bytes();
  struct Case {
    const char* name;
    std::string glb;
    const char* pointer;
    const char* message;
  };
  const Case cases[] = {
      {"longer.glb", glb(quad_json("", 4096).dump(), bin), "/buffers/0/byteLength",
       "byteLength = 4096, but the BIN chunk holds 60 bytes"},
      {"shorter.glb", glb(quad_json("", 40).dump(), bin + std::string(64, '\0')), "/bufferViews/1/byteLength",
       "ends beyond its buffer"},
      {"padded_too_much.glb", glb(quad_json("", 60).dump(), bin + std::string(64, '\0')), "/buffers/0/byteLength",
       "at most 3 bytes of padding"},
      {"zero.glb", glb(quad_json("", 0).dump(), bin), "/buffers/0/byteLength", "byteLength = 0 is out of range"},
      {"no_bin.glb", glb(quad_json("", 60).dump(), ""), "/buffers/0", "the .glb has none"},
      {"header_length.glb", glb(quad_json("", 60).dump(), bin, 100000), "", "the header says the file has 100000"},
  };
  for (const Case& c : cases) {
    CAPTURE(std::string(c.name));
    write(dir.path() / c.name, c.glb);
    // A problem of the file as a whole is reported at the scene's reference to it, naming the file.
    const std::string where = *c.pointer ? std::string(c.name) + ":" + c.pointer + ": "
                                         : "scene.json:/objects/0/file: " + (dir.path() / c.name).string() + ": ";
    expect_refused(validate_as_mesh(dir.path(), c.name), where, c.message);
  }
}

TEST_CASE("a .glb container that lies about its chunks is refused with the byte offset") {
  test::TempDir dir;
  const std::string json = quad_json("", 60).dump(), bin = quad_bytes();
  const std::string good = glb(json, bin);
  std::string beyond = good;  // the JSON chunk claims more bytes than the file has
  beyond.replace(12, 4, le32(1u << 30));
  std::string misaligned = good;  // a JSON chunk length that is not a multiple of 4
  misaligned.replace(12, 4, le32(uint32_t(good.size() - 12 - 8 - 8 - 60 - 1)));
  const std::string bin_first = le32(0x46546C67u) + le32(2) +
                                le32(uint32_t(12 + 8 + 60 + 8 + ((json.size() + 3) / 4 * 4))) + le32(60) +
                                le32(0x004E4942u) + bin + le32(uint32_t((json.size() + 3) / 4 * 4)) +
                                le32(0x4E4F534Au) + json + std::string((4 - json.size() % 4) % 4, ' ');
  const std::string two_bins = [&] {
    std::string s = good + le32(60) + le32(0x004E4942u) + bin;
    s.replace(8, 4, le32(uint32_t(s.size())));
    return s;
  }();
  struct Case {
    const char* name;
    std::string bytes;
    const char* message;
  };
  for (const Case& c : {Case{"beyond.glb", beyond, "beyond the end of the file"},
                        Case{"misaligned.glb", misaligned, "not a multiple of 4"},
                        Case{"bin_first.glb", bin_first, "the first chunk is not the JSON chunk"},
                        Case{"two_bins.glb", two_bins, "only the second chunk may be"},
                        Case{"short.glb", std::string("glTF\2\0\0\0", 8), "fewer than its 12-byte header"}}) {
    CAPTURE(std::string(c.name));
    write(dir.path() / c.name, c.bytes);
    expect_refused(validate_as_mesh(dir.path(), c.name),
                   "scene.json:/objects/0/file: " + (dir.path() / c.name).string() + ": not a valid .glb", c.message);
    expect_refused(run_in(dir.path(), std::string("import ") + c.name + " -o out/m.json"),
                   std::string(c.name) + ":: not a valid .glb", c.message);
  }
}

TEST_CASE("accessor and buffer view ranges that overflow are refused at their pointers") {
  test::TempDir dir;
  Json huge_count = quad_json("", 60);
  huge_count["accessors"][0]["count"] = uint64_t(1) << 62;
  Json huge_offset = quad_json("", 60);
  huge_offset["bufferViews"][0]["byteOffset"] = std::numeric_limits<uint64_t>::max() - 8;
  Json misaligned = quad_json("", 60);
  misaligned["accessors"][1]["byteOffset"] = 1;
  Json stride = quad_json("", 60);
  stride["bufferViews"][0]["byteStride"] = 6;
  struct Case {
    const char* name;
    Json json;
    const char* pointer;
    const char* message;
  };
  for (const Case& c :
       {Case{"count.glb", huge_count, "/accessors/0/count", "reach beyond buffer view 0"},
        Case{"offset.glb", huge_offset, "/bufferViews/0/byteOffset", "is out of range"},
        Case{"aligned.glb", misaligned, "/accessors/1/byteOffset", "multiple of its component size"},
        Case{"stride.glb", stride, "/bufferViews/0/byteStride", "byteStride = 6 is not a multiple of 4"}}) {
    CAPTURE(std::string(c.name));
    write(dir.path() / c.name, glb(c.json.dump(), quad_bytes()));
    expect_refused(validate_as_mesh(dir.path(), c.name), std::string(c.name) + ":" + c.pointer + ": ", c.message);
  }
}

TEST_CASE("buffer URIs may only name regular files inside the glTF file's folder") {
  test::TempDir root;
  const fs::path dir = root.path() / "model";
  fs::create_directories(dir / "folder");
  write(root.path() / "outside.bin", quad_bytes());
  write(dir / "quad.bin", quad_bytes());
  fs::create_symlink(root.path() / "outside.bin", dir / "link.bin");
  REQUIRE(mkfifo((dir / "pipe.bin").c_str(), 0600) == 0);
  struct Case {
    std::string uri, message;
  };
  const Case cases[] = {
      {"pipe.bin", "is a FIFO (named pipe), not a regular file"},
      {"folder", "is a directory, not a regular file"},
      {"/etc/passwd", "is an absolute path, which lamina does not follow"},
      {"../outside.bin", "leads outside the folders lamina reads from"},
      {"folder/..%2F..%2Foutside.bin", "leads outside the folders lamina reads from"},
      {"link.bin", "passes through a symbolic link to"},
      {"file:///etc/passwd", "is a 'file:' URI"},
      {"http://example.com/quad.bin", "is a 'http:' URI"},
      {"/dev/zero", "is an absolute path"},
      {"data:application/octet-stream,AAAA", "not base64-encoded"},
      {"data:application/octet-stream;base64,A", "not valid base64"},
      {"missing.bin", "not found"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.uri);
    write(dir / "quad.gltf", quad_json(c.uri, 60).dump());
    expect_refused(validate_as_mesh(dir, "quad.gltf"), "quad.gltf:/buffers/0/uri: ", c.message);
  }
  write(dir / "quad.gltf", quad_json("quad.bin", 60).dump());
  CHECK(validate_as_mesh(dir, "quad.gltf").run.exit_code == 0);
}

TEST_CASE("import reads only the images its materials use, and extracts only what decodes as an image") {
  test::TempDir root;
  const fs::path dir = root.path() / "model";
  fs::create_directories(dir);
  write(dir / "texture.png", png(4));
  write(dir / "notes.txt", "not an image");
  write(root.path() / "private.png", png(4));
  REQUIRE(mkfifo((dir / "pipe.png").c_str(), 0600) == 0);
  struct Case {
    std::string uri, pointer, message;
  };
  const Case cases[] = {
      {"notes.txt", "/images/0", "the image does not decode"},
      {"/etc/passwd", "/images/0/uri", "is an absolute path"},
      {"../private.png", "/images/0/uri", "leads outside"},
      {"pipe.png", "/images/0/uri", "is a FIFO"},
      {"data:image/png;base64,iVBORw0KGgo=", "/images/0", "the image does not decode"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.uri);
    write(dir / "m.gltf", textured_json(c.uri).dump());
    expect_refused(run_in(dir, "import m.gltf -o out/m.json"), "m.gltf:" + c.pointer + ": ", c.message);
  }
  // An unused image naming a FIFO or /etc/passwd is never opened: the import goes through.
  write(dir / "m.gltf", textured_json("texture.png", "pipe.png").dump());
  const Outcome fine = run_in(dir, "import m.gltf -o out/m.json");
  INFO(fine.run.err);
  CHECK(fine.run.exit_code == 0);
  CHECK(fs::exists(dir / "out" / "m.json"));
  CHECK(fs::exists(dir / "out" / "texture.png"));
  CHECK_FALSE(fs::exists(dir / "out" / "pipe.png"));
}
