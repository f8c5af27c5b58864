// Hostile material and scene files, made at test time: nesting that would exhaust the stack, image
// headers that would exhaust memory, references that lead out of the asset folder or into FIFOs and
// devices, stacks beyond the back ends' capacity, text that would forge messages. Each must give
// exit code 2 with the file, the JSON pointer and what was expected, quickly, and write nothing.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "graph/cpu/image.h"
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

std::string nested(size_t depth, char open, char close) {
  std::string inner = open == '{' ? "1" : "";
  std::string text;
  text.reserve(depth * 6 + inner.size());
  for (size_t i = 0; i < depth; ++i) text += open == '{' ? "{\"k\":" : std::string(1, open);
  text += inner;
  text.append(depth, close);
  return text;
}

// One material whose lambert albedo is `albedo` (any JSON text) and whose weight texture is `file`.
std::string material_with(const std::string& albedo, const std::string& file = "") {
  std::string nodes = R"({"id": "base", "type": "substrate/lambert", "albedo": )" + albedo + "}";
  std::string surface = "@base";
  if (!file.empty()) {
    nodes += R"(, {"id": "other", "type": "substrate/lambert", "albedo": [0.1, 0.1, 0.1]},
      {"id": "mask", "type": "texture/image", "file": ")" +
             file + R"("},
      {"id": "blend", "type": "mix", "a": "@base", "b": "@other", "weight": "@mask.value"})";
    surface = "@blend";
  }
  return R"({"format": 1, "materials": [{"name": "m", "surface": ")" + surface + R"(", "nodes": [)" + nodes + "]}]}";
}

// A chain of `layers` coats over a Lambert base.
std::string chain(int layers) {
  std::string nodes;
  for (int i = 0; i < layers; ++i) {
    const std::string next = i + 1 < layers ? "@l" + std::to_string(i + 1) : "@base";
    nodes += R"({"id": "l)" + std::to_string(i) + R"(", "type": "layer", "interface": "@i)" + std::to_string(i) +
             R"(", "base": ")" + next + R"("}, {"id": "i)" + std::to_string(i) +
             R"(", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 2}, )";
  }
  nodes += R"({"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]})";
  return R"({"format": 1, "materials": [{"name": "chain", "surface": "@l0", "nodes": [)" + nodes + "]}]}";
}

// PNG chunks (ISO/IEC 15948 sec. 5.3) with their CRC-32, so that a header can say anything.
uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}
std::string be32(uint32_t v) { return {char(v >> 24), char((v >> 16) & 0xff), char((v >> 8) & 0xff), char(v & 0xff)}; }
std::string png_chunk(const std::string& type, const std::string& data) {
  return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
}
// A PNG that declares width x height pixels but holds no image data.
std::string png_header_only(uint32_t width, uint32_t height) {
  const std::string ihdr = be32(width) + be32(height) + std::string{char(1), char(0), char(0), char(0), char(0)};
  const std::string empty_deflate("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", empty_deflate) +
         png_chunk("IEND", "");
}
std::string real_png(int size) {
  std::vector<uint8_t> pixels(size_t(size * size * 3));
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(i * 37);
  const auto bytes = gltf::encode_png(size, size, 3, pixels);
  return std::string(bytes.begin(), bytes.end());
}

// Every command that reads a material, with an output in the folder where one is written.
const std::array<std::string, 5> kMaterialCommands{"validate", "eval --wi 0,0,1 --wo 0,0,1", "glsl -o out.glsl",
                                                   "gltf -o out.glb", "plot -o out.png"};

std::string command_on(const std::string& c, const std::string& file) {
  const size_t space = c.find(' ');
  return space == std::string::npos ? c + " " + file : c.substr(0, space) + " " + file + c.substr(space);
}

}  // namespace

