// Round trip: lamina material JSON -> glTF (our exporter) -> lamina JSON (our importer) gives the
// same graphs, value for value, for every example and for the showcase scene.
#include <doctest/doctest.h>

#include <fstream>
#include <map>
#include <set>

#include "graph/gltf/export.h"
#include "graph/gltf/import.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "test_support.h"

using namespace lamina;

namespace {

void write_files(const gltf::Export& exported) {
  for (const auto& f : exported.files) {
    std::ofstream out(f.path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(f.bytes.data()), static_cast<std::streamsize>(f.bytes.size()));
    REQUIRE(out.good());
  }
}

// The canonical text of one material, with image files reduced to their base names (the importer
// extracts textures next to its output and points the nodes there).
std::string canonical(Material m) {
  for (auto& node : m.nodes)
    if (node.type == "texture/image")
      for (auto& p : node.params)
        if (p.name == "file") p.value = std::filesystem::path(std::get<std::string>(p.value)).filename().string();
  Document single;
  single.materials.push_back(std::move(m));
  return write_document(single);
}

// The graph travels in our extension; the fallback only has to be there, so one fit a material.
gltf::ExportOptions quick() {
  gltf::ExportOptions o;
  o.fallback.bake_size = 32;
  o.fallback.max_states = 1;
  return o;
}

// Exports `scene` to `out`, imports it back and compares every material with its source.
void round_trip(const Scene& scene, const std::filesystem::path& out) {
  write_files(gltf::export_scene(scene, out, quick()));
  Diagnostics diagnostics;
  gltf::ImportResult imported = gltf::import_gltf(out, diagnostics);
  for (const auto& d : diagnostics.errors()) INFO(format(d));
  REQUIRE(diagnostics.ok());
  CHECK(diagnostics.warnings().empty());
  std::map<std::string, const Material*> by_name;
  for (const auto& m : imported.document.materials) by_name[m.name] = &m;
  size_t expected = 0;
  for (const auto& file : scene.material_files)
    for (const auto& m : file.document.materials) {
      bool used = false;
      for (const auto& o : scene.objects) used = used || o.material == m.name;
      if (!used) continue;
      ++expected;
      CAPTURE(m.name);
      auto it = by_name.find(m.name);
      REQUIRE(it != by_name.end());
      CHECK(canonical(*it->second) == canonical(m));
    }
  CHECK(imported.document.materials.size() == expected);
  // Each image node's texture comes back with the bytes of the file it was read from.
  for (const auto& file : scene.material_files)
    for (const auto& m : file.document.materials)
      for (const auto& node : m.nodes)
        if (node.type == "texture/image") {
          const auto source = file.resolved.parent_path() / std::get<std::string>(*node.find("file"));
          const auto name = source.filename().string();
          bool found = false;
          for (const auto& t : imported.textures)
            if (t.file_name == name) {
              found = true;
              CHECK(std::string(t.bytes.begin(), t.bytes.end()) == test::read_file(source));
            }
          CHECK_MESSAGE(found, "texture " << name << " was not extracted");
        }
}

// The showcase's objects whose material comes from an example that swept_example_files(0) visits,
// and every object of another material: all of them in the optimised build; under the sanitisers
// the half that the sweep over every example (offset 1) leaves, so the two cover each material.
Scene swept_showcase(Scene scene) {
  std::set<std::filesystem::path> examples, kept;
  for (const auto& f : test::example_files()) examples.insert(f.lexically_normal());
  for (const auto& f : test::swept_example_files(0)) kept.insert(f.lexically_normal());
  std::vector<SceneObject> objects;
  std::set<std::filesystem::path> found;
  for (const auto& o : scene.objects) {
    const MaterialFileRef* file = nullptr;
    REQUIRE(scene.find_material(o.material, &file) != nullptr);
    const auto path = file->resolved.lexically_normal();
    if (examples.count(path)) found.insert(path);
    if (!examples.count(path) || kept.count(path)) objects.push_back(o);
  }
  CHECK(found == examples);  // the showcase shows every example, each found by its file
  scene.objects = std::move(objects);
  // Files no object uses any more are not exported, nor are their textures.
  std::vector<MaterialFileRef> files;
  for (auto& file : scene.material_files) {
    bool used = false;
    for (const auto& m : file.document.materials)
      for (const auto& o : scene.objects) used = used || o.material == m.name;
    if (used) files.push_back(std::move(file));
  }
  scene.material_files = std::move(files);
  return scene;
}

}  // namespace

TEST_CASE("round trip: every example material -> .glb and .gltf -> lamina gives the identical graph") {
  test::TempDir dir;
  // Under the sanitisers every second example, the others' being fitted by fit_pbr's sweep.
  for (const auto& file : test::swept_example_files(1)) {
    CAPTURE(file);
    CheckedFile checked = check_file(file);
    REQUIRE(checked.ok());
    const Scene sheet = sample_sheet(checked.document, file);
    round_trip(sheet, dir.path() / (file.stem().string() + ".glb"));
    round_trip(sheet, dir.path() / (file.stem().string() + ".gltf"));
  }
}

TEST_CASE("round trip: the showcase scene -> .glb -> lamina gives every material's graph back") {
  test::TempDir dir;
  Diagnostics diagnostics;
  const Scene scene = read_scene_file(test::source_dir() / "examples/showcase.json", diagnostics);
  REQUIRE(diagnostics.ok());
  const Scene swept = swept_showcase(scene);
  CHECK(swept.objects.size() >= scene.objects.size() / 2);
  round_trip(swept, dir.path() / "showcase.glb");
}
