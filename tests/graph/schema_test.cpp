#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "graph/registry.h"
#include "graph/schema.h"
#include "test_support.h"

using namespace lamina;
namespace fs = std::filesystem;

TEST_CASE("the committed schema and node reference are exactly what lamina schema generates") {
  // Regenerate with: build/release/lamina schema -o schema
  CHECK(test::read_file(test::source_dir() / "schema/material.schema.json") == material_schema());
  CHECK(test::read_file(test::source_dir() / "schema/nodes.md") == node_reference_markdown());
}

TEST_CASE("the README's node table is the one generated from the declarations") {
  // LAMINA_UPDATE_README=1 rewrites it after a node type or parameter changed.
  const fs::path readme = test::source_dir() / "README.md";
  const std::string text = test::read_file(readme);
  const std::string start = "<!-- node table: generated from the node declarations";
  const std::string end = "<!-- end of node table -->";
  const size_t a = text.find(start);
  REQUIRE(a != std::string::npos);
  const size_t body = text.find('\n', a) + 1;
  const size_t b = text.find(end, body);
  REQUIRE(b != std::string::npos);
  if (std::getenv("LAMINA_UPDATE_README")) {
    std::ofstream(readme, std::ios::binary) << text.substr(0, body) + node_table_markdown() + text.substr(b);
    return;
  }
  INFO("README.md's node table is out of date: rerun with LAMINA_UPDATE_README=1");
  CHECK(text.substr(body, b - body) == node_table_markdown());
}

TEST_CASE("the schema declares every node type with its parameters and nothing else") {
  auto schema = nlohmann::json::parse(material_schema());
  CHECK(schema["$schema"] == "https://json-schema.org/draft/2020-12/schema");
  const auto& defs = schema["$defs"];
  for (const auto& d : NodeRegistry::builtin().all()) {
    CAPTURE(d.type);
    std::string def = "node_" + d.type;
    std::replace(def.begin(), def.end(), '/', '_');
    const auto& node = defs.at(def);
    CHECK(node["additionalProperties"] == false);
    CHECK(node["properties"]["type"]["const"] == d.type);
    CHECK(node["properties"].size() == d.params.size() + 2);
    for (const auto& p : d.params) {
      CAPTURE(p.name);
      const auto& prop = node["properties"].at(p.name);
      CHECK(prop["description"].get<std::string>().find(p.doc) == 0);
      bool listed = std::find(node["required"].begin(), node["required"].end(), p.name) != node["required"].end();
      CHECK(listed == (p.required() && !d.in_alternative(p.name)));
    }
  }
  auto types = defs["node"]["properties"]["type"]["enum"];
  CHECK(types.size() == NodeRegistry::builtin().all().size());
}

TEST_CASE("the node reference lists every parameter with its unit and range") {
  std::string reference = node_reference_markdown();
  CHECK(reference.find("| `thickness` | float or link | micrometres | 0.0 <= thickness <= 10000.0 |") !=
        std::string::npos);
  CHECK(reference.find("Give exactly one of `metal` or `n` + `k`.") != std::string::npos);
  const auto* dielectric = NodeRegistry::builtin().find("interface/dielectric");
  std::string text = node_reference_text(*dielectric);
  CHECK(text.find("ior: float or link, 1.0 <= ior <= 4.0, required") != std::string::npos);
  CHECK(text.find("distribution: beckmann, blinn or ggx, default \"beckmann\"") != std::string::npos);
}

TEST_CASE("the committed scene schema is exactly what lamina schema generates, and forbids unknown keys") {
  // Regenerate with: build/release/lamina schema -o schema
  CHECK(test::read_file(test::source_dir() / "schema/scene.schema.json") == scene_schema());
  auto schema = nlohmann::json::parse(scene_schema());
  CHECK(schema["additionalProperties"] == false);
  for (const char* def : {"camera", "light_point", "light_spot", "object_sphere", "object_mesh", "transform"})
    CHECK(schema["$defs"][def]["additionalProperties"] == false);
  CHECK(schema["$defs"]["light_spot"]["properties"]["outer_cone"]["maximum"] == 90.0);
  CHECK(schema["$defs"]["object_torus"]["properties"]["segments"]["type"] == "integer");
}
