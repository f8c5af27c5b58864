// The stack models a material may name in its "model": one list, read by the document reader,
// the schema, the command line and the compiler.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace lamina {

// The model a material gets when it names none.
inline constexpr std::string_view kDefaultModel = "energy_conserving";

// Every model's name, the default first.
const std::vector<std::string>& model_names();

// Program::model (LAMINA_MODEL_* of nodes/kernels/stack.glsl) for a model's name; -1 for any
// other name.
int model_number(std::string_view name);

// The name of a Program::model; empty for a number no model has.
std::string_view model_name(int number);

// One line for the schema and for error messages: each model and what it promises.
std::string model_summary();

}  // namespace lamina
