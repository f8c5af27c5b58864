// The lamina command-line tool: each sub-command registers itself on the app and, when chosen,
// leaves a runner that returns the exit code: 0 ok, 1 I/O or internal error, 2 user mistake.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lamina::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitIo = 1;
inline constexpr int kExitInvalid = 2;

using Runner = std::function<int()>;

void add_validate(CLI::App& app, Runner& runner);
void add_classify(CLI::App& app, Runner& runner);
void add_nodes(CLI::App& app, Runner& runner);
void add_schema(CLI::App& app, Runner& runner);

// Expands directories into the *.json files under them (sorted); files stay as given.
// Throws IoError for a path that does not exist.
std::vector<std::filesystem::path> expand_inputs(const std::vector<std::string>& inputs);

}  // namespace lamina::cli
