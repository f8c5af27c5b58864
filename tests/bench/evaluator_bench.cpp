// Cost of the layered evaluation against a single Torrance-Sparrow conductor lobe, in one run.
// Run: bash tools/run_bench.sh (prints the ratios), or build/release/tests/bench/lamina_bench.
#include <benchmark/benchmark.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/load.h"
#include "queries.h"

namespace {

constexpr size_t kQueries = 4096;

// One Torrance-Sparrow lobe: the Car Paint's aluminium base without its varnish.
const char* kSingleLobe = R"({"format": 1, "materials": [{"name": "single_lobe", "surface": "@metal", "nodes": [
    {"id": "metal", "type": "substrate/conductor", "metal": "aluminium", "roughness_deg": 12.0}]}]})";

// The textured benchmarks: the Car Paint's stack (varnish over absorbing lacquer over aluminium),
// untextured, then with its lacquer's thickness driven by a checker (the cost of resolving the
// stack at every shading point, with the cheapest texture), a 4-octave fBm noise or Voronoi
// cells, and as a glitter-like select of 4 stacks by Voronoi cell (the car paint and three silver
// flakes of different slopes under the same varnish). Each is evaluated at a different uv per
// query, so that the texture operations run at every call.
const char* kTexturedStack = R"({"format": 1, "materials": [{"name": "NAME", "surface": "SURFACE", "nodes": [
    {"id": "tiles", "type": "texture/checker"},
    {"id": "grain", "type": "texture/noise", "scale": 8.0, "octaves": 4},
    {"id": "cells", "type": "texture/voronoi", "scale": 40.0, "tilt_deg": 3.0},
    {"id": "depth", "type": "math/remap", "value": "@SOURCE", "out_min": 1.0, "out_max": 2.0},
    {"id": "cell_index", "type": "math/remap", "value": "@cells.value", "out_max": 4.0},
    {"id": "pick", "type": "select", "index": "@cell_index", "stack_0": "@paint", "stack_1": "@flake_a",
     "stack_2": "@flake_b", "stack_3": "@flake_c"},
    {"id": "paint", "type": "layer", "interface": "@varnish", "medium": "@lacquer", "base": "@aluminium"},
    {"id": "flake_a", "type": "layer", "interface": "@varnish", "base": "@silver_a"},
    {"id": "flake_b", "type": "layer", "interface": "@varnish", "base": "@silver_b"},
    {"id": "flake_c", "type": "layer", "interface": "@varnish", "base": "@silver_c"},
    {"id": "varnish", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 1.0},
    {"id": "lacquer", "type": "medium/absorbing", "thickness": THICKNESS, "absorption": [0.98, 0.4, 0.28]},
    {"id": "aluminium", "type": "substrate/conductor", "metal": "aluminium", "roughness_deg": 12.0},
    {"id": "silver_a", "type": "substrate/conductor", "metal": "silver", "roughness_deg": 1.0},
    {"id": "silver_b", "type": "substrate/conductor", "metal": "silver", "roughness_deg": 3.0},
    {"id": "silver_c", "type": "substrate/conductor", "metal": "silver", "roughness_deg": 5.0}]}]})";

lamina::cpu::Evaluator textured(const char* name, const char* surface, const char* source, const char* thickness) {
  using lamina::glsl::replace_all;
  const std::string text = replace_all(
      replace_all(replace_all(replace_all(kTexturedStack, "NAME", name), "SURFACE", surface), "SOURCE", source),
      "THICKNESS", thickness);
  auto checked = lamina::check_text(text, "bench.json");
  return lamina::cpu::Evaluator(lamina::compile(*checked.graphs[0], "bench.json"));
}

lamina::cpu::Evaluator evaluator_from_text(const char* text) {
  auto checked = lamina::check_text(text, "bench.json");
  return lamina::cpu::Evaluator(lamina::compile(*checked.graphs[0], "bench.json"));
}

