// Cost of the layered evaluation against a single Torrance-Sparrow conductor lobe, in one run.
// Run: bash tools/run_bench.sh (prints the ratios), or build/release/tests/bench/lamina_bench.
#include <benchmark/benchmark.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/load.h"
#include "queries.h"

namespace {

constexpr size_t kQueries = 4096;

// One Torrance-Sparrow lobe: the Car Paint's aluminium base without its varnish.
const char* kSingleLobe = R"({"format": 1, "materials": [{"name": "single_lobe", "surface": "@metal", "nodes": [
    {"id": "metal", "type": "substrate/conductor", "metal": "aluminium", "roughness_deg": 12.0}]}]})";

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

}  // namespace

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