TEST_CASE("JSON nested far beyond the limit is refused by every command, with the pointer where it got too deep") {
  test::TempDir dir;
  write(dir.path() / "deep_array.json", material_with(nested(45000, '[', ']')));
  write(dir.path() / "deep_object.json",
        R"({"format": 1, "notes": )" + nested(45000, '{', '}') + R"(, "materials": []})");
  const std::string limit = "nest deeper than " + std::to_string(kMaxJsonDepth) + " levels";
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    expect_refused(run_in(dir.path(), command_on(command, "deep_array.json")),
                   "deep_array.json:/materials/0/nodes/0/albedo/0/0/", limit);
    expect_refused(run_in(dir.path(), command_on(command, "deep_object.json")), "deep_object.json:/notes/k/k/k/",
                   limit);
  }
  // The same through a scene, whose material file is the deep one.
  write(dir.path() / "scene.json", R"({"format": 1, "materials": ["deep_array.json"],
    "objects": [{"name": "ball", "shape": "sphere", "material": "m"}]})");
  expect_refused(run_in(dir.path(), "gltf scene.json -o out.glb"), "deep_array.json:/materials/0/nodes/0/albedo/0/",
                 limit);
}

TEST_CASE("a truncated file of 400 KB of open brackets is reported at its nesting limit, not rebuilt per level") {
  test::TempDir dir;
  write(dir.path() / "brackets.json", R"({"format": 1, "materials": )" + std::string(400000, '['));
  // Well within the time limit: the pointer is built once, not once per level.
  const Outcome o = run_in(dir.path(), "validate brackets.json", 20);
  expect_refused(o, "brackets.json:/materials/0/0/0/", "nest deeper than");
  CHECK(o.run.err.size() < 4096);
}

TEST_CASE("image headers are checked against the pixel budget before any pixel is decoded") {
  test::TempDir dir;
  write(dir.path() / "huge.png", png_header_only(100000, 100000));
  write(dir.path() / "big.png", png_header_only(12000, 12000));
  write(dir.path() / "huge.json", material_with("[1, 1, 1]", "huge.png"));
  write(dir.path() / "big.json", material_with("[1, 1, 1]", "big.png"));
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    expect_refused(run_in(dir.path(), command_on(command, "huge.json")), "huge.json:/materials/0/nodes/2/file",
                   "100000 x 100000 pixels, more than the budget of " + std::to_string(kDefaultMaxImagePixels));
    expect_refused(run_in(dir.path(), command_on(command, "big.json")), "big.json:/materials/0/nodes/2/file",
                   "12000 x 12000 pixels");
  }
  // The budget is an option: a real 8 x 8 image passes under 64 pixels and is refused under 63.
  write(dir.path() / "small.png", real_png(8));
  write(dir.path() / "small.json", material_with("[1, 1, 1]", "small.png"));
  CHECK(run_in(dir.path(), "validate small.json --max-image-pixels 64").run.exit_code == 0);
  expect_refused(run_in(dir.path(), "eval small.json --wi 0,0,1 --wo 0,0,1 --max-image-pixels 63"),
                 "small.json:/materials/0/nodes/2/file", "8 x 8 pixels, more than the budget of 63");
}

TEST_CASE("an OpenEXR file of 50 KB whose header declares 100000 x 100000 pixels is refused before decoding") {
  test::TempDir dir;
  // A real 4 x 4 ZIP-compressed EXR from oiiotool, made to declare 100000 x 100000: its dataWindow
  // (box2i: xmin, ymin, xmax, ymax) rewritten and its offset table grown to one entry per 16 rows,
  // as OpenEXR expects (about 50 KB in all).
  REQUIRE(std::system(("oiiotool --pattern constant:color=0.5,0.5,0.5 4x4 3 --compression zip -o '" +
                       (dir.path() / "small.exr").string() + "' >/dev/null 2>&1")
                          .c_str()) == 0);
  std::string exr = test::read_file(dir.path() / "small.exr");
  const std::string field = std::string("dataWindow\0box2i\0", 17);
  const size_t at = exr.find(field);
  REQUIRE(at != std::string::npos);
  const int32_t corners[4] = {0, 0, 99999, 99999};
  exr.replace(at + field.size() + 4, 16, std::string(reinterpret_cast<const char*>(corners), 16));
  // The header is a list of (name, type, size, value) attributes ended by a 0 byte.
  size_t p = 8;
  while (exr[p] != '\0') {
    const size_t type_end = exr.find('\0', exr.find('\0', p) + 1);
    int32_t size = 0;
    std::memcpy(&size, exr.data() + type_end + 1, 4);
    p = type_end + 5 + size_t(size);
  }
  const size_t table = p + 1, extra = 100000 / 16 - 1;
  uint64_t first = 0;
  std::memcpy(&first, exr.data() + table, 8);
  first += extra * 8;
  std::string entries;
  for (size_t k = 0; k <= extra; ++k) entries.append(reinterpret_cast<const char*>(&first), 8);
  exr.replace(table, 8, entries);
  write(dir.path() / "huge.exr", exr);
  write(dir.path() / "huge.json", material_with("[1, 1, 1]", "huge.exr"));
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    expect_refused(run_in(dir.path(), command_on(command, "huge.json")), "huge.json:/materials/0/nodes/2/file",
                   "100000 x 100000 pixels");
  }
}

