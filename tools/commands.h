// The lamina command-line tool: each sub-command registers itself on the app and, when chosen,
// leaves a runner that returns the exit code: 0 ok, 1 I/O or internal error, 2 user mistake.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>
#include "graph/file_access.h"
#include "graph/load.h"
#include "graph/scene/scene.h"
#include "tools/output.h"

namespace lamina::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitIo = 1;
inline constexpr int kExitInvalid = 2;

using Runner = std::function<int()>;

void add_validate(CLI::App& app, Runner& runner);
void add_classify(CLI::App& app, Runner& runner);
void add_nodes(CLI::App& app, Runner& runner);
void add_schema(CLI::App& app, Runner& runner);
void add_eval(CLI::App& app, Runner& runner);
void add_albedo(CLI::App& app, Runner& runner);
void add_reference(CLI::App& app, Runner& runner);
void add_compare(CLI::App& app, Runner& runner);
void add_plot(CLI::App& app, Runner& runner);
void add_glsl(CLI::App& app, Runner& runner);
void add_gltf(CLI::App& app, Runner& runner);
void add_import(CLI::App& app, Runner& runner);
void add_render(CLI::App& app, Runner& runner);
void add_preview(CLI::App& app, Runner& runner);

// How the commands that read materials, scenes or glTF files follow the files those name
// (graph/file_access.h): --asset-root DIR (repeatable) and --max-image-pixels N.
struct InputOptions {
  std::vector<std::string> asset_roots;
  std::uint64_t max_image_pixels = kDefaultMaxImagePixels;

  // The policy for the input file `file` (or, for the files found in a directory argument,
  // `directory`): the given roots, or else that folder.
  AssetPolicy policy_for(const std::filesystem::path& file, const std::filesystem::path& directory = {}) const;
};
void add_input_options(CLI::App& cmd, InputOptions& options);

// The files named on a command line, directories expanded into the *.json files under them
// (sorted); files stay as given. A path that does not exist (exit 1) or a directory without any
// .json file (exit 2) is reported on stderr as "lamina: ..." and skipped, so that one wrong
// argument does not hide what the others hold; `code` is the exit code those problems call for.
struct Inputs {
  std::vector<std::filesystem::path> files;
  std::vector<std::filesystem::path> directories;  // per file: the directory argument it was found in, or ""
  int code = kExitOk;
};
Inputs expand_inputs(const std::vector<std::string>& inputs);

// Checks every input file and hands each readable one to `visit`, which returns whether the
// file passed. Returns the exit code: 1 if any input could not be read, else 2 if any file
// failed, else 0. I/O problems are printed as "lamina: ..." lines.
int for_each_checked_file(const std::vector<std::string>& inputs, const InputOptions& options,
                          const std::function<bool(const std::filesystem::path&, CheckedFile&)>& visit);

// Adds --columns: spheres per row of a material file's sample sheet (1 to 64).
void add_sheet_columns_option(CLI::App& cmd, int& columns);

// Reads `input`: a scene file, or a material file as its sample sheet (one sphere per material in
// rows of `columns`, graph/scene/scene.h). Problems go to `diagnostics`, unprinted; an input that
// cannot be read is printed and returns kExitIo. Otherwise kExitOk, whatever the diagnostics say.
int read_scene_input(const std::string& input, const InputOptions& options, int columns, Scene& scene,
                     Diagnostics& diagnostics);

// "lamina: TEXT" on stderr, TEXT passed through printable(): how the commands report problems
// that are not a file's (I/O errors, command-line mistakes, notes).
void print_problem(std::string_view text);

// Prints errors, then warnings, as "file:pointer: message" lines on stderr; returns whether there
// was no error.
bool print_diagnostics(const Diagnostics& diagnostics);

}  // namespace lamina::cli
