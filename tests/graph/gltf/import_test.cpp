#include "graph/gltf/import.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "graph/gltf/export.h"
#include "graph/gltf/pbr_to_layers.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "test_support.h"

using namespace lamina;

namespace {

std::filesystem::path data(const std::string& name) { return test::source_dir() / "tests/data/gltf" / name; }

struct Imported {
  gltf::ImportResult result;
  Diagnostics diagnostics;
};

Imported import_file(const std::string& name) {
  Imported out;
  out.result = gltf::import_gltf(data(name), out.diagnostics);
  return out;
}

const Node& node(const Material& m, const std::string& id) {
  const Node* n = m.find_node(id);
  REQUIRE_MESSAGE(n, "no node " << id << " in " << m.name);
  return *n;
}

double number(const Node& n, const std::string& param) {
  const Value* v = n.find(param);
  REQUIRE_MESSAGE(v, n.id << " has no " << param);
  return std::get<double>(*v);
}

Vec3d color(const Node& n, const std::string& param) {
  const Value* v = n.find(param);
  REQUIRE_MESSAGE(v, n.id << " has no " << param);
  return std::get<Vec3d>(*v);
}

std::string text(const Node& n, const std::string& param) {
  const Value* v = n.find(param);
  REQUIRE_MESSAGE(v, n.id << " has no " << param);
  return std::get<std::string>(*v);
}

Link link(const Node& n, const std::string& param) {
  const Value* v = n.find(param);
  REQUIRE_MESSAGE(v, n.id << " has no " << param);
  return std::get<Link>(*v);
}

std::vector<std::string> ids(const Material& m) {
  std::vector<std::string> out;
  for (const auto& n : m.nodes) out.push_back(n.id);
  return out;
}

void check_color(const Vec3d& got, const Vec3d& want) {
  for (size_t c = 0; c < 3; ++c) CHECK(got[c] == doctest::Approx(want[c]).epsilon(1e-12).scale(0.0));
}

// Writes the import as `lamina import` does and runs the checker of `lamina validate` on it.
void check_written(const gltf::ImportResult& result) {
  test::TempDir dir;
  for (const auto& t : result.textures) {
    std::ofstream out(dir.path() / t.file_name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(t.bytes.data()), static_cast<std::streamsize>(t.bytes.size()));
  }
  std::ofstream(dir.path() / "imported.json") << write_document(result.document);
  CheckedFile checked = check_file(dir.path() / "imported.json");
  for (const auto& d : checked.diagnostics.errors()) INFO(format(d));
  CHECK(checked.diagnostics.errors().empty());
  CHECK(checked.diagnostics.warnings().empty());
}

bool has_diagnostic(const std::vector<Diagnostic>& list, const std::string& pointer) {
  return std::any_of(list.begin(), list.end(), [&](const Diagnostic& d) { return d.pointer == pointer; });
}

}  // namespace

TEST_CASE("import: the hand-made glTF files give graphs that pass the checker, with no warnings") {
  for (const char* name :
       {"core_metallic_roughness.gltf", "ior.gltf", "specular.gltf", "clearcoat.gltf", "iridescence.gltf",
        "base_color_texture.gltf", "base_color_texture.glb", "lamina_layered.gltf"}) {
    const std::string file = name;
    CAPTURE(file);
    auto imported = import_file(name);
    for (const auto& d : imported.diagnostics.errors()) INFO(format(d));
    CHECK(imported.diagnostics.ok());
    CHECK(imported.diagnostics.warnings().empty());
    check_written(imported.result);
  }
}