TEST_CASE("a truncated PNG is a user mistake at its file parameter, with lamina's words and no libpng text") {
  test::TempDir dir;
  const std::string png = real_png(64);
  write(dir.path() / "cut.png", png.substr(0, png.size() / 2));
  write(dir.path() / "cut.json", material_with("[1, 1, 1]", "cut.png"));
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    const Outcome o = run_in(dir.path(), command_on(command, "cut.json"));
    expect_refused(o, "cut.json:/materials/0/nodes/2/file: texture file 'cut.png' is not a readable image",
                   "truncated");
    CHECK(o.run.err.find("libpng") == std::string::npos);
  }
}

TEST_CASE("an image holding NaN or an infinite texel is refused where it is named: no clamp could remove it") {
  // A 2 x 1 float OpenEXR made by oiiotool from a portable float map (PFM: "PF", size, negative
  // scale for little-endian, then RGB rows); the second texel's green is the hostile value.
  test::TempDir dir;
  auto exr = [&](float green) {
    const float texels[6] = {0.5f, 0.5f, 0.5f, 0.25f, green, 0.25f};
    std::string pfm = "PF\n2 1\n-1.0\n";
    pfm.append(reinterpret_cast<const char*>(texels), sizeof texels);
    write(dir.path() / "texels.pfm", pfm);
    REQUIRE(std::system(("oiiotool '" + (dir.path() / "texels.pfm").string() + "' -d float -o '" +
                         (dir.path() / "texels.exr").string() + "' >/dev/null 2>&1")
                            .c_str()) == 0);
    std::string bytes = test::read_file(dir.path() / "texels.exr");
    fs::remove(dir.path() / "texels.pfm");
    fs::remove(dir.path() / "texels.exr");
    return bytes;
  };
  for (float hostile : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    CAPTURE(hostile);
    const std::string bytes = exr(hostile);
    CHECK_THROWS_WITH_AS(decode_linear_image(bytes, false, kDefaultMaxImagePixels),
                         doctest::Contains("texel (1, 0) is not a finite number"), ImageError);
    write(dir.path() / "hostile.exr", bytes);
    write(dir.path() / "hostile.json", material_with("[1, 1, 1]", "hostile.exr"));
    for (const std::string& command : kMaterialCommands) {
      CAPTURE(command);
      expect_refused(run_in(dir.path(), command_on(command, "hostile.json")),
                     "hostile.json:/materials/0/nodes/2/file: texture file 'hostile.exr'", "not a finite number");
    }
  }
  CHECK(decode_linear_image(exr(2.0f), false, kDefaultMaxImagePixels)->texels[1].g == 2.0f);
}