// An example's first material under `model` ("weidlich_wilkie", "energy_conserving").
lamina::cpu::Evaluator evaluator_from_example(const char* name, const char* model = "weidlich_wilkie") {
  std::string file = std::string(LAMINA_SOURCE_DIR) + "/examples/materials/" + name + ".json";
  std::ifstream in(file);
  nlohmann::json document = nlohmann::json::parse(in);
  document["materials"][0]["model"] = model;
  auto checked = lamina::check_text(document.dump(), file);
  return lamina::cpu::Evaluator(lamina::compile(*checked.graphs[0], file));
}

using lamina::bench::Queries;

const Queries& queries() {
  static const Queries q(kQueries);
  return q;
}

void eval_scalar(benchmark::State& state, const lamina::cpu::Evaluator& e) {
  const Queries& q = queries();
  lamina::ShadingContext ctx;
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e.eval(ctx, q.wi[i], q.wo[i]));
    i = (i + 1) % kQueries;
  }
  state.SetItemsProcessed(state.iterations());
}

void eval_batched(benchmark::State& state, const lamina::cpu::Evaluator& e) {
  const Queries& q = queries();
  std::vector<glm::vec3> f(kQueries);
  for (auto _ : state) {
    e.eval({}, q.wi, q.wo, f);
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t(kQueries));
}

void eval_pdf_batched(benchmark::State& state, const lamina::cpu::Evaluator& e) {
  const Queries& q = queries();
  std::vector<lamina::cpu::EvalPdf> out(kQueries);
  for (auto _ : state) {
    e.eval_pdf({}, q.wi, q.wo, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t(kQueries));
}

// As eval_scalar, at a different uv per query (the u of the query's random numbers).
void eval_textured(benchmark::State& state, const lamina::cpu::Evaluator& e) {
  const Queries& q = queries();
  lamina::ShadingContext ctx;
  size_t i = 0;
  for (auto _ : state) {
    ctx.uv = q.u[i];
    benchmark::DoNotOptimize(e.eval(ctx, q.wi[i], q.wo[i]));
    i = (i + 1) % kQueries;
  }
  state.SetItemsProcessed(state.iterations());
}

void sample_scalar(benchmark::State& state, const lamina::cpu::Evaluator& e) {
  const Queries& q = queries();
  lamina::ShadingContext ctx;
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e.sample(ctx, q.wo[i], q.u[i], q.u_lobe[i]));
    i = (i + 1) % kQueries;
  }
  state.SetItemsProcessed(state.iterations());
}

const lamina::cpu::Evaluator& single() {
  static const auto e = evaluator_from_text(kSingleLobe);
  return e;
}
const lamina::cpu::Evaluator& car_paint() {
  static const auto e = evaluator_from_example("car_paint");
  return e;
}
const lamina::cpu::Evaluator& house_paint() {
  static const auto e = evaluator_from_example("house_paint");
  return e;
}
// The same two under the energy-conserving model.
const lamina::cpu::Evaluator& car_paint_conserving() {
  static const auto e = evaluator_from_example("car_paint", "energy_conserving");
  return e;
}
const lamina::cpu::Evaluator& house_paint_conserving() {
  static const auto e = evaluator_from_example("house_paint", "energy_conserving");
  return e;
}

void BM_eval_single_lobe(benchmark::State& s) { eval_scalar(s, single()); }
void BM_eval_car_paint_2_layers(benchmark::State& s) { eval_scalar(s, car_paint()); }
void BM_eval_house_paint_3_layers(benchmark::State& s) { eval_scalar(s, house_paint()); }
void BM_eval_batch_single_lobe(benchmark::State& s) { eval_batched(s, single()); }
void BM_eval_batch_car_paint_2_layers(benchmark::State& s) { eval_batched(s, car_paint()); }
void BM_eval_batch_house_paint_3_layers(benchmark::State& s) { eval_batched(s, house_paint()); }
void BM_eval_pdf_batch_single_lobe(benchmark::State& s) { eval_pdf_batched(s, single()); }
void BM_eval_pdf_batch_car_paint_2_layers(benchmark::State& s) { eval_pdf_batched(s, car_paint()); }
void BM_eval_pdf_batch_house_paint_3_layers(benchmark::State& s) { eval_pdf_batched(s, house_paint()); }
void BM_sample_single_lobe(benchmark::State& s) { sample_scalar(s, single()); }
void BM_sample_car_paint_2_layers(benchmark::State& s) { sample_scalar(s, car_paint()); }
void BM_sample_house_paint_3_layers(benchmark::State& s) { sample_scalar(s, house_paint()); }

