// lamina eval, albedo and plot: the CLI prints what the library computes, rejects mistakes with
// exit 2 and nothing on stdout, and writes images only for valid input.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "graph/compile.h"
#include "graph/cpu/compare.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu/flake_slab.h"
#include "graph/cpu/image.h"
#include "graph/cpu/reference.h"
#include "graph/cpu_test_support.h"
#include "graph/glsl/glsl_text.h"
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

TEST_CASE("lamina eval --light prints what a fluorescent material returns of light of that colour") {
  const char* const card = "examples/materials/fluorescent_card.json";
  const glm::vec3 wi = glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f));
  const glm::vec3 wo = glm::normalize(glm::vec3(-0.4f, 0.0f, 1.0f));
  cpu::Evaluator evaluator = library_evaluator(card);
  const glm::vec3 green(0.0f, 1.0f, 0.0f);
  const glm::vec3 expected = evaluator.eval(ShadingContext{}, wi, wo, green);
  REQUIRE(expected.r > 0.0f);  // green light comes back partly red: the card glows
  auto r = test::run_cli(std::string("eval ") + card + " --wi 0.3,0.1,1 --wo -0.4,0,1 --light 0,1,0 --json",
                         test::source_dir());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  auto report = nlohmann::json::parse(r.out);
  for (int c = 0; c < 3; ++c) CHECK(report["f"][c].get<float>() == expected[c]);
  CHECK(report["pdf"].get<float>() == evaluator.eval_pdf(ShadingContext{}, wi, wo).pdf);
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
      {"eval" + car + " --wi 1,x,0 --wo 0,0,1", "--wi: 'x' in '1,x,0' is not a number"},
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1e39", "--wo: '1e39' in '0,0,1e39' is beyond the single-precision range"},
      // 1e-320 is a finite number (below float precision: 0); what is wrong is the zero direction.
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1e-320", "--wo: the zero vector '0,0,1e-320' has no direction"},
      {"eval" + car + " --wi 0,0,1 --wo 1,0", "--wo: expected 3 numbers, got 2"},
      {"eval" + car + " --wi 0,0,1 --wo nan,0,1", "--wo: 'nan'"},
      {"eval" + car + " --wi 0,0,0 --wo 0,0,1", "--wi: the zero vector"},
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1 --uv 0.5", "--uv: expected 2 numbers"},
      {"eval" + car + " --material carpaint --wi 0,0,1 --wo 0,0,1",
       "car_paint.json:/materials: no material named 'carpaint' (did you mean 'car_paint'?"},
      {std::string("eval ") + kInvalid + " --wi 0,0,1 --wo 0,0,1", "ior_below_one.json:/materials/0/nodes/1/ior: "},
      {"eval" + car + " --wo 0,0,1", "--wi is required"},
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1 --light 1,-1,0", "--light 1,-1,0: expected three finite numbers >= 0"},
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1 --light 1,1", "--light: expected 3 numbers, got 2 in '1,1' (write R,G,B"},
      {"eval" + car + " --wi 0,0,1 --wo 0,0,1 --light nan,0,0", "--light: 'nan'"},
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

TEST_CASE(
    "the --model option composes the stack in the model named instead of the material's own, and refuses others") {
  // car_paint names no model: each --model gives what a copy of it naming that model gives.
  const std::string text = test::read_file(test::source_dir() / kCarPaint);
  REQUIRE(text.find("\"model\"") == std::string::npos);
  const glm::vec3 wo = glm::normalize(glm::vec3(0.5f, 0.0f, 0.5f));
  std::set<float> reds;
  for (const std::string model : {"weidlich_wilkie", "energy_conserving"}) {
    CAPTURE(model);
    const std::string copy = glsl::replace_all(text, R"("surface")", "\"model\": \"" + model + "\", \"surface\"");
    const cpu::Evaluator evaluator = test::evaluator_from_text(copy);
    const glm::vec3 expected = evaluator.albedo(ShadingContext{}, wo);
    for (const std::string command : {"albedo", "eval"}) {
      const std::string query = command == "albedo" ? " --theta 45" : " --wi 0,0,1 --wo 1,0,1";
      auto r = test::run_cli(command + " " + kCarPaint + query + " --json --model " + model, test::source_dir());
      INFO(r.err);
      REQUIRE(r.exit_code == 0);
      auto report = nlohmann::json::parse(r.out);
      if (command == "albedo") {
        for (int c = 0; c < 3; ++c) CHECK(report["albedo"][c].get<float>() == expected[c]);
      } else {
        const glm::vec3 f = evaluator.eval(ShadingContext{}, glm::vec3(0.0f, 0.0f, 1.0f), wo);
        for (int c = 0; c < 3; ++c) CHECK(report["f"][c].get<float>() == f[c]);
      }
    }
    reds.insert(expected.x);
  }
  CHECK(reds.size() == 2);  // the two models differ here, so the option was not ignored
  auto bad = test::run_cli(std::string("albedo ") + kCarPaint + " --theta 45 --model conserving", test::source_dir());
  CHECK(bad.exit_code == 2);
  CHECK(bad.out.empty());
  CHECK(bad.err.find("--model") != std::string::npos);
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
  auto image = load_image_file(first, false);
  CHECK(image->width == 800);
  CHECK(image->height == 400);
  // It is a picture, not a blank canvas. The figure's layout (tools/plot_figure.cpp): at 800 x 400
  // the slices fill a 2 x 2 grid left of x = 480 below y = 46; the sphere, 300 px wide, is centred
  // in the panel right of x = 480.
  auto pixel = [&](int x, int y) { return image->texels[size_t(y) * size_t(image->width) + size_t(x)]; };
  auto grey = [](glm::vec4 c) { return (c.x + c.y + c.z) / 3.0f; };
  const glm::vec4 panel = pixel(795, 60);  // the sphere panel's background, beside the sphere
  float lo = 1.0f, hi = 0.0f;
  int disk = 0, unlike_panel = 0;
  for (int y = 223 - 100; y <= 223 + 100; ++y)
    for (int x = 640 - 100; x <= 640 + 100; ++x) {
      if ((x - 640) * (x - 640) + (y - 223) * (y - 223) > 100 * 100) continue;
      ++disk;
      const glm::vec4 c = pixel(x, y);
      lo = std::min(lo, grey(c));
      hi = std::max(hi, grey(c));
      if (glm::length(glm::vec3(c) - glm::vec3(panel)) > 0.02f) ++unlike_panel;
    }
  CHECK(unlike_panel == disk);  // the sphere covers its inner two thirds
  CHECK(hi - lo > 0.1f);        // and is shaded, not flat
  for (int cell = 0; cell < 4; ++cell) {
    CAPTURE(cell);
    const int x0 = (cell % 2) * 240, y0 = 46 + (cell / 2) * 177;
    std::set<std::array<float, 3>> colours;
    for (int y = y0; y < y0 + 177; ++y)
      for (int x = x0; x < x0 + 240; ++x) colours.insert({pixel(x, y).x, pixel(x, y).y, pixel(x, y).z});
    CHECK(colours.size() > 20);  // background, grid, axes, labels and the curves' colours
  }
  REQUIRE(test::run_cli(args + quoted(second)).exit_code == 0);
  CHECK(test::read_file(first) == test::read_file(second));
  CHECK(test::listing(dir.path()) ==
        std::vector<std::string>{"again.png", "car_paint.png"});  // no temporary files left

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
  CHECK(test::listing(empty.path()).empty());
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

TEST_CASE("lamina eval, albedo and plot work on every example material") {
  test::TempDir dir;
  // Every third example is plotted from the first (under the sanitisers, where the CLI is 3-5x
  // slower, every fourth untextured one from the fourth): a plot of a textured example resolves its
  // stack at each of 640,000 subsamples (Lavender Lepidolite's 53 entries take 25 s optimised), and
  // the main job (tools/run_examples.sh) plots every example anyway. Chosen by position alone, the
  // sanitised run came to plot two textured examples when three were added, and took 167 s.
#ifdef LAMINA_SANITIZED
  const size_t plot_every = 4, first_plotted = 3;
  const bool untextured_only = true;
#else
  const size_t plot_every = 3, first_plotted = 0;
  const bool untextured_only = false;
#endif
  size_t index = 0, plotted = 0;
  for (const auto& file : test::example_files()) {
    const std::string name = file.stem().string();
    CAPTURE(name);
    cpu::Evaluator evaluator = library_evaluator("examples/materials/" + name + ".json");
    // eval --json: one object, "f" three finite non-negative floats and "pdf" one, the library's values.
    auto eval = test::run_cli("eval " + quoted(file) + " --wi 0.3,0.1,1 --wo -0.4,0,1 --uv 0.3,0.7 --json");
    INFO(eval.err);
    REQUIRE(eval.exit_code == 0);
    CHECK(eval.err.empty());
    auto report = nlohmann::json::parse(eval.out);
    REQUIRE(report.is_object());
    CHECK(report.size() == 2);
    REQUIRE(report.contains("f"));
    REQUIRE(report.contains("pdf"));
    REQUIRE(report["f"].is_array());
    REQUIRE(report["f"].size() == 3);
    REQUIRE(report["pdf"].is_number());
    ShadingContext ctx;
    ctx.uv = glm::vec2(0.3f, 0.7f);
    cpu::EvalPdf expected = evaluator.eval_pdf(ctx, glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f)),
                                               glm::normalize(glm::vec3(-0.4f, 0.0f, 1.0f)));
    for (int c = 0; c < 3; ++c) {
      REQUIRE(report["f"][c].is_number());
      float v = report["f"][c].get<float>();
      CHECK(std::isfinite(v));
      CHECK(v >= 0.0f);
      CHECK(v == expected.f[c]);
    }
    float pdf = report["pdf"].get<float>();
    CHECK(std::isfinite(pdf));
    CHECK(pdf > 0.0f);
    CHECK(pdf == expected.pdf);

    // albedo --json: three finite non-negative floats and the angle.
    auto albedo = test::run_cli("albedo " + quoted(file) + " --theta 45 --points 256 --json");
    INFO(albedo.err);
    REQUIRE(albedo.exit_code == 0);
    auto a = nlohmann::json::parse(albedo.out);
    CHECK(a.size() == 2);
    CHECK(a["theta_deg"].get<double>() == 45.0);
    REQUIRE(a["albedo"].size() == 3);
    for (int c = 0; c < 3; ++c) {
      float v = a["albedo"][c].get<float>();
      CHECK(std::isfinite(v));
      CHECK(v >= 0.0f);
    }

    // plot: a PNG of the requested size, nothing on stdout.
    if (untextured_only && !evaluator.program().ops.empty()) continue;
    if (index++ % plot_every != first_plotted) continue;
    ++plotted;
    auto png = dir.path() / (name + ".png");
    auto plot = test::run_cli("plot " + quoted(file) + " --size 800 -o " + quoted(png));
    INFO(plot.err);
    REQUIRE(plot.exit_code == 0);
    CHECK(plot.out.empty());
    REQUIRE(std::filesystem::is_regular_file(png));
    CHECK(test::read_file(png).rfind("\x89PNG\r\n\x1a\n", 0) == 0);
    auto image = load_image_file(png, false);
    CHECK(image->width == 800);
    CHECK(image->height == 400);
  }
  CHECK(test::listing(dir.path()).size() == plotted);
}