TEST_CASE("texture references that leave the asset folder, or name what is not a regular file, are refused") {
  test::TempDir root;
  const fs::path dir = root.path() / "project";
  fs::create_directories(dir / "textures");
  fs::create_directories(root.path() / "private");
  write(root.path() / "private" / "photo.png", real_png(4));
  write(dir / "textures" / "ok.png", real_png(4));
  fs::create_symlink(root.path() / "private" / "photo.png", dir / "textures" / "link.png");
  fs::create_directory_symlink(root.path() / "private", dir / "textures" / "linked_folder");
  REQUIRE(mkfifo((dir / "textures" / "pipe.png").c_str(), 0600) == 0);
  struct Case {
    std::string file, message;
  };
  const Case cases[] = {
      {"/etc/passwd", "is an absolute path, which lamina does not follow"},
      {(root.path() / "private" / "photo.png").string(), "is an absolute path"},
      {"../private/photo.png", "leads outside the folders lamina reads from"},
      {"textures/../../private/photo.png", "leads outside"},
      {"textures/link.png", "passes through a symbolic link to"},
      {"textures/linked_folder/photo.png", "passes through a symbolic link to"},
      {"textures/pipe.png", "is a FIFO (named pipe), not a regular file"},
      {"textures", "is a directory, not a regular file"},
      {"file:///etc/passwd", "is a 'file:' URI, which lamina does not follow"},
      {"textures\\\\ok.png", "contains a backslash"},
      {"textures/missing.png", "not found"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    write(dir / "m.json", material_with("[1, 1, 1]", c.file));
    for (const std::string command : {"validate", "gltf -o out.glb"}) {
      CAPTURE(command);
      expect_refused(run_in(dir, command_on(command, "m.json"), 20), "m.json:/materials/0/nodes/2/file: texture file",
                     c.message);
    }
  }
  // Inside the folder, and through links that stay inside it, is fine.
  write(dir / "m.json", material_with("[1, 1, 1]", "textures/ok.png"));
  CHECK(run_in(dir, "validate m.json").run.exit_code == 0);
}

TEST_CASE("--asset-root widens the folders references may reach, and a directory argument is its own root") {
  test::TempDir root;
  fs::create_directories(root.path() / "materials");
  fs::create_directories(root.path() / "textures");
  write(root.path() / "textures" / "mask.png", real_png(4));
  write(root.path() / "materials" / "m.json", material_with("[1, 1, 1]", "../textures/mask.png"));
  expect_refused(run_in(root.path(), "validate materials/m.json"), "m.json:/materials/0/nodes/2/file",
                 "leads outside the folders lamina reads from");
  CHECK(run_in(root.path(), "validate materials/m.json --asset-root .").run.exit_code == 0);
  CHECK(run_in(root.path(), "eval materials/m.json --wi 0,0,1 --wo 0,0,1 --asset-root .").run.exit_code == 0);
  CHECK(run_in(root.path(), "validate .").run.exit_code == 0);  // the directory given is the root
}

TEST_CASE("a scene's material, mesh and environment files follow the same rules") {
  test::TempDir root;
  const fs::path dir = root.path() / "scene";
  fs::create_directories(dir);
  write(root.path() / "outside.json", material_with("[1, 1, 1]"));
  write(dir / "m.json", material_with("[1, 1, 1]"));
  REQUIRE(mkfifo((dir / "pipe.json").c_str(), 0600) == 0);
  REQUIRE(mkfifo((dir / "pipe.glb").c_str(), 0600) == 0);
  write(dir / "huge.png", png_header_only(100000, 100000));
  struct Case {
    std::string scene, pointer, message;
  };
  const std::string ball = R"({"name": "ball", "shape": "sphere", "material": "m"})";
  const Case cases[] = {
      {R"({"format": 1, "materials": ["../outside.json"], "objects": [)" + ball + "]}", "/materials/0",
       "material file '../outside.json' leads outside"},
      {R"({"format": 1, "materials": ["pipe.json"], "objects": [)" + ball + "]}", "/materials/0",
       "material file 'pipe.json' is a FIFO"},
      {R"({"format": 1, "materials": ["m.json"], "objects": [{"name": "b", "shape": "mesh", "file": "pipe.glb",
         "material": "m"}]})",
       "/objects/0/file", "mesh file 'pipe.glb' is a FIFO"},
      {R"({"format": 1, "materials": ["m.json"], "lights": [{"name": "sky", "type": "environment", "file":
         "huge.png"}], "objects": [)" +
           ball + "]}",
       "/lights/0/file", "100000 x 100000 pixels"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.scene);
    write(dir / "s.json", c.scene);
    for (const std::string command : {"validate s.json", "gltf s.json -o out.glb"}) {
      CAPTURE(command);
      expect_refused(run_in(dir, command, 20), "s.json:" + c.pointer + ": ", c.message);
    }
  }
}