void BM_eval_car_paint_2_layers_conserving(benchmark::State& s) { eval_scalar(s, car_paint_conserving()); }
void BM_eval_house_paint_3_layers_conserving(benchmark::State& s) { eval_scalar(s, house_paint_conserving()); }
void BM_eval_batch_car_paint_2_layers_conserving(benchmark::State& s) { eval_batched(s, car_paint_conserving()); }
void BM_eval_batch_house_paint_3_layers_conserving(benchmark::State& s) { eval_batched(s, house_paint_conserving()); }
void BM_eval_pdf_batch_car_paint_2_layers_conserving(benchmark::State& s) {
  eval_pdf_batched(s, car_paint_conserving());
}
void BM_eval_pdf_batch_house_paint_3_layers_conserving(benchmark::State& s) {
  eval_pdf_batched(s, house_paint_conserving());
}
void BM_sample_car_paint_2_layers_conserving(benchmark::State& s) { sample_scalar(s, car_paint_conserving()); }
void BM_sample_house_paint_3_layers_conserving(benchmark::State& s) { sample_scalar(s, house_paint_conserving()); }

// Unused nodes are fine here: the checker warns, and compiling skips them.
const lamina::cpu::Evaluator& untextured() {
  static const auto e = textured("untextured", "@paint", "grain", "1.5");
  return e;
}
const lamina::cpu::Evaluator& checker_textured() {
  static const auto e = textured("checker", "@paint", "tiles.value", "\"@depth\"");
  return e;
}
const lamina::cpu::Evaluator& noise_textured() {
  static const auto e = textured("noise", "@paint", "grain", "\"@depth\"");
  return e;
}
const lamina::cpu::Evaluator& voronoi_textured() {
  static const auto e = textured("voronoi", "@paint", "cells", "\"@depth\"");
  return e;
}
const lamina::cpu::Evaluator& glitter_select() {
  static const auto e = textured("glitter", "@pick", "grain", "1.5");
  return e;
}

void BM_eval_textured_untextured_stack(benchmark::State& s) { eval_textured(s, untextured()); }
void BM_eval_textured_checker(benchmark::State& s) { eval_textured(s, checker_textured()); }
void BM_eval_textured_noise_4_octaves(benchmark::State& s) { eval_textured(s, noise_textured()); }
void BM_eval_textured_voronoi(benchmark::State& s) { eval_textured(s, voronoi_textured()); }
void BM_eval_textured_glitter_select_of_4(benchmark::State& s) { eval_textured(s, glitter_select()); }

// The optics' nodes against a dielectric layer over the same base (the single lobe's aluminium), in
// the default (energy-conserving) model: a 300 nm film of index 1.5 over it, each integration.
const char* kFilmOrLayer = R"({"format": 1, "materials": [{"name": "film", "surface": "SURFACE", "nodes": [
    {"id": "coat", "type": "layer", "interface": "@varnish", "base": "@metal"},
    {"id": "varnish", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 1.0},
    {"id": "metal", "type": "substrate/conductor", "metal": "aluminium", "roughness_deg": 12.0},
    {"id": "film", "type": "substrate/thin_film", "metal": "aluminium", "roughness_deg": 12.0, "thickness_nm": 300.0,
     "film_ior": [1.5, 1.5, 1.5], "integration": "INTEGRATION"}]}]})";

lamina::cpu::Evaluator film_or_layer(const char* surface, const char* integration) {
  using lamina::glsl::replace_all;
  return evaluator_from_text(
      replace_all(replace_all(kFilmOrLayer, "SURFACE", surface), "INTEGRATION", integration).c_str());
}
const lamina::cpu::Evaluator& dielectric_layer() {
  static const auto e = film_or_layer("@coat", "spectral");
  return e;
}
const lamina::cpu::Evaluator& thin_film_spectral() {
  static const auto e = film_or_layer("@film", "spectral");
  return e;
}
const lamina::cpu::Evaluator& thin_film_rgb() {
  static const auto e = film_or_layer("@film", "rgb");
  return e;
}

