// glTF export: structure, counts, the extension's exact graph, the fallback, determinism.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <set>

#include "graph/compile.h"
#include "graph/gltf/export.h"
#include "graph/gltf/fallback.h"
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

// Under the sanitisers one fit a material: more repeat the same code at 5 times the cost.
#ifdef LAMINA_SANITIZED
constexpr int kQuickStates = 1;
#else
constexpr int kQuickStates = 3;
#endif
gltf::ExportOptions quick() {
  gltf::ExportOptions o;
  o.fallback.bake_size = 32;
  o.fallback.max_states = kQuickStates;
  return o;
}

// The element of one of the glTF's arrays ("materials", "nodes", ...) with that name; fails the
// test when there is none.
const Json& named(const Json& gltf, const char* array, const std::string& name) {
  for (const auto& element : gltf[array])
    if (element["name"] == name) return element;
  FAIL("no " << array << " element named " << name);
  static Json none;
  return none;
}

const Json& find_material(const Json& gltf, const std::string& name) { return named(gltf, "materials", name); }

}  // namespace

TEST_CASE("glTF export: a material file becomes a sheet of spheres with the exact graph in our extension") {
  // Under the sanitisers every second example: the round trip's sweep (offset 1) exports the others'
  // sheets.
  for (const auto& file : test::swept_example_files(0)) {
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
    // Each material's sphere and, after all spheres, each sphere's label (a quad and its material).
    const size_t count = checked.document.materials.size();
    CHECK(j["meshes"].size() == 2 * count);
    CHECK(j["materials"].size() == 2 * count);
    CHECK(out.materials.size() == count);
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
  // Three fits at most, in every build: this test counts them.
  gltf::ExportOptions options = quick();
  options.fallback.max_states = 3;
  Scene patina = sheet_of(test::source_dir() / "examples/materials/patina_map_copper.json");
  gltf::Export out = gltf::export_scene(patina, "p.glb", options);
  REQUIRE(out.materials.size() == 1);
  const auto& f = out.materials[0].fallback;
  CHECK(f.interpolated);  // the grey map has more levels than max_states
  CHECK(f.states.size() == 3);
  CHECK(f.metallic_roughness.has_value());  // copper (metal) against patina (dielectric)
  Json j = glb_json(out.files[0].bytes);
  const Json& pbr = j["materials"][0]["pbrMetallicRoughness"];
  CHECK(pbr.contains("metallicRoughnessTexture"));
  CHECK(pbr["metallicFactor"] == 1.0);
  // Metallic in the baked texture spans from patina (at most a quarter: the fit lends the green
  // patina a little metallic sheen at grazing views) to copper (about 1).
  uint8_t lo = 255, hi = 0;
  for (size_t t = 0; t < f.metallic_roughness->pixels.size(); t += 3) {
    lo = std::min(lo, f.metallic_roughness->pixels[t + 2]);
    hi = std::max(hi, f.metallic_roughness->pixels[t + 2]);
  }
  CHECK(lo < 64);
  CHECK(hi > 215);

  Scene checker = sheet_of(test::source_dir() / "examples/materials/checker_tiles.json");
  gltf::Export c = gltf::export_scene(checker, "c.glb", options);
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
  // The only texture is the sphere's label.
  REQUIRE(cj["textures"].size() == 1);
  CHECK(cj["images"].size() == 1);
  CHECK_FALSE(cj["materials"][0]["pbrMetallicRoughness"].contains("baseColorTexture"));
  CHECK(cj["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"]["index"] == 0);
}

TEST_CASE(
    "glTF export: a thin-film surface writes KHR_materials_iridescence, with a thickness texture where it varies") {
  // soap_film: a film of index 1.334 (green) whose thickness a noise spreads over 100 to 900 nm.
  const auto file = test::source_dir() / "examples/materials/soap_film.json";
  gltf::Export out = gltf::export_scene(sheet_of(file), "film.glb", quick());
  const Json j = glb_json(out.files[0].bytes);
  const Json& film = find_material(j, "soap_film")["extensions"]["KHR_materials_iridescence"];
  CHECK(film["iridescenceFactor"] == 1.0);
  CHECK(film["iridescenceIor"].get<double>() == doctest::Approx(1.334).epsilon(1e-6));
  const double thinnest = film["iridescenceThicknessMinimum"], thickest = film["iridescenceThicknessMaximum"];
  // The fit moves each state's thickness by less than a quarter wave (550 / (4 x 1.334) nm) to match
  // the colours the extension's cruder film gives.
  CHECK(thinnest >= 100.0 - 104.0);
  CHECK(thickest <= 900.0 + 104.0);
  CHECK(thinnest < thickest);
  REQUIRE(film.contains("iridescenceThicknessTexture"));
  const auto used = j["extensionsUsed"].get<std::vector<std::string>>();
  CHECK(std::find(used.begin(), used.end(), "KHR_materials_iridescence") != used.end());
  // Materials without a film write none.
  const auto brass = test::source_dir() / "examples/materials/brass.json";
  const Json plain = glb_json(gltf::export_scene(sheet_of(brass), "brass.glb", quick()).files[0].bytes);
  CHECK_FALSE(find_material(plain, "brass")["extensions"].contains("KHR_materials_iridescence"));
}

TEST_CASE("glTF export: a coat tilted by a texture gets a clearcoatNormalTexture, its flat base no normalTexture") {
  Scene sheet = sheet_of(test::source_dir() / "tests/data/gltf/tilted_coat.json");
  gltf::ExportOptions options = quick();
  options.fallback.bake_size = 64;
  gltf::Export out = gltf::export_scene(sheet, "coat.glb", options);
  REQUIRE(out.materials.size() == 1);
  CHECK(out.materials[0].fallback.clearcoat_normal.has_value());
  Json j = glb_json(out.files[0].bytes);
  const Json& material = find_material(j, "tilted_coat");
  CHECK_FALSE(material.contains("normalTexture"));
  const Json& coat = material["extensions"]["KHR_materials_clearcoat"];
  REQUIRE(coat.contains("clearcoatNormalTexture"));
  const int texture = coat["clearcoatNormalTexture"]["index"].get<int>();
  REQUIRE(texture >= 0);
  REQUIRE(size_t(texture) < j["textures"].size());
  // Its own image, not the label's or another baked map's.
  const int image = j["textures"][size_t(texture)]["source"].get<int>();
  for (size_t t = 0; t < j["textures"].size(); ++t)
    if (int(t) != texture) CHECK(j["textures"][t]["source"].get<int>() != image);
}

TEST_CASE("glTF export: a material bakes at twice its finest detail over uv, a power of two from 64 to 512") {
  auto program_of = [](const std::string& name) {
    const std::filesystem::path file = test::source_dir() / "examples/materials" / name;
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    return compile(*checked.graphs[0], file.string());
  };
  // Each case's finest detail worked out from the file: 2 x detail, rounded up to a power of two.
  struct Case {
    const char* file;
    double detail;  // features per uv unit
  };
  const Case cases[] = {
      {"checker_tiles.json", 8.0},                    // 8 x 8 checks
      {"patina_map_copper.json", 256.0},              // a 256 x 256 mask, tiled once
      {"procedural_patina_copper.json", 6.0 * 16.0},  // 6 cells, 5 octaves of lacunarity 2
      {"sunstone.json", 600.0},                       // 600 cells, capped
      {"flake_car_paint.json", 1000.0},               // 1000 flakes, capped
      {"car_paint.json", 0.0},                        // untextured: the smallest
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    int expected = gltf::kMinAutoBakeSize;
    while (expected < gltf::kMaxAutoBakeSize && expected < 2.0 * c.detail) expected *= 2;
    CHECK(gltf::auto_bake_size(program_of(c.file)) == expected);
  }
  // The size the fallback used, and an explicit one instead.
  gltf::FallbackOptions options;
  options.max_states = 2;
  options.bake_size = 0;
  CHECK(gltf::fit_fallback(program_of("checker_tiles.json"), options).bake_size == 64);
  options.bake_size = 8;
  const gltf::Fallback fixed = gltf::fit_fallback(program_of("checker_tiles.json"), options);
  CHECK(fixed.bake_size == 8);
  REQUIRE(fixed.base_color.has_value());
  CHECK(fixed.base_color->size == 8);
  CHECK(gltf::fit_fallback(program_of("car_paint.json"), options).bake_size == 0);  // nothing to bake
}

TEST_CASE("glTF export: the showcase has a node per object, camera, light and label, in that order") {
  Diagnostics d;
  Scene scene = read_scene_file(test::source_dir() / "examples/showcase.json", d);
  REQUIRE(d.ok());
  gltf::Export out = gltf::export_scene(scene, "showcase.glb", quick());
  Json j = glb_json(out.files[0].bytes);
  // 1 camera, 2 lights, the objects (a labelled sphere per example material and the floor), and a
  // label per sphere; each sphere's material is a lamina material, each label has its own.
  const size_t objects = scene.objects.size(), spheres = objects - 1;
  REQUIRE(spheres == test::example_files().size());
  CHECK(j["nodes"].size() == 3 + objects + spheres);
  CHECK(j["scenes"][0]["nodes"].size() == 3 + objects + spheres);
  CHECK(j["meshes"].size() == objects + spheres);
  CHECK(j["materials"].size() == 2 * spheres);
  CHECK(out.materials.size() == spheres);  // the fit report: lamina materials only
  CHECK(j["cameras"].size() == 1);
  CHECK(j["extensions"]["KHR_lights_punctual"]["lights"].size() == 2);
  CHECK(j["nodes"][0]["name"] == "main");
  CHECK(j["nodes"][1]["name"] == "key");
  CHECK(j["nodes"][2]["name"] == "fill");
  CHECK(j["nodes"][3]["name"] == "acrylic_lacquer");
  CHECK(j["nodes"][3 + spheres]["name"] == "floor");
  CHECK(j["nodes"][4 + spheres]["name"] == "acrylic_lacquer label");
  CHECK(j["nodes"][3 + objects + spheres - 1]["name"] == scene.objects[spheres - 1].name + " label");
  CHECK(out.notes.empty());
}

namespace {

// A scene written in a folder examples/scenes, with the repository as its asset root.
Scene scene_of(const std::string& text) {
  Diagnostics d;
  Scene scene =
      read_scene(text, (test::source_dir() / "examples/scenes/inline.json").string(), d, test::repository_policy());
  for (const auto& e : d.errors()) INFO(format(e));
  REQUIRE(d.ok());
  return scene;
}

const Json& node_named(const Json& gltf, const std::string& name) { return named(gltf, "nodes", name); }

// `epsilon`: 1e-12 for values computed in double; vertices are floats (1e-6).
void check_numbers(const Json& actual, std::initializer_list<double> expected, double epsilon = 1e-12) {
  REQUIRE(actual.size() == expected.size());
  size_t i = 0;
  for (double e : expected) CHECK(actual[i++].get<double>() == doctest::Approx(e).epsilon(epsilon));  // absolute near 0
}

// glTF node rotation [x, y, z, w] applied to v.
glm::dvec3 rotate(const Json& q, glm::dvec3 v) {
  return glm::dquat(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>()) * v;
}

}  // namespace

TEST_CASE("glTF export: a spot light has its cone angles in radians and shines along its direction") {
  Scene scene = scene_of(R"({"format": 1, "materials": ["../materials/brass.json"],
    "lights": [{"name": "spot", "type": "spot", "position": [1, 2, 3], "direction": [0, -1, -1], "color": [1, 0.5, 0.25],
                "intensity": 40, "inner_cone": 10, "outer_cone": 25, "range": 12}],
    "objects": [{"name": "ball", "shape": "sphere", "material": "brass"}]})");
  Json j = glb_json(gltf::export_scene(scene, "spot.glb", quick()).files[0].bytes);
  const Json& light = j["extensions"]["KHR_lights_punctual"]["lights"][0];
  CHECK(light["type"] == "spot");
  CHECK(light["intensity"] == 40.0);
  CHECK(light["range"] == 12.0);
  check_numbers(light["color"], {1.0, 0.5, 0.25});
  // 10 and 25 degrees: pi / 18 and 5 pi / 36.
  CHECK(light["spot"]["innerConeAngle"].get<double>() ==
        doctest::Approx(0.17453292519943295).epsilon(1e-15).scale(0.0));
  CHECK(light["spot"]["outerConeAngle"].get<double>() ==
        doctest::Approx(0.43633231299858238).epsilon(1e-15).scale(0.0));
  const Json& node = node_named(j, "spot");
  CHECK(node["extensions"]["KHR_lights_punctual"]["light"] == 0);
  check_numbers(node["translation"], {1.0, 2.0, 3.0});
  // -Z turned down by 45 degrees about x: q = (sin(-22.5 deg), 0, 0, cos(22.5 deg)).
  check_numbers(node["rotation"], {-0.38268343236508978, 0.0, 0.0, 0.92387953251128674});
  const glm::dvec3 shines = rotate(node["rotation"], glm::dvec3(0, 0, -1));
  CHECK(shines.y == doctest::Approx(-std::sqrt(0.5)));
  CHECK(shines.z == doctest::Approx(-std::sqrt(0.5)));
}

