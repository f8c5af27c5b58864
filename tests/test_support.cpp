#include "test_support.h"

#include <sys/wait.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace lamina::test {

std::filesystem::path source_dir() { return LAMINA_SOURCE_DIR; }

AssetPolicy repository_policy() {
  AssetPolicy policy;
  policy.roots.push_back(source_dir());
  return policy;
}

std::vector<std::filesystem::path> example_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(source_dir() / "examples" / "materials"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::filesystem::path> swept_example_files(int offset) {
  std::vector<std::filesystem::path> files = example_files();
#ifdef LAMINA_SANITIZED
  std::vector<std::filesystem::path> every_second;
  for (size_t i = size_t(offset); i < files.size(); i += 2) every_second.push_back(files[i]);
  files = std::move(every_second);
#else
  (void)offset;
#endif
  return files;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> listing(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    names.push_back(std::filesystem::relative(e.path(), dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string select_of_layers(int stacks) {
  nlohmann::json select = {{"id", "map"}, {"type", "select"}, {"index", "@cells.value"}};
  nlohmann::json nodes = nlohmann::json::array(
      {{{"id", "cells"}, {"type", "texture/voronoi"}, {"scale", 30.0}},
       {{"id", "varnish"}, {"type", "interface/dielectric"}, {"ior", 1.5}, {"roughness_deg", 4.0}}});
  for (int k = 0; k < stacks; ++k) {
    const std::string n = std::to_string(k);
    select["stack_" + n] = "@coat_" + n;
    nodes.push_back({{"id", "coat_" + n}, {"type", "layer"}, {"interface", "@varnish"}, {"base", "@base_" + n}});
    nodes.push_back({{"id", "base_" + n}, {"type", "substrate/lambert"}, {"albedo", {0.5, 0.04 * k, 0.3}}});
  }
  nodes.push_back(select);
  return nlohmann::json{{"format", 1}, {"materials", {{{"name", "tiles"}, {"surface", "@map"}, {"nodes", nodes}}}}}
      .dump();
}

std::string chain_of_layers(int layers) {
  nlohmann::json nodes = nlohmann::json::array(
      {{{"id", "varnish"}, {"type", "interface/dielectric"}, {"ior", 1.5}, {"roughness_deg", 4.0}},
       {{"id", "base"}, {"type", "substrate/lambert"}, {"albedo", {0.5, 0.4, 0.3}}}});
  for (int k = 0; k < layers; ++k)
    nodes.push_back({{"id", "coat_" + std::to_string(k)},
                     {"type", "layer"},
                     {"interface", "@varnish"},
                     {"base", k + 1 < layers ? "@coat_" + std::to_string(k + 1) : std::string("@base")}});
  return nlohmann::json{{"format", 1}, {"materials", {{{"name", "coats"}, {"surface", "@coat_0"}, {"nodes", nodes}}}}}
      .dump();
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("lamina_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

namespace {

RunResult run(const std::string& prefix, const std::string& args, const std::filesystem::path& working_dir,
              const std::string& stdout_to = {}) {
  TempDir capture;
  auto out = capture.path() / "out.txt";
  auto err = capture.path() / "err.txt";
  std::string command;
  if (!working_dir.empty()) command = "cd '" + working_dir.string() + "' && ";
  command += prefix + "'" + LAMINA_CLI + "' " + args + " >'" + (stdout_to.empty() ? out.string() : stdout_to) +
             "' 2>'" + err.string() + "'";
  int status = std::system(command.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (stdout_to.empty()) r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

}  // namespace

RunResult run_cli(const std::string& args, const std::filesystem::path& working_dir) {
  return run("", args, working_dir);
}

RunResult run_cli_within(int seconds, const std::string& args, const std::filesystem::path& working_dir) {
  return run("timeout --kill-after=5 " + std::to_string(seconds) + " ", args, working_dir);
}

RunResult run_cli_wrapped(const std::string& wrapper, const std::string& args, const std::filesystem::path& working_dir,
                          const std::string& stdout_to) {
  return run(wrapper + " ", args, working_dir, stdout_to);
}

}  // namespace lamina::test