void BM_eval_optics_dielectric_layer(benchmark::State& s) { eval_scalar(s, dielectric_layer()); }
void BM_eval_optics_thin_film_spectral(benchmark::State& s) { eval_scalar(s, thin_film_spectral()); }
void BM_eval_optics_thin_film_rgb(benchmark::State& s) { eval_scalar(s, thin_film_rgb()); }
void BM_sample_optics_dielectric_layer(benchmark::State& s) { sample_scalar(s, dielectric_layer()); }
void BM_sample_optics_thin_film_spectral(benchmark::State& s) { sample_scalar(s, thin_film_spectral()); }

// A fluorescent base and flake paints (pearlescent_white's flakes; two_tone_pearl's coated ones,
// either fold) against a Lambert base under the same varnish (the fluorescent card's); the
// fluorescent one in white light (eval), in a coloured light (the response) and for the adjoint.
const char* kVarnishOver = R"({"format": 1, "materials": [{"name": "card", "surface": "@card", "nodes": [
    {"id": "card", "type": "layer", "interface": "@varnish", "base": "@BASE"},
    {"id": "varnish", "type": "interface/dielectric", "ior": 1.5, "roughness_deg": 17.0},
    {"id": "lambert", "type": "substrate/lambert", "albedo": [0.55, 0.2, 0.04]},
    {"id": "pigment", "type": "substrate/fluorescent", "albedo": [0.55, 0.2, 0.04], "green_to_red": 0.4,
     "blue_to_red": 0.3, "blue_to_green": 0.15},
    {"id": "flakes", "type": "substrate/flake_paint", "base_color": [0.55, 0.2, 0.04], "flake_color": [0.3, 0.28, 0.24],
     "flake_transmittance": 0.68, "coverage": 1.2, "roughness_deg": 9.0},
    {"id": "coated", "type": "substrate/flake_paint", "base_color": [0.55, 0.2, 0.04], "film_thickness_nm": 160,
     "film_ior": [2.55, 2.65, 2.78], "integration": "FOLD", "coverage": 1.0, "roughness_deg": 10.0}]}]})";
// The varnish over the base of that id, the coated flakes' film folded as `fold` says.
lamina::cpu::Evaluator varnish_over(const char* base, const char* fold = "spectral") {
  using lamina::glsl::replace_all;
  return evaluator_from_text(replace_all(replace_all(kVarnishOver, "BASE", base), "FOLD", fold).c_str());
}
const lamina::cpu::Evaluator& coat_over_lambert() {
  static const auto e = varnish_over("lambert");
  return e;
}
const lamina::cpu::Evaluator& coat_over_fluorescent() {
  static const auto e = varnish_over("pigment");
  return e;
}
const lamina::cpu::Evaluator& coat_over_flake_paint() {
  static const auto e = varnish_over("flakes");
  return e;
}
const lamina::cpu::Evaluator& coat_over_coated_flakes_spectral() {
  static const auto e = varnish_over("coated", "spectral");
  return e;
}
const lamina::cpu::Evaluator& coat_over_coated_flakes_rgb() {
  static const auto e = varnish_over("coated", "rgb");
  return e;
}
void eval_light(benchmark::State& state, const lamina::cpu::Evaluator& e, bool adjoint) {
  const Queries& q = queries();
  lamina::ShadingContext ctx;
  const glm::vec3 light(0.2f, 1.0f, 0.4f);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(adjoint ? e.eval_adjoint(ctx, q.wi[i], q.wo[i], light)
                                     : e.eval(ctx, q.wi[i], q.wo[i], light));
    i = (i + 1) % kQueries;
  }
  state.SetItemsProcessed(state.iterations());
}
void BM_eval_optics_coat_over_lambert(benchmark::State& s) { eval_scalar(s, coat_over_lambert()); }
void BM_eval_optics_coat_over_fluorescent(benchmark::State& s) { eval_scalar(s, coat_over_fluorescent()); }
void BM_eval_optics_coat_over_flake_paint(benchmark::State& s) { eval_scalar(s, coat_over_flake_paint()); }
void BM_eval_optics_coat_over_coated_flakes_spectral(benchmark::State& s) {
  eval_scalar(s, coat_over_coated_flakes_spectral());
}
void BM_eval_optics_coat_over_coated_flakes_rgb(benchmark::State& s) { eval_scalar(s, coat_over_coated_flakes_rgb()); }
void BM_sample_optics_coat_over_lambert(benchmark::State& s) { sample_scalar(s, coat_over_lambert()); }
void BM_sample_optics_coat_over_flake_paint(benchmark::State& s) { sample_scalar(s, coat_over_flake_paint()); }
void BM_eval_optics_coat_over_fluorescent_green_light(benchmark::State& s) {
  eval_light(s, coat_over_fluorescent(), false);
}
void BM_eval_optics_coat_over_fluorescent_adjoint(benchmark::State& s) { eval_light(s, coat_over_fluorescent(), true); }

}  // namespace

