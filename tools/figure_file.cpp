#include "tools/figure_file.h"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "graph/file_access.h"
#include "graph/image_codec.h"
#include "tools/commands.h"
#include "tools/plot_canvas.h"

namespace lamina::cli {

std::string image_format(const std::string& path) {
  std::string format = std::filesystem::path(path).extension().string();
  if (!format.empty()) format.erase(0, 1);
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return format;
}

int prepare_figure(const std::string& option, const std::string& path, int width, FigureFile& figure) {
  if (width < kFigureMinSize || width > kFigureMaxSize) {
    std::cerr << "lamina: --size: " << width << " is outside [" << kFigureMinSize << ", " << kFigureMaxSize
              << "] (the width in pixels; the height is half of it)\n";
    return kExitInvalid;
  }
  const std::string format = image_format(path);
  try {
    if (format.empty() || !image_codec().writes(format)) {
      print_problem(option + ": cannot tell an image format from '" + path + "' (name the file e.g. plot.png)");
      return kExitInvalid;
    }
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  }
  figure.fonts = plot::find_fonts();
  if (!plot::fonts_usable(figure.fonts)) {
    std::cerr << "lamina: no font for the labels: DejaVuSans.ttf was not found (on Debian: apt-get install "
                 "fonts-dejavu-core)\n";
    return kExitIo;
  }
  figure.path = path;
  figure.format = format;
  figure.width = width;
  return kExitOk;
}

plot::Canvas figure_canvas(const FigureFile& figure) {
  return plot::Canvas(figure.width, figure.width / 2, glm::vec3(0.0f));
}

int write_figure(plot::Canvas& canvas, const FigureFile& figure, const std::string& description) {
  // Encoded in memory, then written by the one writer: complete or absent, never over an input.
  std::vector<unsigned char> encoded;
  const std::string why = plot::encode_image(canvas, figure.format,
                                             {{"oiio:ColorSpace", "sRGB"}, {"ImageDescription", description}}, encoded);
  if (!why.empty()) {
    print_problem("cannot encode " + figure.path + ": " + why);
    return kExitIo;
  }
  return write_outputs({{figure.path, std::string(encoded.begin(), encoded.end())}});
}

}  // namespace lamina::cli
