#include "tools/plot_text.h"

#include <filesystem>

namespace lamina::cli::plot {

namespace {

namespace fs = std::filesystem;

std::string find_font(bool bold) {
  const char* file = bold ? "DejaVuSans-Bold.ttf" : "DejaVuSans.ttf";
  const char* dirs[] = {"/usr/share/fonts/truetype/dejavu",
                        "/usr/share/fonts/TTF",
                        "/usr/share/fonts/dejavu",
                        "/usr/share/fonts/dejavu-sans-fonts",
                        "/usr/share/fonts/truetype",
                        "/usr/local/share/fonts",
                        "/Library/Fonts"};
  for (const char* dir : dirs) {
    fs::path path = fs::path(dir) / file;
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) return path.string();
  }
  return {};
}

}  // namespace

Fonts find_fonts() {
  Fonts fonts{find_font(false), find_font(true)};
  if (fonts.regular.empty()) fonts.regular = "DejaVuSans";  // let OpenImageIO search its font path
  if (fonts.bold.empty()) fonts.bold = fonts.regular;
  return fonts;
}

bool fonts_usable(const Fonts& fonts) { return image_codec().text_box("lamina", 16, fonts.regular).has_value(); }

int Text::width(const std::string& text, int size, bool bold) const {
  const std::optional<TextBox> box = image_codec().text_box(text, size, bold ? fonts_.bold : fonts_.regular);
  return box ? box->x1 - box->x0 : 0;
}

int Text::fit(const std::string& text, int size, int max_width, bool bold) const {
  while (size > 7 && width(text, size, bold) > max_width) --size;
  return size;
}

void Text::draw(int x, int y, const std::string& text, int size, glm::vec3 colour, int align, bool bold,
                int max_width) {
  if (max_width > 0) size = fit(text, size, max_width, bold);
  float c[3] = {colour.r, colour.g, colour.b};
  const std::string why =
      image_codec().draw_text(canvas_.view(), x, y, text, size, bold ? fonts_.bold : fonts_.regular, c, align);
  if (error_.empty() && !why.empty()) error_ = "'" + text + "': " + why;
}

}  // namespace lamina::cli::plot
