// lamina plot FILE --material NAME -o OUT.png: a picture of a material for people. Four in-plane
// BRDF slices (log10 f per channel against the light's angle, for views at 0, 30, 60 and 80
// degrees, at one uv) beside a sphere lit by one directional light and a dim uniform sky.
// Deterministic for the same input.
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "graph/cpu/frame.h"
#include "nodes/kernels/kernels.h"
#include "tools/commands.h"
#include "tools/material_arg.h"

namespace lamina::cli {

namespace {

namespace fs = std::filesystem;
using glm::vec2;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;
constexpr int kMinSize = 800;
constexpr int kMaxSize = 8192;
constexpr int kDefaultSize = 1600;

// The uniform sky around the sphere, as a radiance: a white Lambertian surface shows this much on
// top of the light. Without it a smooth metal is black wherever it does not mirror the light.
constexpr float kDefaultAmbient = 0.15f;
constexpr float kMaxAmbient = 10.0f;
// The sky's reflection, Evaluator::albedo: for an untextured material, which is isotropic, a table
// over cos(theta_o) of this many intervals, with this many points per lobe...
constexpr int kSkyTableSize = 256;
constexpr int kSkyTablePoints = 256;
// ... and for a textured one once per pixel, with this many.
constexpr int kSkyPixelPoints = 16;

struct PlotOptions {
  MaterialArg material;
  std::string output;
  int size = kDefaultSize;
  std::string uv = "0,0";
  float ambient = kDefaultAmbient;
};

// --- colours (display-referred sRGB values, as written to the file) ------------------------------

const vec3 kFigureBackground(0.105f, 0.108f, 0.118f);
const vec3 kPlotBackground(0.028f, 0.029f, 0.034f);
const vec3 kSphereBackground(0.24f, 0.245f, 0.26f);  // mid grey, so that the unlit side shows its outline
const vec3 kGrid(0.19f, 0.195f, 0.215f);
const vec3 kFrame(0.42f, 0.43f, 0.46f);
const vec3 kMirror(0.62f, 0.62f, 0.66f);
const vec3 kText(0.9f, 0.9f, 0.92f);
const vec3 kTextDim(0.62f, 0.63f, 0.67f);
// The channel curves add up, so where they coincide red + green + blue is white and red + green
// is yellow; blue and red are lifted a little so that they read on the dark background.
const std::array<vec3, 3> kChannel = {vec3(1.0f, 0.12f, 0.08f), vec3(0.0f, 0.95f, 0.0f), vec3(0.12f, 0.3f, 1.0f)};

// --- a float RGB canvas with the few primitives the figure needs ----------------------------------

struct Rect {
  int x0, y0, x1, y1;  // half-open
};

class Canvas {
 public:
  Canvas(int width, int height, vec3 fill) : w_(width), h_(height), rgb_(size_t(width) * size_t(height), fill) {}
  int width() const { return w_; }
  int height() const { return h_; }
  vec3& at(int x, int y) { return rgb_[size_t(y) * size_t(w_) + size_t(x)]; }
  const std::vector<vec3>& pixels() const { return rgb_; }

  void fill(Rect r, vec3 c) {
    for (int y = std::max(r.y0, 0); y < std::min(r.y1, h_); ++y)
      for (int x = std::max(r.x0, 0); x < std::min(r.x1, w_); ++x) at(x, y) = c;
  }