TEST_CASE("import: core metallic-roughness gives a conductor, a metallic mix and a dielectric over Lambert") {
  auto imported = import_file("core_metallic_roughness.gltf");
  REQUIRE(imported.diagnostics.ok());
  const auto& materials = imported.result.document.materials;
  REQUIRE(materials.size() == 3);

  // Names are sanitised; the unnamed material is named after its index.
  CHECK(materials[0].name == "Brushed_Gold");
  CHECK(materials[1].name == "half_metal");
  CHECK(materials[2].name == "material_2");

  // metallic 1: only a GGX conductor, n = 1, k = 2 sqrt(F0 / (1 - F0)), F0 = base colour
  // (1.0 clamped to 0.999); alpha = roughness^2 = 0.25.
  const Material& gold = materials[0];
  CHECK(ids(gold) == std::vector<std::string>{"metal"});
  CHECK(gold.surface == Link{"metal", ""});
  check_color(color(node(gold, "metal"), "n"), {1.0, 1.0, 1.0});
  check_color(color(node(gold, "metal"), "k"), {63.2139225171164, 3.6185656127832053, 1.4227074138916156});
  CHECK(number(node(gold, "metal"), "alpha") == doctest::Approx(0.25));
  CHECK(text(node(gold, "metal"), "distribution") == "ggx");

  // metallic 0.25: mix(dielectric stack, conductor, 0.25); F0 0.5 gives k = 2.
  const Material& half = materials[1];
  CHECK(half.surface == Link{"metallic_mix", ""});
  CHECK(number(node(half, "metallic_mix"), "weight") == doctest::Approx(0.25));
  CHECK(link(node(half, "metallic_mix"), "a") == Link{"dielectric", ""});
  CHECK(link(node(half, "metallic_mix"), "b") == Link{"metal", ""});
  check_color(color(node(half, "metal"), "k"), {2.0, 2.0, 2.0});
  CHECK(number(node(half, "metal"), "alpha") == doctest::Approx(0.04));
  CHECK(number(node(half, "specular"), "ior") == 1.5);  // given as is without KHR_materials_specular
  CHECK(node(half, "diffuse").type == "substrate/lambert");

  // metallic 0: a dielectric interface (default ior 1.5) over the base colour, alpha 1.
  const Material& red = materials[2];
  CHECK(ids(red) == std::vector<std::string>{"diffuse", "specular", "dielectric"});
  CHECK(red.surface == Link{"dielectric", ""});
  check_color(color(node(red, "diffuse"), "albedo"), {0.8, 0.1, 0.1});
  CHECK(number(node(red, "specular"), "alpha") == doctest::Approx(1.0));
  CHECK(link(node(red, "dielectric"), "interface") == Link{"specular", ""});
  CHECK(link(node(red, "dielectric"), "base") == Link{"diffuse", ""});
}

TEST_CASE("import: KHR_materials_ior and KHR_materials_specular set the interface's ior") {
  auto ior = import_file("ior.gltf");
  REQUIRE(ior.diagnostics.ok());
  const Material& water = ior.result.document.materials.at(0);
  CHECK(water.name == "water_ish");
  CHECK(number(node(water, "specular"), "ior") == 1.33);
  CHECK(number(node(water, "specular"), "alpha") == doctest::Approx(0.09));

  // F0 = mean(min(0.04 * [1, 0.8, 0.6], 1) * 0.5) = 0.016 -> ior = (1 + sqrt F0) / (1 - sqrt F0).
  auto spec = import_file("specular.gltf");
  REQUIRE(spec.diagnostics.ok());
  CHECK(number(node(spec.result.document.materials.at(0), "specular"), "ior") ==
        doctest::Approx(1.2896160699323886).epsilon(1e-12).scale(0.0));
  CHECK(std::any_of(spec.result.notes.begin(), spec.result.notes.end(),
                    [](const std::string& n) { return n.find("tint is averaged") != std::string::npos; }));
}

TEST_CASE("import: KHR_materials_clearcoat adds a dielectric layer on top, mixed by a partial factor") {
  auto imported = import_file("clearcoat.gltf");
  REQUIRE(imported.diagnostics.ok());
  const Material& plastic = imported.result.document.materials.at(0);
  CHECK(plastic.surface == Link{"coated", ""});
  CHECK(number(node(plastic, "clearcoat"), "ior") == doctest::Approx(1.5));
  CHECK(number(node(plastic, "clearcoat"), "alpha") == doctest::Approx(0.01));
  CHECK(link(node(plastic, "coated"), "base") == Link{"dielectric", ""});
  CHECK(number(node(plastic, "specular"), "alpha") == doctest::Approx(0.36));

  const Material& metal = imported.result.document.materials.at(1);
  CHECK(ids(metal) == std::vector<std::string>{"metal", "clearcoat", "coated", "clearcoat_mix"});
  CHECK(metal.surface == Link{"clearcoat_mix", ""});
  CHECK(number(node(metal, "clearcoat_mix"), "weight") == doctest::Approx(0.5));
  CHECK(link(node(metal, "clearcoat_mix"), "a") == Link{"metal", ""});
  CHECK(link(node(metal, "clearcoat_mix"), "b") == Link{"coated", ""});
  CHECK(number(node(metal, "clearcoat"), "alpha") == doctest::Approx(0.0));
  check_color(color(node(metal, "metal"), "k"), {6.0, 6.0, 6.0});  // F0 0.9: 2 sqrt(0.9 / 0.1)
}

