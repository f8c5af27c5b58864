#pragma once

#include <string>

namespace lamina {

// Shortest text that reads back to the same double ("1.5", "0.1", "1e-07"); always has a '.'
// or an exponent so that a float stays a float in JSON.
std::string number_text(double value);

}  // namespace lamina
