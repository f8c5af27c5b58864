// Paths and helpers shared by the test suites.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "graph/file_access.h"

namespace lamina::test {

std::filesystem::path source_dir();
// The policy under which test files reach across the repository (tests/data/scenes name
// examples/materials): the repository is the one asset root.
AssetPolicy repository_policy();
std::vector<std::filesystem::path> example_files();  // examples/materials/*.json, sorted
// The examples a sweep over every example visits: all of them, or under the sanitisers (which look
// for memory errors, 3-5x slower) every second one from `offset` (0 or 1), so that two sweeps with
// different offsets cover every example between them while the optimised build runs each in full.
std::vector<std::filesystem::path> swept_example_files(int offset);
std::string read_file(const std::filesystem::path& path);

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};
// Runs the lamina CLI with `args` (already shell-quoted where needed) in `working_dir`.
RunResult run_cli(const std::string& args, const std::filesystem::path& working_dir = {});
// As run_cli, killed after `seconds` (exit code 124 then): for inputs that once made lamina hang.
RunResult run_cli_within(int seconds, const std::string& args, const std::filesystem::path& working_dir = {});
// As run_cli, the CLI started by `wrapper` (a command such as "prlimit --fsize=4096"), and the
// standard output redirected to `stdout_to` instead of captured when it is not empty.
RunResult run_cli_wrapped(const std::string& wrapper, const std::string& args, const std::filesystem::path& working_dir,
                          const std::string& stdout_to = {});

// Every file and directory under `dir`, as paths relative to it, sorted.
std::vector<std::string> listing(const std::filesystem::path& dir);

// A material file's text: one material "tiles" whose surface is a select of `stacks` distinct
// layered stacks (a varnish over a Lambertian colour each) by Voronoi cells, which compiles to
// 3 stacks - 1 entries (2 per stack and a chain of stacks - 1 mixes).
std::string select_of_layers(int stacks);
// A material file whose one stack is `layers` varnish layers over a Lambertian base (layers + 1
// entries, one part).
std::string chain_of_layers(int layers);

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace lamina::test
