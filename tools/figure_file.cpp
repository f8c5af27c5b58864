#include "tools/figure_file.h"

#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "tools/commands.h"
#include "tools/plot_canvas.h"

namespace lamina::cli {

int prepare_figure(const std::string& option, const std::string& path, int width, FigureFile& figure) {
  if (width < kFigureMinSize || width > kFigureMaxSize) {
    std::cerr << "lamina: --size: " << width << " is outside [" << kFigureMinSize << ", " << kFigureMaxSize
              << "] (the width in pixels; the height is half of it)\n";
    return kExitInvalid;
  }
  std::string format = std::filesystem::path(path).extension().string();
  if (!format.empty()) format.erase(0, 1);
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (format.empty() || !OIIO::ImageOutput::create(format)) {
    print_problem(option + ": cannot tell an image format from '" + path + "' (name the file e.g. plot.png)");
    return kExitInvalid;
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

OIIO::ImageBuf figure_image(const FigureFile& figure) {
  return OIIO::ImageBuf(OIIO::ImageSpec(figure.width, figure.width / 2, 3, OIIO::TypeDesc::FLOAT));
}

int write_figure(OIIO::ImageBuf& image, const FigureFile& figure, const std::string& description) {
  image.specmod().attribute("oiio:ColorSpace", "sRGB");
  image.specmod().attribute("ImageDescription", description);
  // Encoded in memory, then written by the one writer: complete or absent, never over an input.
  std::vector<unsigned char> encoded;
  if (!plot::encode_image(image, figure.format, encoded)) {
    print_problem("cannot encode " + figure.path + ": " + image.geterror());
    return kExitIo;
  }
  return write_outputs({{figure.path, std::string(encoded.begin(), encoded.end())}});
}

}  // namespace lamina::cli