TEST_CASE("stacks beyond the back ends' capacity are refused by validate, and every command agrees") {
  test::TempDir dir;
  write(dir.path() / "chain2500.json", chain(2500));
  write(dir.path() / "chain64.json", chain(kMaxStackNodes));  // 64 layers and a base: one too many
  write(dir.path() / "chain63.json", chain(kMaxStackNodes - 1));
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    expect_refused(run_in(dir.path(), command_on(command, "chain2500.json")),
                   "chain2500.json:/materials/0/surface: the stack has 2501 layers, mixes and substrates",
                   "at most " + std::to_string(kMaxStackNodes));
    expect_refused(run_in(dir.path(), command_on(command, "chain64.json")),
                   "chain64.json:/materials/0/surface: the stack has " + std::to_string(kMaxStackNodes + 1), "");
  }
  CHECK(run_in(dir.path(), "validate chain63.json").run.exit_code == 0);
  CHECK(run_in(dir.path(), "eval chain63.json --wi 0,0,1 --wo 0,0,1").run.exit_code == 0);

  // Mixes sharing one stack on both sides double its lobes per level: 40 levels would be 2^40.
  std::string nodes = R"({"id": "m0", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]})";
  for (int i = 1; i <= 40; ++i)
    nodes += R"(, {"id": "m)" + std::to_string(i) + R"(", "type": "mix", "a": "@m)" + std::to_string(i - 1) +
             R"(", "b": "@m)" + std::to_string(i - 1) + R"(", "weight": 0.5})";
  write(dir.path() / "mixes.json",
        R"({"format": 1, "materials": [{"name": "m", "surface": "@m40", "nodes": [)" + nodes + "]}]}");
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    expect_refused(run_in(dir.path(), command_on(command, "mixes.json")), "mixes.json:/materials/0/surface",
                   "more than " + std::to_string(kMaxLobes) + " lobes");
  }

  // A chain of 100,000 remaps feeding a mix: no recursion over it, and more values than registers.
  std::string remaps = R"({"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
    {"id": "blend", "type": "mix", "a": "@base", "b": "@base", "weight": "@r0"},
    {"id": "tiles", "type": "texture/checker"})";
  const int count = 100000;
  for (int i = 0; i < count; ++i)
    remaps += R"(, {"id": "r)" + std::to_string(i) + R"(", "type": "math/remap", "value": ")" +
              (i + 1 < count ? "@r" + std::to_string(i + 1) : std::string("@tiles.value")) + "\"}";
  write(dir.path() / "remaps.json",
        R"({"format": 1, "materials": [{"name": "m", "surface": "@blend", "nodes": [)" + remaps + "]}]}");
  expect_refused(run_in(dir.path(), "validate remaps.json"), "remaps.json:/materials/0/surface",
                 "at most " + std::to_string(kMaxSlots));
}

TEST_CASE("100,000 dangling links give 100,000 short messages, found without a quadratic search") {
  // Each message once listed every id of the material and searched all of them for a suggestion:
  // 5,000 such links wrote 170 MB.
  test::TempDir dir;
  std::string nodes = R"({"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]})";
  const int count = 100000;
  for (int i = 0; i < count; ++i)
    nodes += R"(, {"id": "r)" + std::to_string(i) + R"(", "type": "math/remap", "value": "@missing)" +
             std::to_string(i) + "\"}";
  write(dir.path() / "dangling.json",
        R"({"format": 1, "materials": [{"name": "m", "surface": "@base", "nodes": [)" + nodes + "]}]}");
  const Outcome o = run_in(dir.path(), "validate dangling.json");
  expect_refused(o, "dangling.json:/materials/0/nodes/1/value: link to unknown node 'missing0'",
                 "node ids in this material: base, r0, r1");
  CHECK(o.run.err.find("/materials/0/nodes/100000/value: link to unknown node 'missing99999'") != std::string::npos);
  CHECK(o.run.err.find("... and 99978 more") != std::string::npos);
  CHECK(o.run.err.size() < size_t{count} * 400);
}

