// What the doctest programs that draw example materials share (they define LAMINA_SOURCE_DIR).
#pragma once

#include <doctest/doctest.h>

#include <memory>
#include <string>

#include "glsl/gl_runner.h"
#include "graph/compile.h"
#include "graph/load.h"
#include "graph/program.h"

namespace lamina::test {

// The program of examples/materials/`name` (a file of one material).
inline Program example_program(const std::string& name) {
  std::string file = std::string(LAMINA_SOURCE_DIR) + "/examples/materials/" + name;
  CheckedFile checked = check_file(file);
  REQUIRE(checked.ok());
  REQUIRE(checked.graphs.size() == 1);
  return compile(*checked.graphs[0], file);
}

// One runner per API for the whole test program: a context is made once.
inline gltest::Runner& shared_runner(gltest::Api api) {
  static std::unique_ptr<gltest::Runner> desktop, es;
  std::unique_ptr<gltest::Runner>& r = api == gltest::Api::Es ? es : desktop;
  if (!r) {
    std::string error;
    r = gltest::Runner::create(api, &error);
    INFO(error);
    REQUIRE(r);
  }
  return *r;
}

}  // namespace lamina::test
