// Runs one of the evaluator's queries on a material for a fixed set of random directions (the
// benchmark's, tests/bench/evaluator_bench.cpp), so that callgrind can count the instructions one
// query takes: tools/count_instructions.sh runs it. Counts, unlike times, do not depend on what
// else the machine is doing.
//   lamina_query_driver MATERIAL.json eval|eval_pdf|sample COUNT
// MATERIAL.json's first material is queried in the local frame with the default context.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/load.h"
#include "queries.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: lamina_query_driver MATERIAL.json eval|eval_pdf|sample COUNT\n");
    return 2;
  }
  const std::string query = argv[2];
  const long count = std::strtol(argv[3], nullptr, 10);
  if ((query != "eval" && query != "eval_pdf" && query != "sample") || count <= 0) {
    std::fprintf(stderr, "lamina_query_driver: unknown query '%s' or count '%s'\n", argv[2], argv[3]);
    return 2;
  }
  try {
    const lamina::Document document = lamina::load(argv[1]);
    const lamina::cpu::Evaluator evaluator(lamina::compile(document, document.materials.at(0).name));
    const lamina::bench::Queries q{size_t(count)};
    const lamina::ShadingContext ctx;
    double sum = 0.0;  // printed, so that no query can be optimised away
    for (long i = 0; i < count; ++i) {
      const size_t at = size_t(i);
      if (query == "eval") sum += double(evaluator.eval(ctx, q.wi[at], q.wo[at]).x);
      if (query == "eval_pdf") sum += double(evaluator.eval_pdf(ctx, q.wi[at], q.wo[at]).pdf);
      if (query == "sample") sum += double(evaluator.sample(ctx, q.wo[at], q.u[at], q.u_lobe[at]).pdf);
    }
    std::printf("%.9g\n", sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lamina_query_driver: %s\n", e.what());
    return 1;
  }
  return 0;
}