TEST_CASE("a cycle through 100,000 nodes is reported once, shortened, without recursion") {
  test::TempDir dir;
  std::string nodes = R"({"id": "base", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
    {"id": "blend", "type": "mix", "a": "@base", "b": "@base", "weight": "@r0"})";
  const int count = 100000;
  for (int i = 0; i < count; ++i)
    nodes += R"(, {"id": "r)" + std::to_string(i) + R"(", "type": "math/remap", "value": "@r)" +
             std::to_string((i + 1) % count) + "\"}";
  write(dir.path() / "cycle.json",
        R"({"format": 1, "materials": [{"name": "m", "surface": "@blend", "nodes": [)" + nodes + "]}]}");
  const Outcome o = run_in(dir.path(), "validate cycle.json");
  expect_refused(o, "cycle.json:/materials/0/nodes/", "cycle: r0 -> r1 -> r2");
  CHECK(o.run.err.find("more) -> r99999 -> r0") != std::string::npos);
  CHECK(o.run.err.size() < 4096);
}

TEST_CASE("a material file beyond the size limit is refused before it is parsed") {
  test::TempDir dir;
  std::string text = material_with("[1, 1, 1]");
  text.insert(text.size() - 1, ", \"padding\": \"" + std::string(kMaxJsonFileBytes, ' ') + "\"");
  write(dir.path() / "big.json", text);
  expect_refused(run_in(dir.path(), "validate big.json"), "big.json:: the file is",
                 "more than 64 MiB, the most lamina reads from such a file");
}

TEST_CASE("keys and strings are echoed with control characters escaped, so no message can be forged") {
  test::TempDir dir;
  write(dir.path() / "forged.json",
        R"({"format": 1, "materials": [{"name": "m", "surface": "@b", "nodes": [{"id": "b",
            "type": "x\u001b[31mred\nother.json:/x: fake error\u0000", "albedo": [1, 1, 1]}],
            "ke\u0007y\u009b": 1}]})");
  const Outcome o = run_in(dir.path(), "validate forged.json");
  expect_refused(o, "forged.json:/materials/0/nodes/0/type: unknown node type", "x\\x1b[31mred\\nother.json:/x");
  CHECK(o.run.err.find('\x1b') == std::string::npos);
  CHECK(o.run.err.find('\a') == std::string::npos);
  CHECK(o.run.err.find(std::string("\0", 1)) == std::string::npos);
  CHECK(o.run.err.find("\xc2\x9b") == std::string::npos);  // the C1 control CSI
  CHECK(o.run.err.find("ke\\x07y\\u009b") != std::string::npos);
  // Every line of the output is one message of the file, or the summary.
  size_t start = 0;
  while (start < o.run.err.size()) {
    const size_t end = o.run.err.find('\n', start);
    CHECK(o.run.err.compare(start, 12, "forged.json:") == 0);
    start = end == std::string::npos ? o.run.err.size() : end + 1;
  }
}

