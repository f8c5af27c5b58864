// lamina eval, albedo and plot: the CLI prints what the library computes, rejects mistakes with
// exit 2 and nothing on stdout, and writes images only for valid input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu/image.h"
#include "graph/load.h"
#include "test_support.h"

using namespace lamina;

namespace {

const char* const kCarPaint = "examples/materials/car_paint.json";
const char* const kInvalid = "tests/data/bad/ior_below_one.json";

cpu::Evaluator library_evaluator(const std::string& relative) {
  std::string file = (test::source_dir() / relative).string();
  CheckedFile checked = check_file(file);
  REQUIRE(checked.ok());
  REQUIRE(checked.graphs.size() == 1);
  return cpu::Evaluator(compile(*checked.graphs[0], file));
}

std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

std::vector<std::string> listing(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("lamina eval prints the library's f and pdf in plain text and as JSON") {
  const glm::vec3 wi = glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f));
  const glm::vec3 wo = glm::normalize(glm::vec3(-0.4f, 0.0f, 1.0f));
  cpu::Evaluator evaluator = library_evaluator(kCarPaint);
  cpu::EvalPdf expected = evaluator.eval_pdf(ShadingContext{}, wi, wo);

  std::string args = std::string("eval ") + kCarPaint + " --wi 0.3,0.1,1 --wo -0.4,0,1";
  auto plain = test::run_cli(args + " --material car_paint", test::source_dir());
  INFO(plain.err);
  REQUIRE(plain.exit_code == 0);
  CHECK(plain.err.empty());
  float r = -1, g = -1, b = -1, pdf = -1;
  REQUIRE(std::sscanf(plain.out.c_str(), "f = %g %g %g  pdf = %g", &r, &g, &b, &pdf) == 4);
  for (float v : {r, g, b, pdf}) {
    CHECK(std::isfinite(v));
    CHECK(v >= 0.0f);
  }
  CHECK(pdf > 0.0f);
  char line[200];
  std::snprintf(line, sizeof line, "f = %.6g %.6g %.6g  pdf = %.6g\n", double(expected.f.r), double(expected.f.g),
                double(expected.f.b), double(expected.pdf));
  CHECK(plain.out == line);

  // --material may be omitted when the file has one material.
  auto json = test::run_cli(args + " --json", test::source_dir());
  INFO(json.err);
  REQUIRE(json.exit_code == 0);
  auto report = nlohmann::json::parse(json.out);
  REQUIRE(report.is_object());
  CHECK(report.size() == 2);
  REQUIRE(report["f"].size() == 3);
  CHECK(report["f"][0].get<float>() == expected.f.r);
  CHECK(report["f"][1].get<float>() == expected.f.g);
  CHECK(report["f"][2].get<float>() == expected.f.b);
  CHECK(report["pdf"].get<float>() == expected.pdf);
}

TEST_CASE("lamina eval gives exactly 0 for a light below the horizon") {
  auto r = test::run_cli(std::string("eval ") + kCarPaint + " --wi 0.5,0,-0.2 --wo 0,0,1 --json", test::source_dir());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  auto report = nlohmann::json::parse(r.out);
  for (int c = 0; c < 3; ++c) CHECK(report["f"][c].get<double>() == 0.0);
  CHECK(report["pdf"].get<double>() == 0.0);
}

TEST_CASE("lamina eval rejects mistakes with exit 2 and nothing on stdout") {
  struct Case {
    std::string args, message;
  };
  const std::string car = std::string(" ") + kCarPaint;
  const Case cases[] = {
      {"eval" + car + " --wi 1,x,0 --wo 0,0,1", "--wi: 'x' in '1,x,0' is not a finite number"},
      {"eval" + car + " --wi 0,0,1 --wo 1,0", "--wo: expected 3 numbers, got 2"},
      {"eval" + car + " --wi 0,0,1 --wo nan,0,1", "--wo: 'nan'"},
      {"eval" + car + " --wi 0,0,0 --wo 0,0,1", "--wi: the zero vector"},
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1 --uv 0.5", "--uv: expected 2 numbers"},
      {"eval" + car + " --material carpaint --wi 0,0,1 --wo 0,0,1",
       "car_paint.json:/materials: no material named 'carpaint' (did you mean 'car_paint'?"},
      {std::string("eval ") + kInvalid + " --wi 0,0,1 --wo 0,0,1", "ior_below_one.json:/materials/0/nodes/1/ior: "},
      {"eval" + car + " --wo 0,0,1", "--wi is required"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.args);
    auto r = test::run_cli(c.args, test::source_dir());
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find(c.message) != std::string::npos);
  }
  auto missing = test::run_cli("eval no/such/file.json --wi 0,0,1 --wo 0,0,1", test::source_dir());
  CHECK(missing.exit_code == 1);
  CHECK(missing.out.empty());
}