TEST_CASE("glTF export: a camera looks at its target, and a directional light shines along its direction") {
  Scene scene = scene_of(R"({"format": 1, "materials": ["../materials/brass.json"],
    "cameras": [{"name": "cam", "position": [4, 0, 4], "look_at": [0, 0, 0], "yfov": 35, "aspect": 2, "znear": 0.5,
                 "zfar": 80}],
    "lights": [{"name": "sun", "type": "directional", "direction": [1, 0, 0], "intensity": 3}],
    "objects": [{"name": "ball", "shape": "sphere", "material": "brass"}]})");
  Json j = glb_json(gltf::export_scene(scene, "camera.glb", quick()).files[0].bytes);
  const Json& camera = j["cameras"][0];
  CHECK(camera["type"] == "perspective");
  CHECK(camera["perspective"]["yfov"].get<double>() == doctest::Approx(0.61086523819801535).epsilon(1e-15).scale(0.0));
  CHECK(camera["perspective"]["aspectRatio"] == 2.0);
  CHECK(camera["perspective"]["znear"] == 0.5);
  CHECK(camera["perspective"]["zfar"] == 80.0);
  const Json& cam = node_named(j, "cam");
  check_numbers(cam["translation"], {4.0, 0.0, 4.0});
  // Turned 45 degrees about y: q = (0, sin(22.5 deg), 0, cos(22.5 deg)); -Z then points at the origin.
  check_numbers(cam["rotation"], {0.0, 0.38268343236508978, 0.0, 0.92387953251128674});
  const Json& sun = node_named(j, "sun");
  CHECK_FALSE(sun.contains("translation"));
  // -Z turned to +x: 90 degrees about y, negative: q = (0, -sin(45 deg), 0, cos(45 deg)).
  check_numbers(sun["rotation"], {0.0, -0.70710678118654757, 0.0, 0.70710678118654757});
  CHECK(j["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] == "directional");
  CHECK(j["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] == 3.0);
}

TEST_CASE("glTF export: an environment light is left out with a note, in the library and through the CLI") {
  const std::string text = R"({"format": 1, "materials": ["MATERIAL"],
    "lights": [{"name": "key", "type": "point", "position": [0, 3, 0], "intensity": 10},
               {"name": "sky", "type": "environment", "file": "TEXTURE", "intensity": 2}],
    "objects": [{"name": "ball", "shape": "sphere", "material": "brass"}]})";
  auto with_paths = [&](const std::string& material, const std::string& texture) {
    std::string s = text;
    s.replace(s.find("MATERIAL"), 8, material);
    s.replace(s.find("TEXTURE"), 7, texture);
    return s;
  };
  Scene scene = scene_of(with_paths("../materials/brass.json", "../materials/textures/patina_mask.png"));
  gltf::Export out = gltf::export_scene(scene, "env.glb", quick());
  Json j = glb_json(out.files[0].bytes);
  REQUIRE(out.notes.size() == 1);
  CHECK(out.notes[0].find("environment light 'sky' has no glTF 2.0 counterpart") != std::string::npos);
  REQUIRE(j["extensions"]["KHR_lights_punctual"]["lights"].size() == 1);
  CHECK(j["extensions"]["KHR_lights_punctual"]["lights"][0]["name"] == "key");
  CHECK(j["nodes"].size() == 2);  // the point light and the ball
  for (const auto& n : j["nodes"]) CHECK(n["name"] != "sky");

  test::TempDir dir;
  std::filesystem::copy_file(test::source_dir() / "examples/materials/brass.json", dir.path() / "brass.json");
  std::filesystem::copy_file(test::source_dir() / "examples/materials/textures/patina_mask.png",
                             dir.path() / "sky.png");
  std::ofstream(dir.path() / "env.json") << with_paths("brass.json", "sky.png");
  auto r = test::run_cli("gltf env.json --bake-size 8 -o env.glb", dir.path());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("lamina: note: environment light 'sky' has no glTF 2.0 counterpart") != std::string::npos);
  CHECK(std::filesystem::exists(dir.path() / "env.glb"));
}