 private:
  int w_, h_;
  std::vector<vec3> rgb_;
};

// Anti-aliased coverage of a polyline of the given width, clipped to `clip`; the maximum over
// segments, so joints are not counted twice.
void cover_polyline(std::vector<float>& coverage, int width, const std::vector<vec2>& points, float line_width,
                    Rect clip) {
  float half = 0.5f * line_width;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    vec2 a = points[i], b = points[i + 1];
    int x0 = std::max(clip.x0, int(std::floor(std::min(a.x, b.x) - half - 1.0f)));
    int x1 = std::min(clip.x1, int(std::ceil(std::max(a.x, b.x) + half + 1.0f)));
    int y0 = std::max(clip.y0, int(std::floor(std::min(a.y, b.y) - half - 1.0f)));
    int y1 = std::min(clip.y1, int(std::ceil(std::max(a.y, b.y) + half + 1.0f)));
    vec2 ab = b - a;
    float length_squared = glm::dot(ab, ab);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        vec2 p(float(x) + 0.5f, float(y) + 0.5f);
        float t = length_squared > 0.0f ? std::clamp(glm::dot(p - a, ab) / length_squared, 0.0f, 1.0f) : 0.0f;
        float d = glm::length(p - (a + t * ab));
        float c = std::clamp(half + 0.5f - d, 0.0f, 1.0f);
        float& cell = coverage[size_t(y) * size_t(width) + size_t(x)];
        cell = std::max(cell, c);
      }
  }
}

// --- text through OpenImageIO's FreeType renderer ----------------------------------------------------

// DejaVu (Debian: fonts-dejavu-core) where the common systems keep it.
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

struct Fonts {
  std::string regular, bold;
};

class Text {
 public:
  Text(OIIO::ImageBuf& image, const Fonts& fonts) : image_(image), fonts_(fonts) {}

  int width(const std::string& text, int size, bool bold = false) const {
    OIIO::ROI roi = OIIO::ImageBufAlgo::text_size(text, size, bold ? fonts_.bold : fonts_.regular);
    return roi.defined() ? roi.xend - roi.xbegin : 0;
  }

  // The largest size up to `size` at which `text` is at most `max_width` wide (never below 7).
  int fit(const std::string& text, int size, int max_width, bool bold = false) const {
    while (size > 7 && width(text, size, bold) > max_width) --size;
    return size;
  }

  // Draws `text` with its baseline at y; align < 0 left, 0 centre, > 0 right of x. With
  // max_width > 0 the size shrinks until the text fits.
  void draw(int x, int y, const std::string& text, int size, vec3 colour, int align = -1, bool bold = false,
            int max_width = 0) {
    if (max_width > 0) size = fit(text, size, max_width, bold);
    float c[3] = {colour.r, colour.g, colour.b};
    auto alignx = align < 0    ? OIIO::ImageBufAlgo::TextAlignX::Left
                  : align == 0 ? OIIO::ImageBufAlgo::TextAlignX::Center
                               : OIIO::ImageBufAlgo::TextAlignX::Right;
    if (!OIIO::ImageBufAlgo::render_text(image_, x, y, text, size, bold ? fonts_.bold : fonts_.regular, c, alignx,
                                         OIIO::ImageBufAlgo::TextAlignY::Baseline))
      ok_ = false;
  }
  bool ok() const { return ok_; }

 private:
  OIIO::ImageBuf& image_;
  const Fonts& fonts_;
  bool ok_ = true;
};

// --- the figure ------------------------------------------------------------------------------------

constexpr std::array<float, 4> kViewAngles = {0.0f, 30.0f, 60.0f, 80.0f};
constexpr float kThetaLimit = 89.5f;  // the slices stop short of grazing, where f is 0
constexpr float kThetaStep = 0.25f;   // lands exactly on every view angle's mirror direction

struct Slice {
  float theta_o_deg;
  std::vector<float> theta_i_deg;
  std::vector<vec3> f;
};

// Light directions in the plane of incidence (x, z): theta_i > 0 on the mirror side of the view.
std::vector<Slice> compute_slices(const cpu::Evaluator& evaluator, vec2 uv) {
  std::vector<Slice> slices;
  int count = int(std::lround(2.0f * kThetaLimit / kThetaStep)) + 1;
  for (float theta_o : kViewAngles) {
    Slice s{theta_o, {}, {}};
    double o = double(theta_o) * kPi / 180.0;
    vec3 wo(float(std::sin(o)), 0.0f, float(std::cos(o)));
    std::vector<vec3> wi, wos(size_t(count), wo);
    std::vector<vec2> uvs(size_t(count), uv);
    for (int k = 0; k < count; ++k) {
      float theta_i = -kThetaLimit + kThetaStep * float(k);
      double t = double(theta_i) * kPi / 180.0;
      s.theta_i_deg.push_back(theta_i);
      wi.push_back(vec3(float(-std::sin(t)), 0.0f, float(std::cos(t))));
    }
    s.f.resize(size_t(count));
    evaluator.eval(wi, wos, uvs, s.f);
    slices.push_back(std::move(s));
  }
  return slices;
}

