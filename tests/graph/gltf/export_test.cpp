// glTF export: structure, counts, the extension's exact graph, the fallback, determinism.
#include <doctest/doctest.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "graph/gltf/export.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "test_support.h"

using namespace lamina;
using Json = nlohmann::json;

namespace {

uint32_t u32(const std::vector<unsigned char>& b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// The JSON chunk of a .glb, after checking the container's header and chunk layout.
Json glb_json(const std::vector<unsigned char>& glb, size_t* bin_size = nullptr) {
  REQUIRE(glb.size() >= 20);
  CHECK(u32(glb, 0) == 0x46546C67u);
  CHECK(u32(glb, 4) == 2u);
  CHECK(u32(glb, 8) == glb.size());
  const uint32_t json_length = u32(glb, 12);
  CHECK(json_length % 4 == 0);
  CHECK(u32(glb, 16) == 0x4E4F534Au);
  Json j = Json::parse(std::string(glb.begin() + 20, glb.begin() + 20 + json_length));
  const size_t bin_at = 20 + json_length;
  if (bin_at < glb.size()) {
    CHECK(u32(glb, bin_at + 4) == 0x004E4942u);
    CHECK(u32(glb, bin_at) % 4 == 0);
    CHECK(bin_at + 8 + u32(glb, bin_at) == glb.size());
    if (bin_size) *bin_size = u32(glb, bin_at);
  }
  return j;
}

Scene sheet_of(const std::filesystem::path& file) {
  CheckedFile checked = check_file(file);
  REQUIRE(checked.ok());
  return sample_sheet(checked.document, file);
}

gltf::ExportOptions quick() {
  gltf::ExportOptions o;
  o.fallback.bake_size = 32;
  o.fallback.max_states = 3;
  return o;
}

const Json& find_material(const Json& gltf, const std::string& name) {
  for (const auto& m : gltf["materials"])
    if (m["name"] == name) return m;
  FAIL("no material " << name);
  static Json none;
  return none;
}

}  // namespace

TEST_CASE("glTF export: a material file becomes a sheet of spheres with the exact graph in our extension") {
  for (const auto& file : test::example_files()) {
    CAPTURE(file);
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    Scene scene = sample_sheet(checked.document, file);
    gltf::Export out = gltf::export_scene(scene, "sheet.glb", quick());
    REQUIRE(out.files.size() == 1);
    size_t bin_size = 0;
    Json j = glb_json(out.files[0].bytes, &bin_size);
    CHECK(j["asset"]["version"] == "2.0");
    CHECK(j["buffers"].size() == 1);
    const size_t byte_length = j["buffers"][0]["byteLength"];
    CHECK(byte_length <= bin_size);
    CHECK(bin_size - byte_length < 4);  // the BIN chunk only pads to four bytes
    CHECK_FALSE(j["buffers"][0].contains("uri"));
    CHECK_FALSE(j.contains("extensionsRequired"));
    const auto used = j["extensionsUsed"].get<std::vector<std::string>>();
    CHECK(std::find(used.begin(), used.end(), gltf::kExtensionName) != used.end());
    const size_t count = checked.document.materials.size();
    CHECK(j["meshes"].size() == count);
    CHECK(j["materials"].size() == count);
    for (const auto& m : checked.document.materials) {
      const Json& gm = find_material(j, m.name);
      const Json& ext = gm["extensions"][gltf::kExtensionName];
      CHECK(ext["format"] == 1);
      // The extension's material is the canonical text of the source material, value for value.
      Document single;
      single.materials.push_back(m);
      CHECK(ext["material"] == Json::parse(write_document(single))["materials"][0]);
      for (const auto& node : m.nodes)
        if (node.type == "texture/image") {
          REQUIRE(ext["textures"].contains(node.id));
          const int texture = ext["textures"][node.id]["index"];
          const int image = j["textures"][texture]["source"];
          CHECK(j["images"][image]["mimeType"] == "image/png");
        }
      // Every extension the material uses is declared.
      for (const auto& [name, value] : gm["extensions"].items())
        CHECK(std::find(used.begin(), used.end(), name) != used.end());
    }
  }
}

TEST_CASE("glTF export: vertex data is valid glTF: bounds, unit normals, unit tangents with a sign") {
  Scene scene = sheet_of(test::source_dir() / "examples/materials/car_paint.json");
  gltf::Export out = gltf::export_scene(scene, "car.glb", quick());
  size_t bin_size = 0;
  Json j = glb_json(out.files[0].bytes, &bin_size);
  const auto& glb = out.files[0].bytes;
  const size_t bin_at = 20 + u32(glb, 12) + 8;
  auto floats = [&](int accessor_index) {
    const Json& a = j["accessors"][accessor_index];
    const Json& v = j["bufferViews"][a["bufferView"].get<int>()];
    CHECK(a["componentType"] == 5126);
    CHECK(v["byteOffset"].get<size_t>() % 4 == 0);
    std::vector<float> values(v["byteLength"].get<size_t>() / 4);
    std::memcpy(values.data(), glb.data() + bin_at + v["byteOffset"].get<size_t>(), values.size() * 4);
    return values;
  };
  const Json& attributes = j["meshes"][0]["primitives"][0]["attributes"];
  auto positions = floats(attributes["POSITION"]);
  const Json& pa = j["accessors"][attributes["POSITION"].get<int>()];
  for (int c = 0; c < 3; ++c) {
    float lo = 1e30f, hi = -1e30f;
    for (size_t i = static_cast<size_t>(c); i < positions.size(); i += 3) {
      lo = std::min(lo, positions[i]);
      hi = std::max(hi, positions[i]);
    }
    CHECK(pa["min"][c].get<float>() == lo);
    CHECK(pa["max"][c].get<float>() == hi);
  }
  auto normals = floats(attributes["NORMAL"]);
  for (size_t i = 0; i < normals.size(); i += 3)
    CHECK(std::abs(
              std::sqrt(normals[i] * normals[i] + normals[i + 1] * normals[i + 1] + normals[i + 2] * normals[i + 2]) -
              1.0f) < 1e-5f);
  auto tangents = floats(attributes["TANGENT"]);
  for (size_t i = 0; i < tangents.size(); i += 4) {
    CHECK(std::abs(std::abs(tangents[i + 3]) - 1.0f) == 0.0f);
    CHECK(std::abs(std::sqrt(tangents[i] * tangents[i] + tangents[i + 1] * tangents[i + 1] +
                             tangents[i + 2] * tangents[i + 2]) -
                   1.0f) < 1e-5f);
  }
}

TEST_CASE("glTF export: .gltf writes its buffer next to it, and output is byte-for-byte deterministic") {
  Scene scene = sheet_of(test::source_dir() / "examples/materials/patina_map_copper.json");
  gltf::Export a = gltf::export_scene(scene, "dir/patina.gltf", quick());
  gltf::Export b = gltf::export_scene(scene, "dir/patina.gltf", quick());
  REQUIRE(a.files.size() == 2);
  CHECK(a.files[0].path == std::filesystem::path("dir/patina.gltf"));
  CHECK(a.files[1].path == std::filesystem::path("dir/patina.bin"));
  CHECK(a.files[0].bytes == b.files[0].bytes);
  CHECK(a.files[1].bytes == b.files[1].bytes);
  Json j = Json::parse(std::string(a.files[0].bytes.begin(), a.files[0].bytes.end()));
  CHECK(j["buffers"][0]["uri"] == "patina.bin");
  CHECK(j["buffers"][0]["byteLength"] == a.files[1].bytes.size());
  // The glb of the same scene holds the same JSON apart from the buffer's uri.
  gltf::Export glb = gltf::export_scene(scene, "dir/patina.glb", quick());
  Json g = glb_json(glb.files[0].bytes);
  j["buffers"][0].erase("uri");
  CHECK(g == j);
}

TEST_CASE("glTF export: textured materials get baked fallback textures, uniform ones plain factors") {
  Scene patina = sheet_of(test::source_dir() / "examples/materials/patina_map_copper.json");
  gltf::Export out = gltf::export_scene(patina, "p.glb", quick());
  REQUIRE(out.materials.size() == 1);
  const auto& f = out.materials[0].fallback;
  CHECK(f.interpolated);  // the grey map has more levels than max_states
  CHECK(f.states.size() == 3);
  CHECK(f.metallic_roughness.has_value());  // copper (metal) against patina (dielectric)
  Json j = glb_json(out.files[0].bytes);
  const Json& pbr = j["materials"][0]["pbrMetallicRoughness"];
  CHECK(pbr.contains("metallicRoughnessTexture"));
  CHECK(pbr["metallicFactor"] == 1.0);
  // Metallic in the baked texture spans from patina (about 0) to copper (about 1).
  uint8_t lo = 255, hi = 0;
  for (size_t t = 0; t < f.metallic_roughness->pixels.size(); t += 3) {
    lo = std::min(lo, f.metallic_roughness->pixels[t + 2]);
    hi = std::max(hi, f.metallic_roughness->pixels[t + 2]);
  }
  CHECK(lo < 40);
  CHECK(hi > 215);

  Scene checker = sheet_of(test::source_dir() / "examples/materials/checker_tiles.json");
  gltf::Export c = gltf::export_scene(checker, "c.glb", quick());
  CHECK_FALSE(c.materials[0].fallback.interpolated);
  CHECK(c.materials[0].fallback.states.size() == 2);  // two tiles: two exact fits
  CHECK(c.materials[0].fallback.base_color.has_value());

  Scene car = sheet_of(test::source_dir() / "examples/materials/car_paint.json");
  gltf::Export plain = gltf::export_scene(car, "car.glb", quick());
  const auto& cf = plain.materials[0].fallback;
  CHECK(cf.states.size() == 1);
  CHECK_FALSE(cf.base_color.has_value());
  CHECK_FALSE(cf.metallic_roughness.has_value());
  Json cj = glb_json(plain.files[0].bytes);
  CHECK_FALSE(cj.contains("textures"));
  CHECK_FALSE(cj.contains("images"));
}

TEST_CASE("glTF export: the showcase scene has one mesh and node per object, its cameras and lights") {
  Diagnostics d;
  Scene scene = read_scene_file(test::source_dir() / "examples/scenes/showcase.json", d);
  REQUIRE(d.ok());
  gltf::Export out = gltf::export_scene(scene, "showcase.glb", quick());
  Json j = glb_json(out.files[0].bytes);
  size_t punctual = 0;
  for (const auto& l : scene.lights) punctual += l.type != LightType::Environment;
  CHECK(j["meshes"].size() == scene.objects.size());
  CHECK(j["nodes"].size() == scene.objects.size() + scene.cameras.size() + punctual);
  CHECK(j["scenes"][0]["nodes"].size() == j["nodes"].size());
  CHECK(j.value("cameras", Json::array()).size() == scene.cameras.size());
  if (punctual) CHECK(j["extensions"]["KHR_lights_punctual"]["lights"].size() == punctual);
  std::set<std::string> names;
  for (const auto& o : scene.objects) names.insert(o.material);
  CHECK(j["materials"].size() == names.size());
  // Nodes are labelled with the objects' names.
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    bool found = false;
    for (const auto& n : j["nodes"]) found = found || n["name"] == scene.objects[i].name;
    CHECK(found);
  }
}

TEST_CASE("lamina gltf: bad output names, invalid inputs and a missing file exit non-zero and write nothing") {
  test::TempDir dir;
  auto r = test::run_cli("gltf examples/materials/car_paint.json -o " + (dir.path() / "car.obj").string(),
                         test::source_dir());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find(".gltf or .glb") != std::string::npos);
  r = test::run_cli("gltf tests/data/bad/cycle_two_layers.json -o " + (dir.path() / "bad.glb").string(),
                    test::source_dir());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("tests/data/bad/cycle_two_layers.json:/materials/0") != std::string::npos);
  r = test::run_cli("gltf no_such_file.json -o " + (dir.path() / "none.glb").string(), test::source_dir());
  CHECK(r.exit_code == 1);
  CHECK(std::filesystem::is_empty(dir.path()));

  r = test::run_cli(
      "gltf examples/materials/gold_paint.json --report --bake-size 16 -o " + (dir.path() / "gold.gltf").string(),
      test::source_dir());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(std::filesystem::exists(dir.path() / "gold.gltf"));
  CHECK(std::filesystem::exists(dir.path() / "gold.bin"));
  CHECK(r.out.find("gold_paint") != std::string::npos);
  CHECK(r.out.find("albedo0") != std::string::npos);
}
