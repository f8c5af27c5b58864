// What the evaluating commands (eval, albedo, plot) share: the FILE and --material arguments, a
// checked and compiled material's CPU evaluator, and "X,Y,Z" number lists on the command line.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "tools/commands.h"

namespace lamina::cli {

struct MaterialArg {
  std::string file;
  std::string material;  // empty: the file's only material
  std::string model;     // --model: evaluate in this model instead of each material's own
  InputOptions input_options;
};

// Adds the positional FILE (required), --material NAME, --model NAME and the input options to
// `cmd`.
void add_material_options(CLI::App& cmd, MaterialArg& arg);
// Adds only --model NAME (for commands that name their materials their own way).
void add_model_option(CLI::App& cmd, MaterialArg& arg);

// Reads and checks the file, finds the material, compiles it and builds its evaluator. On failure
// prints the problem on stderr and returns the exit code, else returns kExitOk with `out` set:
//   kExitInvalid  the file is invalid (its diagnostics, as `lamina validate` prints them), the
//                 material name is unknown or missing from a file with several (the names are
//                 listed), or the material is too large for the CPU evaluator;
//   kExitIo       the file or one of its textures cannot be read.
int load_material(const MaterialArg& arg, std::optional<cpu::Evaluator>& out);

// As load_material, but compiles to Programs: the named material, the only one, or with
// `all_when_unnamed` every material of the file when no name is given. `indices`, when given,
// receives each program's material index in the file.
int load_programs(const MaterialArg& arg, bool all_when_unnamed, std::vector<Program>& out,
                  std::vector<size_t>* indices = nullptr);

// Parses `count` comma-separated finite numbers ("0.3,0,1"; spaces around them are allowed).
// On a mistake prints "lamina: OPTION: ..." on stderr and returns nothing.
// `form` is what the message asks for ("R,G,B, e.g. 0,1,0"); empty: the form of a uv, a direction or
// a list of `count` numbers.
std::optional<std::vector<float>> parse_numbers(std::string_view option, std::string_view text, size_t count,
                                                std::string_view form = {});

// A direction from "X,Y,Z", normalised; a zero vector is a mistake (printed, nothing returned).
std::optional<glm::vec3> parse_direction(std::string_view option, std::string_view text);

// The shading point of --uv, --position and --footprint (textures read it; an untextured material
// is the same everywhere). The defaults: uv (0, 0), position (0, 0, 0), a point sample.
struct ContextArg {
  std::string uv = "0,0";
  std::string position = "0,0,0";
  double footprint = 0.0;
};

// Adds --uv, --position and --footprint to a command that evaluates at one shading point.
void add_context_options(CLI::App& cmd, ContextArg& arg);

// The shading context of those options; on a mistake prints it and returns nothing.
std::optional<ShadingContext> parse_context(const ContextArg& arg);

// The view direction theta degrees off the normal, (sin theta, 0, cos theta), for --theta in
// [0, 90); otherwise prints the mistake and returns nothing.
std::optional<glm::vec3> parse_view_angle(double theta_deg);

// For the commands that run the reference solver (reference, compare): kExitOk when the bound
// point's stack has no tilted entry, else prints which node's normal input tilts it (the solver
// walks flat boundaries only, graph/cpu/reference.h) and returns kExitInvalid.
int refuse_tilted(const MaterialArg& arg, const cpu::Evaluator& evaluator, const cpu::ShadingPoint& point);

}  // namespace lamina::cli