TEST_CASE("glTF export: what glTF cannot hold of render-only settings is noted, and the rest written") {
  Scene scene = scene_of(R"({"format": 1, "materials": ["../materials/brass.json"],
    "cameras": [{"name": "lens", "position": [0, 1, 5], "aperture_radius": 0.05, "focus_distance": 4}],
    "lights": [{"name": "sun", "type": "directional", "angular_radius": 0.27}],
    "objects": [{"name": "lamp", "shape": "box", "material": "brass", "emission": [2, 2, 2]}]})");
  const gltf::Export out = gltf::export_scene(scene, "notes.glb", quick());
  std::string notes;
  for (const auto& n : out.notes) notes += n + "\n";
  INFO(notes);
  CHECK(out.notes.size() == 3);
  CHECK(notes.find("camera 'lens' is written as a pinhole") != std::string::npos);
  CHECK(notes.find("directional light 'sun' is written as a point at infinity") != std::string::npos);
  CHECK(notes.find("object 'lamp'") != std::string::npos);
  const Json j = glb_json(out.files[0].bytes);
  CHECK(j["cameras"].size() == 1);
  CHECK(j["extensions"]["KHR_lights_punctual"]["lights"].size() == 1);
}

TEST_CASE("glTF export: box, torus and mesh-file objects have their vertices, bounds and transforms") {
  Scene scene = scene_of(R"({"format": 1, "materials": ["../materials/brass.json"],
    "objects": [{"name": "crate", "shape": "box", "size": [1, 2, 3], "material": "brass",
                 "transform": {"translation": [1, 2, 3], "rotation_deg": [90, 0, 0], "scale": [2, 2, 2]}},
                {"name": "ring", "shape": "torus", "major_radius": 1, "minor_radius": 0.25, "segments": 16,
                 "material": "brass"},
                {"name": "quad", "shape": "mesh", "file": "../../tests/data/scenes/quad.gltf", "material": "brass",
                 "transform": {"rotation": [0, 0, 1, 0]}}]})");
  Json j = glb_json(gltf::export_scene(scene, "shapes.glb", quick()).files[0].bytes);
  REQUIRE(j["meshes"].size() == 3);
  auto accessor = [&](size_t mesh, const char* attribute) -> const Json& {
    const Json& primitive = j["meshes"][mesh]["primitives"][0];
    return j["accessors"][std::string(attribute) == "indices" ? primitive["indices"].get<size_t>()
                                                              : primitive["attributes"][attribute].get<size_t>()];
  };
  // Box: six faces of four vertices and two triangles.
  CHECK(accessor(0, "POSITION")["count"] == 24);
  CHECK(accessor(0, "indices")["count"] == 36);
  CHECK(accessor(0, "indices")["componentType"] == 5123);
  check_numbers(accessor(0, "POSITION")["min"], {-0.5, -1.0, -1.5});
  check_numbers(accessor(0, "POSITION")["max"], {0.5, 1.0, 1.5});
  // Torus: 16 segments around and 8 across, a seam row and column repeated: 17 x 9 vertices.
  CHECK(accessor(1, "POSITION")["count"] == 153);
  CHECK(accessor(1, "indices")["count"] == 768);
  check_numbers(accessor(1, "POSITION")["min"], {-1.25, -0.25, -1.25});
  check_numbers(accessor(1, "POSITION")["max"], {1.25, 0.25, 1.25});
  // quad.gltf: its node transform (scale 2, +1 along x) is baked into the vertices.
  CHECK(accessor(2, "POSITION")["count"] == 4);
  CHECK(accessor(2, "indices")["count"] == 6);
  check_numbers(accessor(2, "POSITION")["min"], {0.0, -1.0, 0.0});
  check_numbers(accessor(2, "POSITION")["max"], {2.0, 1.0, 0.0});
  for (size_t m = 0; m < 3; ++m) CHECK(accessor(m, "TANGENT")["type"] == "VEC4");

  const Json& crate = node_named(j, "crate");
  check_numbers(crate["translation"], {1.0, 2.0, 3.0});
  check_numbers(crate["scale"], {2.0, 2.0, 2.0});
  check_numbers(crate["rotation"], {0.70710678118654757, 0.0, 0.0, 0.70710678118654757});  // 90 degrees about x
  CHECK_FALSE(node_named(j, "ring").contains("rotation"));
  check_numbers(node_named(j, "quad")["rotation"], {0.0, 0.0, 1.0, 0.0});
}