TEST_CASE("messages quote a hostile key or string by its start and length, not all of it") {
  test::TempDir dir;
  const std::string key(10000, 'k');
  write(dir.path() / "long_key.json",
        R"({"format": 1, "materials": [{"name": "m", "surface": "@b", "nodes": [{"id": "b",
            "type": "substrate/lambert", "albedo": [1, 1, 1], ")" +
            key + R"(": {"x": [1, }}]}]})");
  const Outcome o = run_in(dir.path(), "validate long_key.json");
  expect_refused(o, "long_key.json:/materials/0/nodes/0/" + key.substr(0, 32) + "...(a key of 10000 bytes)/x/1",
                 "malformed JSON");
  CHECK(o.run.err.size() < 1000);
  // An unterminated string of 100,000 bytes: the parser's quote of it keeps its last bytes.
  write(dir.path() / "open_string.json", "{\"format\": 1, \"materials\": \"" + std::string(100000, 's') + "\u0001");
  const Outcome s = run_in(dir.path(), "validate open_string.json");
  expect_refused(s, "open_string.json:/materials: malformed JSON", "(the last 64 of 1000");
  CHECK(s.run.err.size() < 1000);
}

TEST_CASE("a file reference longer than any path is refused by its start and length, before it is resolved") {
  test::TempDir dir;
  const std::string name = std::string(kMaxReferenceLength - 4, 'a') + ".png";  // exactly the limit
  const std::string longer = "a" + name;
  write(dir.path() / "long.json", material_with("[1, 1, 1]", longer));
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    const Outcome o = run_in(dir.path(), command_on(command, "long.json"));
    expect_refused(o, "long.json:/materials/0/nodes/2/file: texture file '" + longer.substr(0, 64) + "...'",
                   "is longer than any path lamina follows (4096 bytes)");
    CHECK(o.run.err.size() < 1000);
  }
  // At the limit it is an ordinary path: not found (no file system takes 4096-byte names).
  write(dir.path() / "limit.json", material_with("[1, 1, 1]", name));
  const Outcome at_limit = run_in(dir.path(), "validate limit.json");
  CHECK(at_limit.run.exit_code == 2);
  CHECK(at_limit.run.err.find("longer than any path") == std::string::npos);
}

TEST_CASE("a material name of 100,000 characters is refused by every command, not rendered as a label") {
  test::TempDir dir;
  std::string text = material_with("[1, 1, 1]");
  text.replace(text.find("\"m\""), 3, "\"" + std::string(100000, 'n') + "\"");
  write(dir.path() / "long.json", text);
  for (const std::string& command : kMaterialCommands) {
    CAPTURE(command);
    const Outcome o = run_in(dir.path(), command_on(command, "long.json"), 20);
    expect_refused(o, "long.json:/materials/0/name: expected a name of at most " + std::to_string(kMaxIdentifierLength),
                   "(a string of 100000 bytes)");
    CHECK(o.run.err.size() < 4096);
  }
}

TEST_CASE("a small scene cannot make lamina tessellate gigabytes: its distinct shapes have a vertex budget") {
  test::TempDir dir;
  fs::copy_file(test::source_dir() / "examples/materials/brass.json", dir.path() / "brass.json");
  // 100 spheres of 1024 segments, each of its own radius: about 3.8 GB of glTF before the budget.
  std::string objects;
  for (int i = 0; i < 100; ++i)
    objects += std::string(i ? ", " : "") + R"({"name": "b)" + std::to_string(i) +
               R"(", "shape": "sphere", "segments": 1024, "radius": )" + std::to_string(1.0 + i * 0.001) +
               R"(, "material": "brass"})";
  write(dir.path() / "spheres.json", R"({"format": 1, "materials": ["brass.json"], "objects": [)" + objects + "]}");
  for (const std::string command : {"validate spheres.json", "gltf spheres.json -o out.glb"}) {
    CAPTURE(command);
    expect_refused(run_in(dir.path(), command, 20), "spheres.json:/objects/15: with this object the scene's",
                   "more than the " + std::to_string(kMaxSceneVertices));
  }
  // The same sphere placed 100 times is one mesh, well within the budget.
  std::string same;
  for (int i = 0; i < 100; ++i)
    same += std::string(i ? ", " : "") + R"({"name": "b)" + std::to_string(i) +
            R"(", "shape": "sphere", "segments": 1024, "material": "brass"})";
  write(dir.path() / "same.json", R"({"format": 1, "materials": ["brass.json"], "objects": [)" + same + "]}");
  CHECK(run_in(dir.path(), "validate same.json").run.exit_code == 0);
}