BENCHMARK(BM_eval_optics_dielectric_layer);
BENCHMARK(BM_eval_optics_coat_over_lambert);
BENCHMARK(BM_eval_optics_coat_over_fluorescent);
BENCHMARK(BM_eval_optics_coat_over_flake_paint);
BENCHMARK(BM_eval_optics_coat_over_coated_flakes_spectral);
BENCHMARK(BM_eval_optics_coat_over_coated_flakes_rgb);
BENCHMARK(BM_sample_optics_coat_over_lambert);
BENCHMARK(BM_sample_optics_coat_over_flake_paint);
BENCHMARK(BM_eval_optics_coat_over_fluorescent_green_light);
BENCHMARK(BM_eval_optics_coat_over_fluorescent_adjoint);
BENCHMARK(BM_eval_optics_thin_film_spectral);
BENCHMARK(BM_eval_optics_thin_film_rgb);
BENCHMARK(BM_sample_optics_dielectric_layer);
BENCHMARK(BM_sample_optics_thin_film_spectral);

BENCHMARK(BM_eval_textured_untextured_stack);
BENCHMARK(BM_eval_textured_checker);
BENCHMARK(BM_eval_textured_noise_4_octaves);
BENCHMARK(BM_eval_textured_voronoi);
BENCHMARK(BM_eval_textured_glitter_select_of_4);
BENCHMARK(BM_eval_single_lobe);
BENCHMARK(BM_eval_car_paint_2_layers);
BENCHMARK(BM_eval_house_paint_3_layers);
BENCHMARK(BM_eval_batch_single_lobe);
BENCHMARK(BM_eval_batch_car_paint_2_layers);
BENCHMARK(BM_eval_batch_house_paint_3_layers);
BENCHMARK(BM_eval_pdf_batch_single_lobe);
BENCHMARK(BM_eval_pdf_batch_car_paint_2_layers);
BENCHMARK(BM_eval_pdf_batch_house_paint_3_layers);
BENCHMARK(BM_sample_single_lobe);
BENCHMARK(BM_sample_car_paint_2_layers);
BENCHMARK(BM_sample_house_paint_3_layers);

BENCHMARK(BM_eval_car_paint_2_layers_conserving);
BENCHMARK(BM_eval_house_paint_3_layers_conserving);
BENCHMARK(BM_eval_batch_car_paint_2_layers_conserving);
BENCHMARK(BM_eval_batch_house_paint_3_layers_conserving);
BENCHMARK(BM_eval_pdf_batch_car_paint_2_layers_conserving);
BENCHMARK(BM_eval_pdf_batch_house_paint_3_layers_conserving);
BENCHMARK(BM_sample_car_paint_2_layers_conserving);
BENCHMARK(BM_sample_house_paint_3_layers_conserving);

BENCHMARK_MAIN();
