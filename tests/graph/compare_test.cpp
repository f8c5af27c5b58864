// lamina compare's measurements (graph/cpu/compare.h): where the layered model is exact, the
// comparison finds no error; every angle it promises is there, each with the reference's error.
#include <doctest/doctest.h>

#include "graph/cpu/compare.h"
#include "graph/cpu_test_support.h"
#include "test_support.h"

namespace lamina {
namespace {

TEST_CASE("a bare Lambert base, where the layered model is exact, compares with no error") {
  const cpu::Evaluator e = test::evaluator_from_text(R"({"format": 1, "materials": [{"name": "m", "surface": "@base",
      "nodes": [{"id": "base", "type": "substrate/lambert", "albedo": [0.8, 0.4, 0.1]}]}]})");
  const cpu::Comparison c = cpu::compare_to_reference(e.bind({}), {2000, 200, 0});
  REQUIRE(c.albedo.size() == std::size(cpu::kCompareAlbedoAngles));
  REQUIRE(c.slices.size() == std::size(cpu::kCompareViewAngles));
  for (const cpu::AlbedoComparison& row : c.albedo) {
    INFO("theta " << row.theta_deg);
    CHECK(row.relative_error < 1e-5);
    CHECK(row.albedo.reference.r == doctest::Approx(0.8).epsilon(1e-6).scale(0.0));
  }
  for (const cpu::SliceComparison& s : c.slices) {
    CHECK(s.f.size() == s.theta_i_deg.size());
    CHECK(s.theta_i_deg.front() == -cpu::kCompareLightLimit);
    CHECK(s.theta_i_deg.back() == doctest::Approx(cpu::kCompareLightLimit));
    CHECK(s.rms_relative_error < 1e-5);
  }
  CHECK(c.max_albedo_error < 1e-5);
}

TEST_CASE("compare measures the model's error against the reference's value, with the reference's noise") {
  // A coat over a white base: the layered model is not exact here, and the error is what the
  // definitions say, computed from the reported values.
  const cpu::Evaluator e = test::load_evaluator(test::source_dir() / "examples" / "materials" / "sugar.json");
  const cpu::Comparison c = cpu::compare_to_reference(e.bind({}), {4000, 300, 1});
  double worst = 0.0;
  for (const cpu::AlbedoComparison& row : c.albedo) {
    double expected = 0.0;
    for (int ch = 0; ch < 3; ++ch) {
      const double r = row.albedo.reference[ch];
      expected = std::max(expected, std::abs(row.albedo.model[ch] - r) / std::max(r, cpu::kCompareErrorFloor));
      CHECK(row.albedo.std_error[ch] > 0.0);
    }
    CHECK(row.relative_error == doctest::Approx(expected));
    worst = std::max(worst, expected);
  }
  CHECK(c.max_albedo_error == doctest::Approx(worst));
  for (const cpu::SliceComparison& s : c.slices) CHECK(s.rms_relative_error > 0.0);
}

}  // namespace
}  // namespace lamina