struct Decades {
  int low, high;  // the y axis shows log10 f from low to high
};

Decades value_range(const std::vector<Slice>& slices) {
  float largest = 0.0f, smallest = std::numeric_limits<float>::infinity();
  for (const Slice& s : slices)
    for (size_t k = 0; k < s.f.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        float v = s.f[k][c];
        if (!std::isfinite(v) || v <= 0.0f) continue;
        largest = std::max(largest, v);
        if (std::abs(s.theta_i_deg[k]) <= 80.0f) smallest = std::min(smallest, v);
      }
  if (largest <= 0.0f) return {-3, 0};
  int high = int(std::ceil(std::log10(largest) + 0.02f));
  int low = std::isfinite(smallest) ? int(std::floor(std::log10(smallest) - 0.02f)) : high - 3;
  low = std::clamp(low, high - 6, high - 2);
  return {low, high};
}

struct Layout {
  double s;  // scale against the 1600-pixel design
  int px(double v) const { return int(std::lround(v * s)); }
  int font(double design_size) const { return std::max(8, px(design_size)); }
};

// Where one slice panel draws: its plot area and the mapping of (theta_i, log10 f) into it.
struct SliceGeometry {
  Rect cell, plot;
  Decades range;

  SliceGeometry(const Layout& l, Rect cell_, Decades range_)
      : cell(cell_),
        plot{cell_.x0 + l.px(66), cell_.y0 + l.px(40), cell_.x1 - l.px(22), cell_.y1 - l.px(56)},
        range(range_) {}
  float x_of(float theta_deg) const { return float(plot.x0) + (theta_deg + 90.0f) / 180.0f * float(plot.x1 - plot.x0); }
  float y_of(float decade) const {
    float t = (decade - float(range.low)) / float(range.high - range.low);
    return float(plot.y1) - std::clamp(t, 0.0f, 1.0f) * float(plot.y1 - plot.y0);
  }
};

constexpr int kGridStepDeg = 30;

void draw_slice_pixels(Canvas& canvas, const Layout& l, const Slice& slice, const SliceGeometry& g) {
  const Rect& plot = g.plot;
  canvas.fill(plot, kPlotBackground);
  int line = std::max(1, l.px(1.0));
  // Grid: every 30 degrees and every decade.
  for (int theta = -90; theta <= 90; theta += kGridStepDeg) {
    int x = std::min(int(g.x_of(float(theta))), plot.x1 - line);
    canvas.fill({x, plot.y0, x + line, plot.y1}, kGrid);
  }
  for (int d = g.range.low; d <= g.range.high; ++d) {
    int y = std::min(int(g.y_of(float(d))), plot.y1 - line);
    canvas.fill({plot.x0, y, plot.x1, y + line}, kGrid);
  }
  // The mirror direction, dashed.
  int mirror = std::min(int(g.x_of(slice.theta_o_deg)), plot.x1 - line);
  for (int y = plot.y0; y < plot.y1; y += l.px(12))
    canvas.fill({mirror, y, mirror + line, std::min(y + l.px(6), plot.y1)}, kMirror);
  // The curves, added channel by channel; f = 0 sits on the bottom edge.
  for (int c = 0; c < 3; ++c) {
    std::vector<vec2> points;
    for (size_t k = 0; k < slice.f.size(); ++k) {
      float v = slice.f[k][c];
      float decade = (std::isfinite(v) && v > 0.0f) ? std::log10(v) : float(g.range.low);
      points.push_back(vec2(g.x_of(slice.theta_i_deg[k]), g.y_of(decade)));
    }
    std::vector<float> coverage(size_t(canvas.width()) * size_t(canvas.height()), 0.0f);
    cover_polyline(coverage, canvas.width(), points, float(std::max(1.6, 2.2 * l.s)), plot);
    for (int y = plot.y0; y < plot.y1; ++y)
      for (int x = plot.x0; x < plot.x1; ++x) {
        float cov = coverage[size_t(y) * size_t(canvas.width()) + size_t(x)];
        if (cov > 0.0f) canvas.at(x, y) = glm::min(canvas.at(x, y) + cov * kChannel[size_t(c)], vec3(1.0f));
      }
  }
  // Frame.
  canvas.fill({plot.x0, plot.y0, plot.x1, plot.y0 + line}, kFrame);
  canvas.fill({plot.x0, plot.y1 - line, plot.x1, plot.y1}, kFrame);
  canvas.fill({plot.x0, plot.y0, plot.x0 + line, plot.y1}, kFrame);
  canvas.fill({plot.x1 - line, plot.y0, plot.x1, plot.y1}, kFrame);
}