TEST_CASE("lamina plot takes the slices' uv and the sky's radiance, and rejects bad values with exit 2") {
  test::TempDir dir;
  // The seeds' model, whose textured points resolve without the default model's quadratures: these
  // options do not depend on the model, and every example is plotted in its own model above.
  const std::string checker =
      quoted(test::source_dir() / "examples/materials/checker_tiles.json") + " --model weidlich_wilkie";
  // The slices of a textured material follow --uv: on a red square and on a gold square the
  // pictures differ; with the sky (the default) the sphere is brighter than without.
  auto red = dir.path() / "red.png", gold = dir.path() / "gold.png", sky = dir.path() / "sky.png";
  REQUIRE(test::run_cli("plot " + checker + " --size 800 --ambient 0 --uv 0.05,0.05 -o " + quoted(red)).exit_code == 0);
  REQUIRE(test::run_cli("plot " + checker + " --size 800 --ambient 0 --uv 0.18,0.05 -o " + quoted(gold)).exit_code ==
          0);
  REQUIRE(test::run_cli("plot " + checker + " --size 800 --uv 0.05,0.05 -o " + quoted(sky)).exit_code == 0);
  CHECK(test::read_file(red) != test::read_file(gold));
  auto lit = load_image_file(sky, false), unlit = load_image_file(red, false);
  double sum_lit = 0.0, sum_unlit = 0.0;
  for (size_t i = 0; i < lit->texels.size(); ++i) {
    sum_lit += double(lit->texels[i].x + lit->texels[i].y + lit->texels[i].z);
    sum_unlit += double(unlit->texels[i].x + unlit->texels[i].y + unlit->texels[i].z);
  }
  CHECK(sum_lit > sum_unlit);

  test::TempDir empty;
  const std::string out = " -o " + quoted(empty.path() / "plot.png");
  for (const char* bad : {"--uv 0.5", "--uv 0.5,x", "--uv nan,0", "--ambient -1", "--ambient 11", "--ambient nan",
                          "--size 10", "--material nope"}) {
    CAPTURE(bad);
    auto r = test::run_cli("plot " + checker + " " + bad + out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK(!r.err.empty());
  }
  auto no_format = test::run_cli("plot " + checker + " -o " + quoted(empty.path() / "plot.nothing"));
  CHECK(no_format.exit_code == 2);
  for (const char* bad : {"--wi 0,0,1 --wo 0,0,1 --uv 1", "--wi 0,0,1 --wo 0,0", "--wo 0,0,1"}) {
    CAPTURE(bad);
    auto r = test::run_cli("eval " + checker + " " + bad + " --json");
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
  }
  for (const char* bad : {"--theta 90", "--theta 10 --points 0", "--theta 10 --uv 2"}) {
    CAPTURE(bad);
    auto r = test::run_cli("albedo " + checker + " " + bad + " --json");
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
  }
  CHECK(test::listing(empty.path()).empty());
}

TEST_CASE("lamina reference prints the library's estimate with its error, and rejects mistakes with exit 2") {
  const glm::vec3 wi = glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f));
  const glm::vec3 wo = glm::normalize(glm::vec3(-0.4f, 0.0f, 1.0f));
  cpu::Evaluator evaluator = library_evaluator(kCarPaint);
  const cpu::ReferenceEstimate expected = cpu::reference_eval(evaluator.bind({}), wi, wo, {4000, 1000, 5});

  auto json = test::run_cli(
      std::string("reference ") + kCarPaint + " --wi 0.3,0.1,1 --wo -0.4,0,1 --walks 4000 " + "--seed 5 --json",
      test::source_dir());
  INFO(json.err);
  REQUIRE(json.exit_code == 0);
  const nlohmann::json report = nlohmann::json::parse(json.out);
  for (int c = 0; c < 3; ++c) {
    CHECK(report.at("f")[c].get<double>() == expected.value[c]);
    CHECK(report.at("std_error")[c].get<double>() == expected.std_error[c]);
  }
  CHECK(report.at("walks") == 4000);

  auto albedo =
      test::run_cli(std::string("reference ") + kCarPaint + " --albedo --theta 30 --walks 2000", test::source_dir());
  REQUIRE(albedo.exit_code == 0);
  double r = -1, g = -1, b = -1;
  REQUIRE(std::sscanf(albedo.out.c_str(), "albedo = %lg %lg %lg  +-", &r, &g, &b) == 3);
  for (double v : {r, g, b}) CHECK((v > 0.0 && v < 1.0));

  for (const char* bad : {" --wi 0,0,1", " --albedo", " --albedo --theta 90", " --wi 0,0,1 --wo 0,0,1 --walks 0",
                          " --albedo --theta 10 --wo 0,0,1", " --wi 0,0,1 --wo 0,0,1 --max-depth 0"}) {
    auto run = test::run_cli(std::string("reference ") + kCarPaint + bad, test::source_dir());
    INFO(bad << ": " << run.err);
    CHECK(run.exit_code == 2);
    CHECK(run.out.empty());
    CHECK(run.err.find("lamina: ") != std::string::npos);
  }
  auto invalid = test::run_cli(std::string("reference ") + kInvalid + " --albedo --theta 10", test::source_dir());
  CHECK(invalid.exit_code == 2);
  CHECK(invalid.out.empty());
  CHECK(invalid.err.find("ior_below_one.json") != std::string::npos);
}

