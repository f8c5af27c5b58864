// The course's material taxonomy (Weidlich and Wilkie, ch. 4, fig. 4.3/4.4): classes a) to h)
// from a stack's structure.
#pragma once

#include <string>
#include <vector>

#include "graph/graph.h"

namespace lamina {

// A top or base is smooth when its RMS slope angle is below this. The course's smooth tops run
// 0.01-4 degrees and its rough ones start at 5 (class a vs c); its smooth metal bases go up to
// 4 degrees (Brass, class d) and its rough ones start at 10 (Silver Paint, class g).
inline constexpr double kSmoothBelowDeg = 5.0;
// A medium is tinted when its round trip at normal incidence, exp(-2 a d), absorbs more than 1%
// in some channel; Red Lacquer absorbs 91% of green, the clear course examples nothing.
inline constexpr double kTintedAbsorbs = 0.01;

struct Classification {
  std::string letter;                 // "a".."h"; "" for a bare substrate or a mix of two classes
  std::string name;                   // "metallic paint", "mix of b) and e)", "unlayered substrate"
  std::string reason;                 // the decision, with the numbers it used
  std::vector<std::string> accepted;  // class tags that agree with the structure
};

Classification classify(const Graph& graph);
std::string class_name(const std::string& letter);

}  // namespace lamina