void draw_slice_labels(Text& text, const Layout& l, const Slice& slice, const SliceGeometry& g) {
  const Rect& plot = g.plot;
  int tick_font = l.font(14), label_font = l.font(16);
  for (int theta = -90; theta <= 90; theta += kGridStepDeg)
    text.draw(int(g.x_of(float(theta))), plot.y1 + l.px(20), std::to_string(theta), tick_font, kTextDim, 0);
  for (int d = g.range.low; d <= g.range.high; ++d)
    text.draw(plot.x0 - l.px(8), int(g.y_of(float(d))) + l.px(5), std::to_string(d), tick_font, kTextDim, 1);
  char title[64];
  std::snprintf(title, sizeof title, "theta_o = %g deg", double(slice.theta_o_deg));
  int plot_width = plot.x1 - plot.x0;
  text.draw((plot.x0 + plot.x1) / 2, plot.y0 - l.px(12), title, l.font(18), kText, 0, true, plot_width / 2);
  text.draw(g.cell.x0 + l.px(10), plot.y0 - l.px(12), "log10 f", label_font, kTextDim, -1);
  text.draw((plot.x0 + plot.x1) / 2, plot.y1 + l.px(44), "theta_i (deg), > 0 toward the mirror direction", label_font,
            kTextDim, 0, false, plot_width);
}