TEST_CASE("lamina reference --flakes solves the paint's full model beside the evaluation, and refuses other stacks") {
  // pearlescent_white's paint written out here as the full model's slab (its coat of index 1.5 the
  // binder's boundary, its flakes' 9 degrees a Beckmann slope of tan 9 deg), solved coarsely as the
  // command is asked to.
  const std::string file = "examples/materials/pearlescent_white.json";
  const double flake[3] = {0.3, 0.28, 0.24}, base[3] = {0.8, 0.8, 0.78};
  const glm::vec3 wi = glm::normalize(glm::vec3(0.4f, 0.0f, 1.0f)), wo = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));
  cpu::Evaluator evaluator = library_evaluator(file);
  const cpu::ShadingPoint point = evaluator.bind({});
  auto albedo =
      test::run_cli("reference " + file + " --flakes --coarse --albedo --theta 30 --json", test::source_dir());
  auto brdf =
      test::run_cli("reference " + file + " --flakes --coarse --wi 0.4,0,1 --wo 0,0.3,1 --json", test::source_dir());
  INFO(albedo.err << brdf.err);
  REQUIRE(albedo.exit_code == 0);
  REQUIRE(brdf.exit_code == 0);
  const nlohmann::json a = nlohmann::json::parse(albedo.out), f = nlohmann::json::parse(brdf.out);
  const glm::vec3 view(std::sin(glm::radians(30.0f)), 0.0f, std::cos(glm::radians(30.0f)));
  for (int c = 0; c < 3; ++c) {
    cpu::FlakeSlab slab;
    slab.eta = 1.5;
    slab.coverage = 1.2;
    slab.flake_slope = std::tan(9.0 * test::kPi / 180.0);
    slab.flake_reflectance = flake[c];
    slab.flake_transmittance = 0.68;
    slab.substrate_albedo = base[c];
    const cpu::FlakeSlabSolution seen(slab, {std::cos(30.0 * test::kPi / 180.0)}, cpu::FlakeSlabOptions::coarse());
    CHECK(a.at("albedo")[c].get<double>() == doctest::Approx(seen.albedo(0) + seen.mirror(0)).epsilon(1e-5));
    // wo lies a quarter turn from the mirror side of the plane of incidence.
    const cpu::FlakeSlabSolution pair(slab, {double(wi.z), double(wo.z)}, cpu::FlakeSlabOptions::coarse());
    CHECK(f.at("f")[c].get<double>() == doctest::Approx(pair.brdf(0, 1, test::kPi / 2.0)).epsilon(1e-5));
    CHECK(a.at("model")[c].get<double>() == doctest::Approx(point.albedo(view)[c]).epsilon(1e-6));
    CHECK(f.at("model")[c].get<double>() == doctest::Approx(point.eval(wi, wo)[c]).epsilon(1e-6));
  }
  CHECK(a.at("boundary_slope").get<double>() == doctest::Approx(std::tan(2.0 * test::kPi / 180.0)).epsilon(1e-5));
  CHECK(a.at("spectral_fold") == false);

  // Not a layer over a flake paint alone; --coarse without --flakes; directions below the horizon.
  for (const std::string& bad :
       {std::string(kCarPaint) + " --flakes --albedo --theta 30", file + " --coarse --albedo --theta 30",
        file + " --flakes --coarse --wi 0.4,0,1 --wo 0,0.3,-1"}) {
    auto run = test::run_cli("reference " + bad, test::source_dir());
    INFO(bad << ": " << run.err);
    CHECK(run.exit_code == 2);
    CHECK(run.out.empty());
    CHECK(run.err.find("lamina: ") != std::string::npos);
  }
  auto other =
      test::run_cli(std::string("reference ") + kCarPaint + " --flakes --albedo --theta 30", test::source_dir());
  CHECK(other.err.find("car_paint.json: material \"car_paint\": the full flake model takes a material whose surface "
                       "is a layer over a substrate/flake_paint") != std::string::npos);
}