TEST_CASE("import: KHR_materials_iridescence puts the metal under a thin film, mixed by a partial factor") {
  auto imported = import_file("iridescence.gltf");
  REQUIRE(imported.diagnostics.ok());
  const Material& whole = imported.result.document.materials.at(0);
  CHECK(ids(whole) == std::vector<std::string>{"film"});
  CHECK(whole.surface == Link{"film", ""});
  CHECK(number(node(whole, "film"), "thickness_nm") == doctest::Approx(300.0));
  check_color(color(node(whole, "film"), "film_ior"), {1.8, 1.8, 1.8});
  check_color(color(node(whole, "film"), "k"), {6.0, 2 * std::sqrt(0.8 / 0.2), 2 * std::sqrt(0.6 / 0.4)});
  CHECK(number(node(whole, "film"), "alpha") == doctest::Approx(0.04));

  // Half: the bare metal and the filmed one, mixed; the thickness texture's range gives its middle,
  // and the index beyond lamina's range is clamped, each with a note.
  const Material& half = imported.result.document.materials.at(1);
  CHECK(ids(half) == std::vector<std::string>{"metal", "film", "iridescence_mix"});
  CHECK(half.surface == Link{"iridescence_mix", ""});
  CHECK(number(node(half, "iridescence_mix"), "weight") == doctest::Approx(0.5));
  CHECK(link(node(half, "iridescence_mix"), "a") == Link{"metal", ""});
  CHECK(link(node(half, "iridescence_mix"), "b") == Link{"film", ""});
  CHECK(number(node(half, "film"), "thickness_nm") == doctest::Approx(400.0));
  check_color(color(node(half, "film"), "film_ior"), {3.0, 3.0, 3.0});
  // Half metallic: the film is the metal part of the metallic mix; the dielectric part has none.
  const Material& half_metal = imported.result.document.materials.at(2);
  CHECK(half_metal.surface == Link{"metallic_mix", ""});
  CHECK(link(node(half_metal, "metallic_mix"), "b") == Link{"film", ""});
  CHECK(number(node(half_metal, "film"), "thickness_nm") == doctest::Approx(250.0));
  for (const char* note : {"iridescenceThicknessTexture is not imported", "iridescenceIor 4.0 is clamped to 3.0",
                           "iridescence over the non-metallic part is not imported"})
    CHECK(std::any_of(imported.result.notes.begin(), imported.result.notes.end(),
                      [&](const std::string& n) { return n.find(note) != std::string::npos; }));
}

TEST_CASE("import: baseColorTexture becomes an image node with the extracted PNG, in .gltf and .glb alike") {
  for (const std::string name : {"base_color_texture.gltf", "base_color_texture.glb"}) {
    CAPTURE(name);
    auto imported = import_file(name);
    REQUIRE(imported.diagnostics.ok());
    const Material& m = imported.result.document.materials.at(0);
    const Node& texture = node(m, "base_color");
    CHECK(texture.type == "texture/image");
    CHECK(text(texture, "file") == "checker.png");
    CHECK(text(texture, "wrap") == "clamp");
    CHECK(text(texture, "color_space") == "srgb");
    CHECK(link(node(m, "diffuse"), "albedo") == Link{"base_color", "color"});
    // Only the base colour image is extracted: the metallic-roughness one is reduced to its means
    // (blue 0, 0, 0.2, 0 -> metallic 0.05; green 1, 0, 1, 0 -> roughness 0.5 * 0.5, alpha 0.0625).
    REQUIRE(imported.result.textures.size() == 1);
    CHECK(imported.result.textures[0].file_name == "checker.png");
    CHECK(imported.result.textures[0].bytes.size() == 75);  // the generator's PNG, stored as is
    CHECK(imported.result.textures[0].bytes[1] == 'P');
    CHECK(number(node(m, "metallic_mix"), "weight") == doctest::Approx(0.05).epsilon(1e-6).scale(0.0));
    CHECK(number(node(m, "specular"), "alpha") == doctest::Approx(0.0625).epsilon(1e-6).scale(0.0));
  }
}

