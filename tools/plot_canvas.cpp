#include "tools/plot_canvas.h"

#include <algorithm>
#include <cmath>

#include "graph/file_access.h"

namespace lamina::cli::plot {

namespace {

// Anti-aliased coverage of a polyline of the given width, clipped to `clip`; the maximum over
// segments, so joints are not counted twice.
void cover_polyline(std::vector<float>& coverage, int width, const std::vector<glm::vec2>& points, float line_width,
                    Rect clip) {
  float half = 0.5f * line_width;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    glm::vec2 a = points[i], b = points[i + 1];
    int x0 = std::max(clip.x0, int(std::floor(std::min(a.x, b.x) - half - 1.0f)));
    int x1 = std::min(clip.x1, int(std::ceil(std::max(a.x, b.x) + half + 1.0f)));
    int y0 = std::max(clip.y0, int(std::floor(std::min(a.y, b.y) - half - 1.0f)));
    int y1 = std::min(clip.y1, int(std::ceil(std::max(a.y, b.y) + half + 1.0f)));
    glm::vec2 ab = b - a;
    float length_squared = glm::dot(ab, ab);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
        float t = length_squared > 0.0f ? std::clamp(glm::dot(p - a, ab) / length_squared, 0.0f, 1.0f) : 0.0f;
        float d = glm::length(p - (a + t * ab));
        float c = std::clamp(half + 0.5f - d, 0.0f, 1.0f);
        float& cell = coverage[size_t(y) * size_t(width) + size_t(x)];
        cell = std::max(cell, c);
      }
  }
}

}  // namespace

void Canvas::fill(Rect r, glm::vec3 c) {
  for (int y = std::max(r.y0, 0); y < std::min(r.y1, h_); ++y)
    for (int x = std::max(r.x0, 0); x < std::min(r.x1, w_); ++x) at(x, y) = c;
}

void Canvas::add_polyline(const std::vector<glm::vec2>& points, float line_width, Rect clip, glm::vec3 colour) {
  clip = {std::max(clip.x0, 0), std::max(clip.y0, 0), std::min(clip.x1, w_), std::min(clip.y1, h_)};
  std::vector<float> coverage(size_t(w_) * size_t(h_), 0.0f);
  cover_polyline(coverage, w_, points, line_width, clip);
  for (int y = clip.y0; y < clip.y1; ++y)
    for (int x = clip.x0; x < clip.x1; ++x) {
      float cov = coverage[size_t(y) * size_t(w_) + size_t(x)];
      if (cov > 0.0f) at(x, y) = glm::min(at(x, y) + cov * colour, glm::vec3(1.0f));
    }
}

std::string encode_image(Canvas& canvas, const std::string& format,
                         const std::vector<std::pair<std::string, std::string>>& metadata,
                         std::vector<unsigned char>& encoded) {
  try {
    return image_codec().encode(format, canvas.view(), metadata, encoded);
  } catch (const IoError& e) {
    return e.what();
  }
}

}  // namespace lamina::cli::plot