TEST_CASE("glTF export: a label is an unlit quad under its object, facing the first camera, left out of the report") {
  Scene scene = scene_of(R"({"format": 1, "materials": ["../materials/brass.json"],
    "cameras": [{"name": "cam", "position": [10, 3, 10], "look_at": [0, 3, 0]}],
    "objects": [{"name": "ball", "shape": "sphere", "radius": 2, "material": "brass", "label": "Brass",
                 "transform": {"translation": [0, 5, 0]}},
                {"name": "plain", "shape": "sphere", "material": "brass", "transform": {"translation": [6, 0, 0]}}]})");
  gltf::Export out = gltf::export_scene(scene, "label.glb", quick());
  Json j = glb_json(out.files[0].bytes);
  CHECK(out.materials.size() == 1);
  REQUIRE(j["materials"].size() == 2);
  const Json& material = j["materials"][1];
  CHECK(material["name"] == "ball label");
  CHECK(material["extras"] == Json{{"lamina_label", "Brass"}});
  CHECK(material["extensions"] == Json{{"KHR_materials_unlit", Json::object()}});
  CHECK(material["alphaMode"] == "BLEND");
  CHECK(material["pbrMetallicRoughness"]["metallicFactor"] == 0.0);
  const auto used = j["extensionsUsed"].get<std::vector<std::string>>();
  CHECK(std::find(used.begin(), used.end(), "KHR_materials_unlit") != used.end());

  REQUIRE(j["nodes"].size() == 4);  // camera, two spheres, one label
  const Json& label = j["nodes"][3];
  CHECK(label["name"] == "ball label");
  // The camera looks along (-1, 0, -1): the label turns 45 degrees about y to face it.
  check_numbers(label["rotation"], {0.0, 0.38268343236508978, 0.0, 0.92387953251128674});
  // The sphere is 4 wide seen from the camera: the text is 0.14 x 4 = 0.56 high, its top 0.02 x 4
  // = 0.08 below the sphere's lowest point (5 - 2); x and z centred under it.
  const Json& scale = label["scale"];
  CHECK(scale[1].get<double>() == doctest::Approx(0.56).epsilon(1e-6).scale(0.0));
  CHECK(scale[0].get<double>() > scale[1].get<double>());  // "Brass" is wider than high
  CHECK(scale[0].get<double>() <= 1.2 * 4.0 + 1e-12);      // and never wider than 1.2 x the object
  check_numbers(label["translation"], {0.0, 2.92, 0.0}, 1e-6);
  // The quad's texture: the label image, clamped, its content in the top-left of a power of two.
  const Json& primitive = j["meshes"][label["mesh"].get<size_t>()]["primitives"][0];
  CHECK(primitive["material"] == 1);
  const Json& texture = j["textures"][material["pbrMetallicRoughness"]["baseColorTexture"]["index"].get<size_t>()];
  CHECK(j["samplers"][texture["sampler"].get<size_t>()]["wrapS"] == 33071);
  CHECK(j["images"][texture["source"].get<size_t>()]["mimeType"] == "image/png");
}

