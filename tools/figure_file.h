// The image file of a figure (`lamina plot`, `lamina compare --plot`): its size and format are
// checked and the fonts found before any work, and the finished image is encoded in memory and
// written by the one writer, complete or absent.
#pragma once

#include <string>

#include "tools/plot_text.h"

namespace lamina::cli {

inline constexpr int kFigureMinSize = 800;
inline constexpr int kFigureMaxSize = 8192;
inline constexpr int kFigureDefaultSize = 1600;

struct FigureFile {
  std::string path;    // as given with `option`
  std::string format;  // the OpenImageIO format its extension names
  int width = kFigureDefaultSize;
  plot::Fonts fonts;
};

// The image format a path's extension names, lower case without the dot ("png", "exr"); "" for none.
std::string image_format(const std::string& path);

// Checks the width (`--size`, the height is half of it) and that `path` names a format OpenImageIO
// writes, and finds the fonts; prints the problem and returns its exit code otherwise.
int prepare_figure(const std::string& option, const std::string& path, int width, FigureFile& figure);

// The canvas to draw on: width x width / 2.
plot::Canvas figure_canvas(const FigureFile& figure);

// Encodes `canvas` (display sRGB) with `description` and writes it; an exit code.
int write_figure(plot::Canvas& canvas, const FigureFile& figure, const std::string& description);

}  // namespace lamina::cli
