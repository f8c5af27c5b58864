// Runs one of the evaluator's queries on a material for a fixed set of random directions (the
// benchmark's, tests/bench/evaluator_bench.cpp), so that callgrind can count the instructions one
// query takes: tools/count_instructions.sh runs it. Counts, unlike times, do not depend on what
// else the machine is doing.
//   lamina_query_driver MATERIAL.json eval|eval_pdf|sample COUNT
// MATERIAL.json's first material is queried in the local frame with the default context.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/load.h"

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
    // The benchmark's generator: directions with cosines from 0.01 up, and uniform numbers.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    auto direction = [&] {
      float z = std::max(uniform(rng), 0.01f), phi = 6.2831853f * uniform(rng);
      float s = std::sqrt(1.0f - z * z);
      return glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
    };
    std::vector<glm::vec3> wi, wo;
    std::vector<glm::vec2> u;
    std::vector<float> u_lobe;
    for (long i = 0; i < count; ++i) {
      wi.push_back(direction());
      wo.push_back(direction());
      u.emplace_back(uniform(rng), uniform(rng));
      u_lobe.push_back(uniform(rng));
    }
    const lamina::ShadingContext ctx;
    double sum = 0.0;  // printed, so that no query can be optimised away
    for (long i = 0; i < count; ++i) {
      if (query == "eval") sum += double(evaluator.eval(ctx, wi[size_t(i)], wo[size_t(i)]).x);
      if (query == "eval_pdf") sum += double(evaluator.eval_pdf(ctx, wi[size_t(i)], wo[size_t(i)]).pdf);
      if (query == "sample") sum += double(evaluator.sample(ctx, wo[size_t(i)], u[size_t(i)], u_lobe[size_t(i)]).pdf);
    }
    std::printf("%.9g\n", sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lamina_query_driver: %s\n", e.what());
    return 1;
  }
  return 0;
}