TEST_CASE("import: LAMINA_materials_layered gives back the exact graph of the exported examples") {
  auto imported = import_file("lamina_layered.gltf");
  for (const auto& d : imported.diagnostics.errors()) INFO(format(d));
  REQUIRE(imported.diagnostics.ok());
  Document expected;
  for (const char* name : {"car_paint", "patina_map_copper"}) {
    Document example = load(test::source_dir() / "examples/materials" / (std::string(name) + ".json"));
    expected.materials.push_back(example.materials.at(0));
  }
  // The image node keeps only the base name of its file: the texture is extracted next to the output.
  for (auto& p : expected.materials[1].nodes[2].params)
    if (p.name == "file") p.value = std::string("patina_mask.png");
  CHECK(write_document(imported.result.document) == write_document(expected));
  REQUIRE(imported.result.textures.size() == 1);
  const std::string mask = test::read_file(test::source_dir() / "examples/materials/textures/patina_mask.png");
  CHECK(imported.result.textures[0].file_name == "patina_mask.png");
  CHECK(std::string(imported.result.textures[0].bytes.begin(), imported.result.textures[0].bytes.end()) == mask);
}

TEST_CASE("import: an extension lamina does not read is a warning with its glTF pointer") {
  auto imported = import_file("unknown_extension.gltf");
  CHECK(imported.diagnostics.ok());
  CHECK(imported.diagnostics.warnings().size() == 2);
  CHECK(has_diagnostic(imported.diagnostics.warnings(), "/extensionsUsed/0"));
  CHECK(has_diagnostic(imported.diagnostics.warnings(), "/materials/0/extensions/VENDOR_materials_sparkle"));
  CHECK(imported.result.document.materials.size() == 1);
}

TEST_CASE("import: broken glTF files give errors with the file and the glTF pointer") {
  struct Case {
    const char* file;
    const char* pointer;
    const char* message;
  };
  for (const Case& c : {
           Case{"bad/extension_not_object.gltf", "/materials/0/extensions/LAMINA_materials_layered",
                "expected an object"},
           Case{"bad/invalid_graph.gltf", "/materials/0/extensions/LAMINA_materials_layered/material/nodes/1/ior",
                "out of range"},
           Case{"bad/texture_out_of_range.gltf",
                "/materials/1/extensions/LAMINA_materials_layered/textures/patina/index", "does not exist"},
           Case{"bad/truncated.glb", "", "not a valid .glb: the header says the file has"},
       }) {
    const std::string file = c.file;
    CAPTURE(file);
    auto imported = import_file(c.file);
    REQUIRE_FALSE(imported.diagnostics.ok());
    const Diagnostic& d = imported.diagnostics.errors().front();
    CHECK(d.file == data(c.file).string());
    CHECK(d.pointer == c.pointer);
    CHECK(d.message.find(c.message) != std::string::npos);
  }
  Diagnostics diagnostics;
  CHECK_THROWS_AS(gltf::import_gltf(data("no_such_file.gltf"), diagnostics), IoError);
}

TEST_CASE("import: the conversion formulas match the Fresnel equations they invert") {
  // Independent values (python3): f0(1.5) = 0.04; ior_from_f0(0.04) = 1.5; k(0.766) = 3.61856561...
  CHECK(gltf::f0_from_ior(1.5) == doctest::Approx(0.04));
  CHECK(gltf::ior_from_f0(0.04) == doctest::Approx(1.5));
  CHECK(gltf::conductor_k_from_f0(0.766) == doctest::Approx(3.6185656127832053).epsilon(1e-12).scale(0.0));
  CHECK(gltf::conductor_k_from_f0(0.0) == 0.0);
}

namespace {

void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(out.good());
}

}  // namespace