TEST_CASE("glTF export: the .bin's URI is percent-encoded, and lamina import reads it back") {
  test::TempDir dir;
  Scene scene = sheet_of(test::source_dir() / "examples/materials/car_paint.json");
  const auto output = dir.path() / "my scene#1%+.gltf";
  gltf::Export out = gltf::export_scene(scene, output, quick());
  REQUIRE(out.files.size() == 2);
  CHECK(out.files[1].path == dir.path() / "my scene#1%+.bin");
  Json j = Json::parse(std::string(out.files[0].bytes.begin(), out.files[0].bytes.end()));
  CHECK(j["buffers"][0]["uri"] == "my%20scene%231%25%2B.bin");
  for (const auto& f : out.files) {
    std::ofstream file(f.path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(f.bytes.data()), static_cast<std::streamsize>(f.bytes.size()));
  }
  auto r = test::run_cli("import \"my scene#1%+.gltf\" -o imported.json", dir.path());
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(std::filesystem::exists(dir.path() / "imported.json"));
}

TEST_CASE(
    "lamina gltf and validate: every broken scene of the corpus exits 2 with its file and pointer, and gltf writes "
    "nothing") {
  const auto dir = test::source_dir() / "tests/data/bad_scenes";
  test::TempDir out;
  for (const auto& c : Json::parse(test::read_file(dir / "cases.json"))) {
    const std::string name = c["file"];
    CAPTURE(name);
    const std::filesystem::path scene = std::filesystem::path("tests/data/bad_scenes") / name;
    const std::string file = c.contains("in")
                                 ? (scene.parent_path() / c["in"].get<std::string>()).lexically_normal().string()
                                 : scene.string();
    const std::string at = file + ":" + c["pointer"].get<std::string>() + ":";
    auto r = test::run_cli("gltf " + scene.string() + " --bake-size 8 -o " + (out.path() / "out.glb").string(),
                           test::source_dir());
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(at) != std::string::npos);
    CHECK(std::filesystem::is_empty(out.path()));
    // lamina validate reports a broken mesh file the same way.
    if (name.rfind("mesh_", 0) == 0) {
      auto v = test::run_cli("validate " + scene.string(), test::source_dir());
      INFO(v.err);
      CHECK(v.exit_code == 2);
      CHECK(v.err.find(at) != std::string::npos);
    }
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
  // --bake-size: 0 (per material) or 1 to 4096.
  for (const char* size : {"-1", "4097"}) {
    CAPTURE(size);
    r = test::run_cli("gltf examples/materials/checker_tiles.json --bake-size " + std::string(size) + " -o " +
                          (dir.path() / "tiles.glb").string(),
                      test::source_dir());
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--bake-size") != std::string::npos);
  }
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
