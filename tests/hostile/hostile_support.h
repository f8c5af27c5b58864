// What the hostile-input suites share: running a command in a folder while watching the folder.
#pragma once

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace lamina::test {

// `bytes` as the whole content of `path`.
inline void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

struct Outcome {
  RunResult run;
  std::vector<std::string> before, after;  // the folder's listing around the run
};

// Runs the CLI in `dir`, killed after `seconds` (hostile inputs once made lamina hang).
inline Outcome run_in(const std::filesystem::path& dir, const std::string& args, int seconds = 60) {
  Outcome o;
  o.before = listing(dir);
  o.run = run_cli_within(seconds, args, dir);
  o.after = listing(dir);
  return o;
}

// A user mistake: exit 2, the message names `where` and says `message`, and nothing was written
// (no output, no temporary, no scratch folder left).
inline void expect_refused(const Outcome& o, const std::string& where, const std::string& message) {
  INFO(o.run.err);
  CHECK(o.run.exit_code == 2);
  CHECK(o.run.err.find(where) != std::string::npos);
  CHECK(o.run.err.find(message) != std::string::npos);
  CHECK(o.before == o.after);
}

}  // namespace lamina::test