TEST_CASE("lamina compare prints the model against the reference, as text and JSON, and rejects mistakes") {
  auto json = test::run_cli(std::string("compare ") + kCarPaint + " --albedo-walks 500 --slice-walks 50 --json",
                            test::source_dir());
  INFO(json.err);
  REQUIRE(json.exit_code == 0);
  const nlohmann::json report = nlohmann::json::parse(json.out);
  CHECK(report.at("albedo").size() == std::size(cpu::kCompareAlbedoAngles));
  CHECK(report.at("slices").size() == std::size(cpu::kCompareViewAngles));
  for (const auto& row : report.at("albedo")) {
    CHECK(row.at("model").size() == 3);
    CHECK(row.at("reference").size() == 3);
    CHECK(row.at("std_error").size() == 3);
  }
  auto text =
      test::run_cli(std::string("compare ") + kCarPaint + " --albedo-walks 500 --slice-walks 50", test::source_dir());
  REQUIRE(text.exit_code == 0);
  CHECK(text.out.find("summary: albedo error at most") != std::string::npos);
  for (const char* bad : {" --albedo-walks 0", " --slice-walks -3", " --uv 0.5"}) {
    auto run = test::run_cli(std::string("compare ") + kCarPaint + bad, test::source_dir());
    INFO(bad << ": " << run.err);
    CHECK(run.exit_code == 2);
    CHECK(run.out.empty());
  }
  auto invalid = test::run_cli(std::string("compare ") + kInvalid, test::source_dir());
  CHECK(invalid.exit_code == 2);
  CHECK(invalid.out.empty());
}

