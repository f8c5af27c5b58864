// A headless OpenGL runner for tests and benchmarks: draws one generated GLSL fragment shader over
// a float framebuffer (one fragment per query) and reads the results back exactly. It uses EGL's
// surfaceless platform, so it needs no display; on the test machines that is Mesa llvmpipe.
//
// Conventions: the query index of pixel (x, y) is y * width + x, with y = 0 the first row both of
// every input texture (texelFetch(t, ivec2(x, 0), 0) reads texels[x]) and of the read-back
// outputs, so ivec2(gl_FragCoord.xy) is the pixel's own (x, y). Values pass through unclamped.
//
// ES 3.00 fragment shaders declare the precisions they need: the default for sampler2D in a
// fragment shader is lowp, so write `precision highp float; precision highp sampler2D;`.
//
// A Runner owns one GL context and is used from one thread. Several runners (say, a desktop and
// an ES one) may live side by side; each call makes its own context current.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace lamina::gltest {

enum class Api {
  Desktop,  // an OpenGL 4.5 core context: runs "#version 330 core" and "#version 450 core"
  Es,       // an OpenGL ES 3.x context: runs "#version 300 es"
};

// A 2D texture, GL_NEAREST, GL_CLAMP_TO_EDGE: RGBA32F bound to `uniform sampler2D <name>;`, or,
// when `integers` holds the texels, R16UI bound to `uniform usampler2D <name>;`.
struct Texture {
  std::string name;
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;   // width * height, row 0 first
  std::vector<uint16_t> integers;  // or these
};

struct Pass {
  // A complete fragment shader starting with its #version line, writing
  // `layout(location = i) out vec4 ...;` for every i < outputs.
  std::string fragment_source;
  int width = 0, height = 0;  // the framebuffer: one fragment per query
  int outputs = 1;            // RGBA32F colour attachments (MRT)
  std::vector<Texture> textures;
  // Optional std140 uniform block, bound to binding point 0 from these bytes; they must cover
  // the block's GL_UNIFORM_BLOCK_DATA_SIZE.
  std::string uniform_block_name;
  std::vector<std::byte> uniform_block_data;
};

class Runner {
 public:
  // Returns nullptr and sets *error when no context can be made (no EGL, no surfaceless
  // platform, no float colour buffers on ES, ...); never throws for that.
  static std::unique_ptr<Runner> create(Api api, std::string* error);
  ~Runner();
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;

  Api api() const { return api_; }
  std::string renderer() const { return renderer_; }  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const { return version_; }    // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"

  // Compiles, links and draws the pass once; (*outputs)[i][y * width + x] is output i at pixel
  // (x, y). On failure returns false with *error set: compile and link errors carry the info log
  // followed by the source lines it names, numbered as in the source.
  bool run(const Pass& pass, std::vector<std::vector<glm::vec4>>* outputs, std::string* error);

  // For benchmarks: sets the pass up and draws it once to warm up (llvmpipe compiles the shader
  // to machine code on its first draw), then draws it `frames` times with a glFinish after each.
  // Returns the mean seconds per frame without set-up or read-back; < 0 with *error on failure.
  double time_pass(const Pass& pass, int frames, std::string* error);

 private:
  Runner(Api api, void* display, void* context);
  bool make_current(std::string* error) const;

  Api api_;
  void* display_;  // EGLDisplay, shared by all runners for the life of the process
  void* context_;  // EGLContext
  std::string renderer_, version_;
};

// Under LeakSanitizer, runs the process's leak check now; later ones, the one at exit included, are
// then skipped. Programs that draw call it as main returns, after every Runner is gone: Mesa's
// worker threads are idle then, whereas at exit its exit handlers stop them while the sanitizer
// suspends every thread, and a thread caught half-way through its exit crashes the sanitizer
// ("LeakSanitizer has encountered a fatal error", once in CI). Without the sanitizer: nothing.
void check_leaks_now();

}  // namespace lamina::gltest