// An orthographic view down -z of the unit sphere, one directional light from the upper left with
// irradiance pi (a white Lambertian surface facing it shows 1), plus a uniform sky of radiance
// `ambient`, which a surface reflects as ambient times its directional albedo at wo (the albedo is
// the reflection of a uniform unit environment), exposure 1, clipped, sRGB. 4 x 4 samples per
// pixel for the light; the sky's term from a table over cos(theta_o) for untextured materials, else
// once per pixel at its first sample on the sphere. Rows are shared among threads, each pixel
// computed on its own.
void draw_sphere(Canvas& canvas, const cpu::Evaluator& evaluator, Rect area, vec3 background, float ambient) {
  const vec3 light = glm::normalize(vec3(-1.0f, 1.0f, 1.0f));
  const vec3 view(0.0f, 0.0f, 1.0f);
  const float irradiance = float(kPi), exposure = 1.0f;
  const int n = 4;
  int diameter = std::min(area.x1 - area.x0, area.y1 - area.y0);
  float radius = 0.5f * float(diameter);
  float cx = 0.5f * float(area.x0 + area.x1), cy = 0.5f * float(area.y0 + area.y1);
  vec3 background_linear = kernels::srgb_to_linear(background);
  std::vector<vec3> sky_table;
  if (ambient > 0.0f && evaluator.program().ops.empty())
    for (int i = 0; i <= kSkyTableSize; ++i) {
      float c = float(i) / float(kSkyTableSize);
      vec3 wo(std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c);
      sky_table.push_back(ambient * evaluator.albedo(ShadingContext{}, wo, kSkyTablePoints));
    }
  auto sky_at = [&](const ShadingContext& ctx, vec3 wo) {
    if (sky_table.empty()) return ambient * evaluator.albedo(ctx, wo, kSkyPixelPoints);
    float t = std::clamp(wo.z, 0.0f, 1.0f) * float(kSkyTableSize);
    int i = std::min(int(t), kSkyTableSize - 1);
    return glm::mix(sky_table[size_t(i)], sky_table[size_t(i + 1)], t - float(i));
  };
  auto shade_row = [&](int y) {
    for (int x = area.x0; x < area.x1; ++x) {
      vec3 sum(0.0f), sky(0.0f);
      bool have_sky = false;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          float sx = (float(x) + (float(i) + 0.5f) / float(n) - cx) / radius;
          float sy = (cy - (float(y) + (float(j) + 0.5f) / float(n))) / radius;
          float r2 = sx * sx + sy * sy;
          if (r2 >= 1.0f) {
            sum += background_linear;
            continue;
          }
          vec3 normal(sx, sy, std::sqrt(1.0f - r2));
          vec3 tangent(normal.z, 0.0f, -normal.x);  // along the longitude, around the vertical axis
          Frame frame = Frame::from_normal_tangent(normal, tangent);
          ShadingContext ctx;
          ctx.uv = vec2(0.5f + float(std::atan2(double(normal.x), double(normal.z)) / (2.0 * kPi)),
                        float(std::acos(double(std::clamp(normal.y, -1.0f, 1.0f))) / kPi));
          ctx.position = normal;
          ctx.normal = normal;
          ctx.tangent = frame.tangent;
          ctx.view_distance = 1.0f;
          vec3 wi = frame.to_local(light), wo = frame.to_local(view);
          vec3 radiance = wi.z > 0.0f ? evaluator.eval(ctx, wi, wo) * wi.z * irradiance : vec3(0.0f);
          if (ambient > 0.0f && !have_sky) {
            sky = sky_at(ctx, wo);
            have_sky = true;
          }
          radiance += sky;
          vec3 display = glm::clamp(radiance * exposure, vec3(0.0f), vec3(1.0f));
          if (!std::isfinite(display.r + display.g + display.b)) display = vec3(0.0f);
          sum += display;
        }
      vec3 mean = sum / float(n * n);
      canvas.at(x, y) = kernels::srgb_from_linear(mean);
    }
  };
  int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int y = area.y0 + t; y < area.y1; y += threads) shade_row(y);
    });
  for (auto& thread : pool) thread.join();
}