TEST_CASE("import: a glTF with no materials is an error, and lamina import writes nothing") {
  // An empty material file is not a valid one (lamina validate rejects it), so it is not written.
  const auto quad = test::source_dir() / "tests/data/scenes/quad.gltf";
  Diagnostics diagnostics;
  auto result = gltf::import_gltf(quad, diagnostics);
  REQUIRE(diagnostics.errors().size() == 1);
  CHECK(diagnostics.errors()[0].file == quad.string());
  CHECK(diagnostics.errors()[0].pointer == "");
  CHECK(diagnostics.errors()[0].message.find("no materials") != std::string::npos);
  CHECK(result.document.materials.empty());

  test::TempDir dir;
  auto r = test::run_cli("import " + quad.string() + " -o out/imported.json", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find(quad.string() + ":: the glTF file has no materials") != std::string::npos);
  CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("import: object label materials are left out, with a note and no warning, and labels alone are an error") {
  // A lamina export's labels: the sample sheet of car_paint has one sphere and its label.
  test::TempDir dir;
  CheckedFile checked = check_file(test::source_dir() / "examples/materials/car_paint.json");
  REQUIRE(checked.ok());
  gltf::ExportOptions quick;
  quick.fallback.bake_size = 16;
  gltf::Export exported =
      gltf::export_scene(sample_sheet(checked.document, test::source_dir() / "examples/materials/car_paint.json"),
                         dir.path() / "sheet.gltf", quick);
  for (const auto& f : exported.files) write_bytes(f.path, f.bytes);
  Diagnostics diagnostics;
  auto result = gltf::import_gltf(dir.path() / "sheet.gltf", diagnostics);
  CHECK(diagnostics.ok());
  CHECK(diagnostics.warnings().empty());  // KHR_materials_unlit is used by the label only
  REQUIRE(result.document.materials.size() == 1);
  CHECK(result.document.materials[0].name == "car_paint");
  CHECK(std::find(result.notes.begin(), result.notes.end(), "1 object label material was left out") !=
        result.notes.end());

  // Only the label left: nothing to import.
  auto j = nlohmann::json::parse(test::read_file(dir.path() / "sheet.gltf"));
  j["materials"].erase(0);
  j["meshes"][0]["primitives"][0].erase("material");
  j["meshes"][1]["primitives"][0]["material"] = 0;
  std::ofstream(dir.path() / "labels.gltf") << j.dump();
  Diagnostics only_labels;
  gltf::import_gltf(dir.path() / "labels.gltf", only_labels);
  REQUIRE(only_labels.errors().size() == 1);
  CHECK(only_labels.errors()[0].pointer == "/materials");
  CHECK(only_labels.errors()[0].message.find("all object labels") != std::string::npos);
  CHECK(only_labels.warnings().empty());
}

TEST_CASE("import: a LAMINA_materials_layered material takes its name from the graph, not from the glTF") {
  // A tool renamed the glTF material; the graph inside the extension still says car_paint.
  auto j = nlohmann::json::parse(test::read_file(data("lamina_layered.gltf")));
  REQUIRE(j["materials"][0]["extensions"]["LAMINA_materials_layered"]["material"]["name"] == "car_paint");
  j["materials"][0]["name"] = "Car Paint (renamed)";
  test::TempDir dir;
  std::ofstream(dir.path() / "renamed.gltf") << j.dump();
  Diagnostics diagnostics;
  auto result = gltf::import_gltf(dir.path() / "renamed.gltf", diagnostics);
  for (const auto& d : diagnostics.errors()) INFO(format(d));
  REQUIRE(diagnostics.ok());
  REQUIRE(result.document.materials.size() == 2);
  CHECK(result.document.materials[0].name == "car_paint");
  CHECK(result.document.materials[1].name == "patina_map_copper");
}

TEST_CASE("import: an image's percent-encoded URI is decoded, for reading it and for the extracted file's name") {
  test::TempDir dir;
  std::filesystem::copy_file(test::source_dir() / "examples/materials/textures/patina_mask.png",
                             dir.path() / "my mask#1.png");
  auto j = nlohmann::json::parse(test::read_file(data("base_color_texture.gltf")));
  j["images"][0] = {{"uri", "my%20mask%231.png"}};
  std::ofstream(dir.path() / "encoded.gltf") << j.dump();
  Diagnostics diagnostics;
  auto result = gltf::import_gltf(dir.path() / "encoded.gltf", diagnostics);
  for (const auto& d : diagnostics.errors()) INFO(format(d));
  REQUIRE(diagnostics.ok());
  REQUIRE(result.textures.size() == 1);
  // "my mask#1.png" made safe for every file system.
  CHECK(result.textures[0].file_name == "my_mask_1.png");
  CHECK(std::string(result.textures[0].bytes.begin(), result.textures[0].bytes.end()) ==
        test::read_file(dir.path() / "my mask#1.png"));
}