TEST_CASE("lamina albedo prints the library's directional albedo and rejects theta outside 0 to 90") {
  cpu::Evaluator evaluator = library_evaluator(kCarPaint);
  glm::vec3 expected = evaluator.albedo(ShadingContext{}, glm::vec3(0.0f, 0.0f, 1.0f));

  auto r =
      test::run_cli(std::string("albedo ") + kCarPaint + " --material car_paint --theta 0 --json", test::source_dir());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  auto report = nlohmann::json::parse(r.out);
  CHECK(report["theta_deg"].get<double>() == 0.0);
  REQUIRE(report["albedo"].size() == 3);
  for (int c = 0; c < 3; ++c) {
    float a = report["albedo"][c].get<float>();
    CHECK(a >= 0.0f);
    CHECK(a <= 1.0f);
    CHECK(a == expected[c]);
  }
  auto plain = test::run_cli(std::string("albedo ") + kCarPaint + " --theta 0", test::source_dir());
  CHECK(plain.exit_code == 0);
  CHECK(plain.out.rfind("albedo = ", 0) == 0);

  for (const char* theta : {"95", "90", "-1", "nan"}) {
    CAPTURE(theta);
    auto bad = test::run_cli(std::string("albedo ") + kCarPaint + " --theta " + theta, test::source_dir());
    CHECK(bad.exit_code == 2);
    CHECK(bad.out.empty());
  }
}

TEST_CASE("lamina plot writes the same PNG of the requested size every time and nothing for an invalid file") {
  test::TempDir dir;
  auto first = dir.path() / "car_paint.png";
  auto second = dir.path() / "again.png";
  std::string args = "plot " + quoted(test::source_dir() / kCarPaint) + " --material car_paint --size 800 -o ";
  auto r = test::run_cli(args + quoted(first));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.empty());
  auto image = load_linear_image(first, false);
  CHECK(image->width == 800);
  CHECK(image->height == 400);
  REQUIRE(test::run_cli(args + quoted(second)).exit_code == 0);
  CHECK(test::read_file(first) == test::read_file(second));
  CHECK(listing(dir.path()) == std::vector<std::string>{"again.png", "car_paint.png"});  // no temporary files left

  test::TempDir empty;
  auto invalid =
      test::run_cli("plot " + quoted(test::source_dir() / kInvalid) + " -o " + quoted(empty.path() / "plot.png"));
  CHECK(invalid.exit_code == 2);
  CHECK(invalid.err.find("/materials/0/nodes/1/ior: ") != std::string::npos);
  auto unknown = test::run_cli(args + quoted(empty.path() / "plot.png") + " --material nope");
  CHECK(unknown.exit_code == 2);
  auto small = test::run_cli("plot " + quoted(test::source_dir() / kCarPaint) + " --size 10 -o " +
                             quoted(empty.path() / "plot.png"));
  CHECK(small.exit_code == 2);
  CHECK(listing(empty.path()).empty());
}

TEST_CASE("lamina eval and albedo and plot explain themselves with --help") {
  for (const char* command : {"eval", "albedo", "plot"}) {
    CAPTURE(command);
    auto r = test::run_cli(std::string(command) + " --help");
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("--material") != std::string::npos);
  }
  CHECK(test::run_cli("eval --help").out.find("--wi") != std::string::npos);
  CHECK(test::run_cli("albedo --help").out.find("--theta") != std::string::npos);
  CHECK(test::run_cli("plot --help").out.find("--size") != std::string::npos);
}