void draw_figure(OIIO::ImageBuf& image, const cpu::Evaluator& evaluator, const std::string& file, const Fonts& fonts,
                 vec2 uv, float ambient, bool& text_ok) {
  const int width = image.spec().width, height = image.spec().height;
  Layout l{double(width) / 1600.0};
  Canvas canvas(width, height, kFigureBackground);

  std::vector<Slice> slices = compute_slices(evaluator, uv);
  Decades range = value_range(slices);
  int top = l.px(92);
  int split = l.px(960);
  int cell_w = split / 2, cell_h = (height - top) / 2;

  // Draw the pixels first; text goes on top through OIIO.
  Rect sphere_panel{split, top, width, height};
  canvas.fill({split, top, width, height}, kSphereBackground);
  Rect sphere{split + l.px(20), top + l.px(44), width - l.px(20), height - l.px(44)};
  int side = std::min(sphere.x1 - sphere.x0, sphere.y1 - sphere.y0);
  int sx0 = (sphere.x0 + sphere.x1 - side) / 2, sy0 = (sphere.y0 + sphere.y1 - side) / 2;
  draw_sphere(canvas, evaluator, {sx0, sy0, sx0 + side, sy0 + side}, kSphereBackground, ambient);

  std::vector<SliceGeometry> geometry;
  for (size_t i = 0; i < slices.size(); ++i) {
    int col = int(i % 2), row = int(i / 2);
    geometry.emplace_back(l, Rect{col * cell_w, top + row * cell_h, (col + 1) * cell_w, top + (row + 1) * cell_h},
                          range);
    draw_slice_pixels(canvas, l, slices[i], geometry.back());
  }
  image.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, canvas.pixels().data());

  // Text on top, through OpenImageIO.
  Text text(image, fonts);
  for (size_t i = 0; i < slices.size(); ++i) draw_slice_labels(text, l, slices[i], geometry[i]);

  // Title and legend.
  const Program& program = evaluator.program();
  int margin = l.px(24), x = margin;
  int title_font = text.fit(program.name, l.font(30), width / 2, true);
  text.draw(x, l.px(40), program.name, title_font, kText, -1, true);
  text.draw(x + text.width(program.name, title_font, true), l.px(40), "   " + fs::path(file).filename().string(),
            l.font(18), kTextDim, -1, false, width / 3);
  const std::string intro = "In-plane BRDF slices, log10 f (1/sr) per channel:";
  const char* names[] = {"red", "green", "blue"};
  std::string rest = "(white where they agree); dashed: mirror direction";
  if (!program.ops.empty()) {
    char at[80];
    std::snprintf(at, sizeof at, "; textured: slices at uv = %g, %g", double(uv.x), double(uv.y));
    rest += at;
  }
  int legend_y = l.px(74), swatch = l.px(22), gap = l.px(6), space = l.px(14);
  auto legend_width = [&](int size) {
    int w = text.width(intro, size) + text.width(rest, size);
    for (const char* name : names) w += space + swatch + gap + text.width(name, size);
    return w + space;
  };
  int legend_font = l.font(16);
  while (legend_font > 7 && legend_width(legend_font) > width - 2 * margin) --legend_font;
  text.draw(x, legend_y, intro, legend_font, kTextDim);
  x += text.width(intro, legend_font);
  for (int c = 0; c < 3; ++c) {
    x += space;
    float rgb[3] = {kChannel[size_t(c)].r, kChannel[size_t(c)].g, kChannel[size_t(c)].b};
    int thick = std::max(2, l.px(3));
    int mid = legend_y - legend_font * 3 / 10;
    OIIO::ImageBufAlgo::fill(image, rgb, OIIO::ROI(x, x + swatch, mid - thick / 2, mid - thick / 2 + thick));
    x += swatch + gap;
    text.draw(x, legend_y, names[c], legend_font, kText);
    x += text.width(names[c], legend_font);
  }
  text.draw(x + space, legend_y, rest, legend_font, kTextDim);

  int centre = (sphere_panel.x0 + sphere_panel.x1) / 2;
  int panel_width = sphere_panel.x1 - sphere_panel.x0 - 2 * margin;
  text.draw(centre, top + l.px(30),
            ambient > 0.0f ? "sphere: one directional light from the upper left, a dim uniform sky"
                           : "sphere: one directional light from the upper left",
            l.font(18), kText, 0, true, panel_width);
  char footer[160];
  if (ambient > 0.0f)
    std::snprintf(footer, sizeof footer, "orthographic; light along (-1, 1, 1); radiance = pi f cos_i + %g albedo(wo)",
                  double(ambient));
  else
    std::snprintf(footer, sizeof footer, "orthographic; light along (-1, 1, 1); radiance = pi f cos_i");
  text.draw(centre, height - l.px(16), footer, l.font(15), kTextDim, 0, false, panel_width);
  text_ok = text.ok();
}