TEST_CASE(
    "lamina compare --plot draws the model's albedo and slices with the reference's points, and nothing for "
    "mistakes") {
  // A bare Lambert base, which the model and the reference both know exactly: in the albedo panel each
  // channel is a flat line at its albedo.
  test::TempDir dir;
  std::ofstream(dir.path() / "paper.json") << R"({"format": 1, "materials": [{"name": "paper", "surface": "@paper",
    "nodes": [{"id": "paper", "type": "substrate/lambert", "albedo": [0.2, 0.5, 0.8]}]}]})";
  auto r =
      test::run_cli("compare paper.json --albedo-walks 256 --slice-walks 16 --size 800 --plot paper.png", dir.path());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("summary: albedo error at most") != std::string::npos);  // the table is printed too
  auto image = load_image_file(dir.path() / "paper.png", false);
  REQUIRE(image->width == 800);
  REQUIRE(image->height == 400);
  auto pixel = [&](int x, int y) { return glm::vec3(image->texels[size_t(y) * size_t(image->width) + size_t(x)]); };
  // The layout (tools/plot_compare.cpp) at 800 x 400: the albedo axes span x 513..789 for 0..90
  // degrees and y 372..68 for albedo 0..1. At 47 degrees, between the reference's points at 40 and
  // 50 and off the grid, only the model's lines are drawn: red at 0.2, green at 0.5, blue at 0.8, and
  // nothing between.
  const int x = int(std::lround(513.0 + 276.0 * 47.0 / 90.0));
  auto y_of = [](double a) { return int(std::lround(372.0 - 304.0 * a)); };
  auto strongest = [&](int y) {
    glm::vec3 best(0.0f);
    for (int dy = -2; dy <= 2; ++dy) best = glm::max(best, pixel(x, y + dy));
    return best;
  };
  const glm::vec3 red = strongest(y_of(0.2)), green = strongest(y_of(0.5)), blue = strongest(y_of(0.8));
  CHECK(red.x > 0.6f);
  CHECK(red.x > 2.0f * std::max(red.y, red.z));
  CHECK(green.y > 0.6f);
  CHECK(green.y > 2.0f * std::max(green.x, green.z));
  CHECK(blue.z > 0.6f);
  CHECK(blue.z > 1.5f * std::max(blue.x, blue.y));
  CHECK(glm::length(pixel(x, y_of(0.65))) < 0.15f);  // the panel's background
  // The reference's squares at 40 and 50 degrees sit on the same lines.
  for (int theta : {40, 50}) {
    const int xr = int(std::lround(513.0 + 276.0 * theta / 90.0));
    CHECK(pixel(xr, y_of(0.8)).z > 0.6f);
  }
  // The four slice panels hold their curves and points.
  for (int cell = 0; cell < 4; ++cell) {
    CAPTURE(cell);
    const int x0 = (cell % 2) * 240, y0 = 46 + (cell / 2) * 177;
    std::set<std::array<float, 3>> colours;
    for (int y = y0; y < y0 + 177; ++y)
      for (int xx = x0; xx < x0 + 240; ++xx) colours.insert({pixel(xx, y).x, pixel(xx, y).y, pixel(xx, y).z});
    CHECK(colours.size() > 20);
  }

  test::TempDir empty;
  std::ofstream(empty.path() / "paper.json") << test::read_file(dir.path() / "paper.json");
  for (const char* bad : {" --plot paper.unknown", " --plot paper.png --size 10"}) {
    auto run = test::run_cli(std::string("compare paper.json --albedo-walks 16 --slice-walks 4") + bad, empty.path());
    INFO(bad << ": " << run.err);
    CHECK(run.exit_code == 2);
    CHECK(run.out.empty());
  }
  CHECK(test::listing(empty.path()) == std::vector<std::string>{"paper.json"});
}