int run_plot(const PlotOptions& o) {
  if (o.size < kMinSize || o.size > kMaxSize) {
    std::cerr << "lamina: --size: " << o.size << " is outside [" << kMinSize << ", " << kMaxSize
              << "] (the width in pixels; the height is half of it)\n";
    return kExitInvalid;
  }
  if (!(o.ambient >= 0.0f && o.ambient <= kMaxAmbient)) {
    std::cerr << "lamina: --ambient: " << o.ambient << " is outside [0, " << kMaxAmbient
              << "] (the radiance of the uniform sky; 0 for the light alone)\n";
    return kExitInvalid;
  }
  auto uv = parse_numbers("--uv", o.uv, 2);
  if (!uv) return kExitInvalid;
  fs::path output(o.output);
  std::string format = output.extension().string();
  if (!format.empty()) format.erase(0, 1);
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (format.empty() || !OIIO::ImageOutput::create(format)) {
    print_problem("-o: cannot tell an image format from '" + o.output + "' (name the file e.g. plot.png)");
    return kExitInvalid;
  }
  Fonts fonts{find_font(false), find_font(true)};
  if (fonts.regular.empty()) fonts.regular = "DejaVuSans";  // let OpenImageIO search its font path
  if (fonts.bold.empty()) fonts.bold = fonts.regular;
  if (!OIIO::ImageBufAlgo::text_size("lamina", 16, fonts.regular).defined()) {
    std::cerr << "lamina: no font for the labels: DejaVuSans.ttf was not found (on Debian: apt-get install "
                 "fonts-dejavu-core)\n";
    return kExitIo;
  }

  std::optional<cpu::Evaluator> evaluator;
  if (int code = load_material(o.material, evaluator); code != kExitOk) return code;

  OIIO::ImageSpec spec(o.size, o.size / 2, 3, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf image(spec);
  bool text_ok = true;
  draw_figure(image, *evaluator, o.material.file, fonts, vec2((*uv)[0], (*uv)[1]), o.ambient, text_ok);
  if (!text_ok) {
    print_problem("cannot draw the labels with " + fonts.regular + ": " + image.geterror());
    return kExitIo;
  }
  image.specmod().attribute("oiio:ColorSpace", "sRGB");
  image.specmod().attribute("ImageDescription", "lamina plot of " + evaluator->program().name);

  // Encoded in memory, then written by the one writer: complete or absent, never over an input.
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput proxy(encoded);
  image.set_write_ioproxy(&proxy);
  if (!image.write("plot." + format, OIIO::TypeDesc::UINT8, format)) {
    print_problem("cannot encode " + o.output + ": " + image.geterror());
    return kExitIo;
  }
  if (int code = write_outputs({{output, std::string(encoded.begin(), encoded.end())}}); code != kExitOk) return code;
  return kExitOk;
}

}  // namespace

void add_plot(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<PlotOptions>();
  auto* cmd = app.add_subcommand("plot", "Draw a material: four in-plane BRDF slices beside a lit sphere");
  add_material_options(*cmd, o->material);
  cmd->add_option("-o,--output", o->output, "the image to write, e.g. plot.png (any format OpenImageIO writes)")
      ->required();
  cmd->add_option("--size", o->size, "image width in pixels; the height is half of it")->capture_default_str();
  cmd->add_option("--uv", o->uv, "texture coordinates U,V of the slices (textured materials)")->capture_default_str();
  cmd->add_option("--ambient", o->ambient,
                  "radiance of the uniform sky around the sphere, in [0, 10]; 0 for the directional light alone")
      ->capture_default_str();
  cmd->footer(
      "The slices show log10 f per channel in the plane of incidence, against the light's angle theta_i from the "
      "normal (positive on the mirror side), for views at 0, 30, 60 and 80 degrees, at one uv. The sphere is lit by "
      "one directional light from the upper left (irradiance pi: a white Lambertian surface facing it shows 1) and a "
      "dim uniform sky (--ambient; a surface reflects it as ambient times its directional albedo, so smooth metals "
      "show their colour away from the highlight), seen orthographically; uv follows longitude and latitude. Nothing "
      "is written for an invalid file.");
  cmd->callback([o, &runner] { runner = [o] { return run_plot(*o); }; });
}

}  // namespace lamina::cli
