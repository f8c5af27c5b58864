#include "glsl/gl_runner.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <sstream>

#include <EGL/egl.h>
#include <EGL/eglext.h>
// GL entry points come from GLVND's libOpenGL for both APIs. Its functions are stubs that jump
// through libGLdispatch's table for the thread's current context, which eglMakeCurrent fills in
// from Mesa for desktop and ES contexts alike; every function used here exists in GL 4.5 and in
// ES 3.x, so libGLESv2 (the same stubs, fewer of them) is not needed and not linked.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

// clang says __has_feature(address_sanitizer), GCC defines __SANITIZE_ADDRESS__; ASan carries LSan.
#if defined(__SANITIZE_ADDRESS__)
#define LAMINA_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
#define LAMINA_LEAK_SANITIZER 1
#endif
#endif
#ifdef LAMINA_LEAK_SANITIZER
#include <sanitizer/lsan_interface.h>
#endif

namespace lamina::gltest {

static_assert(sizeof(glm::vec4) == 4 * sizeof(float), "texels and outputs are read as packed RGBA floats");

// The EGL macros EGL_NO_DISPLAY etc. are old-style casts of 0, which -Wold-style-cast rejects.
constexpr EGLDisplay kNoDisplay = nullptr;
constexpr EGLContext kNoContext = nullptr;
constexpr EGLSurface kNoSurface = nullptr;
constexpr EGLConfig kNoConfig = nullptr;  // EGL_NO_CONFIG_KHR

namespace {

std::string hex(long long value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%llx", value);
  return buf;
}

std::string egl_failure(const char* what) {
  return std::string(what) + " failed (EGL error " + hex(eglGetError()) + ")";
}

bool has_word(const char* list, const std::string& word) {
  if (!list) return false;
  std::istringstream words(list);
  std::string w;
  while (words >> w)
    if (w == word) return true;
  return false;
}

// Whether `name` occurs in `source` as a whole identifier.
bool mentions(const std::string& source, const std::string& name) {
  auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t at = source.find(name); at != std::string::npos; at = source.find(name, at + 1)) {
    const size_t end = at + name.size();
    if ((at == 0 || !ident(source[at - 1])) && (end == source.size() || !ident(source[end]))) return true;
  }
  return false;
}

const char* gl_error_name(GLenum code) {
  switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
  }
}

// Reports every pending GL error; false if there was one.
bool gl_ok(const char* what, std::string* error) {
  std::string codes;
  for (GLenum code = glGetError(); code != GL_NO_ERROR; code = glGetError())
    codes += std::string(codes.empty() ? "" : ", ") + gl_error_name(code) + " (" + hex(code) + ")";
  if (codes.empty()) return true;
  *error = std::string(what) + ": " + codes;
  return false;
}

GLint get_int(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

std::string gl_string(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}

bool has_gl_extension(const std::string& name) {
  const GLint count = get_int(GL_NUM_EXTENSIONS);
  for (GLint i = 0; i < count; ++i)
    if (const GLubyte* e = glGetStringi(GL_EXTENSIONS, GLuint(i)); e && name == reinterpret_cast<const char*>(e))
      return true;
  return false;
}

// The source line a log line names: Mesa "0:12(5): error", glslang "ERROR: 0:12:", NVIDIA
// "0(12) : error"; 0 if none. (std::regex would do, but trips GCC 12's -Wmaybe-uninitialized
// under the sanitisers.)
int named_line(const std::string& log_line) {
  size_t at = log_line.find_first_not_of(' ');
  for (const char* tag : {"ERROR: ", "WARNING: "})
    if (at != std::string::npos && log_line.compare(at, std::strlen(tag), tag) == 0) at += std::strlen(tag);
  auto digits = [&](size_t from, size_t* end) {
    *end = from;
    while (*end < log_line.size() && std::isdigit(static_cast<unsigned char>(log_line[*end]))) ++*end;
    return *end > from;
  };
  size_t end = 0, line_end = 0;
  if (at == std::string::npos || !digits(at, &end) || end >= log_line.size()) return 0;
  const char open = log_line[end];
  if ((open != ':' && open != '(') || !digits(end + 1, &line_end)) return 0;
  if (open == '(' && (line_end >= log_line.size() || log_line[line_end] != ')')) return 0;
  return std::stoi(log_line.substr(end + 1, line_end - end - 1));
}

// The info log followed by the source lines it names, with two lines before each for errors
// only detected at the next token. Lines count from 1 at the #version line, as GLSL counts.
std::string annotate(const std::string& log, const std::string& source) {
  std::vector<std::string> lines;
  std::istringstream in(source);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::set<int> named, shown;
  std::istringstream log_lines(log);
  for (std::string l; std::getline(log_lines, l) && named.size() < 10;) {
    const int n = named_line(l);
    if (n < 1 || n > int(lines.size())) continue;
    named.insert(n);
    for (int k = std::max(1, n - 2); k <= n; ++k) shown.insert(k);
  }
  std::string out = log;
  if (!out.empty() && out.back() != '\n') out += '\n';
  int previous = 0;
  for (int n : shown) {
    if (previous && n != previous + 1) out += "  ...\n";
    char prefix[32];
    std::snprintf(prefix, sizeof prefix, "%c%5d | ", named.count(n) ? '>' : ' ', n);
    out += prefix + lines[size_t(n - 1)] + '\n';
    previous = n;
  }
  return out;
}

bool compile(GLenum stage, const std::string& source, const char* label, GLuint* shader, std::string* error) {
  *shader = glCreateShader(stage);
  const char* text = source.c_str();
  const GLint length = GLint(source.size());
  glShaderSource(*shader, 1, &text, &length);
  glCompileShader(*shader);
  GLint ok = GL_FALSE, log_length = 0;
  glGetShaderiv(*shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return gl_ok(label, error);
  glGetShaderiv(*shader, GL_INFO_LOG_LENGTH, &log_length);
  std::string log(size_t(std::max(log_length, 1)), '\0');
  glGetShaderInfoLog(*shader, GLsizei(log.size()), nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  *error = std::string(label) + " failed to compile:\n" + annotate(log, source);
  return false;
}

// A triangle from gl_VertexID with corners (-1,-1), (3,-1), (-1,3) covers the viewport, so each
// pixel gets exactly one fragment at its centre. It needs no attributes, only a bound VAO.
std::string vertex_source(const std::string& version_line) {
  return version_line +
         "\n"
         "void main() {\n"
         "  vec2 p = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;\n"
         "  gl_Position = vec4(p, 0.0, 1.0);\n"
         "}\n";
}

// Every GL object of one pass, deleted together whatever way the pass ends.
struct PassObjects {
  GLuint vertex = 0, fragment = 0, program = 0, vao = 0, fbo = 0, ubo = 0;
  std::vector<GLuint> inputs, targets;  // textures
  PassObjects() = default;
  PassObjects(const PassObjects&) = delete;
  PassObjects& operator=(const PassObjects&) = delete;
  ~PassObjects() {
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    glDeleteProgram(program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteBuffers(1, &ubo);
    glDeleteTextures(GLsizei(inputs.size()), inputs.data());
    glDeleteTextures(GLsizei(targets.size()), targets.data());
    glGetError();  // nothing above can fail on valid names; do not leak an error into the next pass
  }
};

bool check_pass(const Pass& pass, std::string* error) {
  const GLint max_size = get_int(GL_MAX_TEXTURE_SIZE);
  auto bad_size = [&](int w, int h) { return w < 1 || h < 1 || w > max_size || h > max_size; };
  if (bad_size(pass.width, pass.height)) {
    *error = "framebuffer size " + std::to_string(pass.width) + " x " + std::to_string(pass.height) +
             " is not within 1 .. " + std::to_string(max_size);
    return false;
  }
  const GLint max_outputs = std::min(get_int(GL_MAX_DRAW_BUFFERS), get_int(GL_MAX_COLOR_ATTACHMENTS));
  if (pass.outputs < 1 || pass.outputs > max_outputs) {
    *error =
        std::to_string(pass.outputs) + " outputs requested; the context supports 1 .. " + std::to_string(max_outputs);
    return false;
  }
  if (int(pass.textures.size()) > get_int(GL_MAX_TEXTURE_IMAGE_UNITS)) {
    *error = std::to_string(pass.textures.size()) + " textures exceed the fragment shader's " +
             std::to_string(get_int(GL_MAX_TEXTURE_IMAGE_UNITS)) + " texture units";
    return false;
  }
  for (size_t i = 0; i < pass.textures.size(); ++i) {
    const Texture& t = pass.textures[i];
    const std::string which = "texture \"" + t.name + "\"";
    if (t.name.empty()) {
      *error = "texture " + std::to_string(i) + " has no name";
      return false;
    }
    for (size_t j = 0; j < i; ++j)
      if (pass.textures[j].name == t.name) {
        *error = which + " is given twice";
        return false;
      }
    if (bad_size(t.width, t.height)) {
      *error = which + " has size " + std::to_string(t.width) + " x " + std::to_string(t.height);
      return false;
    }
    const size_t count = t.integers.empty() ? t.texels.size() : t.integers.size();
    if (count != size_t(t.width) * size_t(t.height) || (!t.integers.empty() && !t.texels.empty())) {
      *error = which + " has " + std::to_string(t.texels.size()) + " RGBA and " + std::to_string(t.integers.size()) +
               " integer texels for " + std::to_string(t.width) + " x " + std::to_string(t.height);
      return false;
    }
  }
  if (pass.uniform_block_name.empty() != pass.uniform_block_data.empty()) {
    *error = "a uniform block needs both a name and data";
    return false;
  }
  return true;
}

std::string uniform_name(GLuint program, GLuint index, GLint* size, GLenum* type) {
  char name[256];
  GLsizei length = 0;
  glGetActiveUniform(program, index, GLsizei(sizeof name), &length, size, type, name);
  return std::string(name, size_t(length));
}

// Binds the pass's textures and uniform block to the linked program, and refuses what would
// otherwise fail silently: a shader uniform the pass leaves unset (it would read zeros or
// texture unit 0), or a pass input the shader never declares (a misspelt name).
bool bind_inputs(const Pass& pass, PassObjects& objects, std::string* error) {
  const GLuint program = objects.program;
  glUseProgram(program);

  GLint uniforms = 0;
  glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &uniforms);
  for (GLuint u = 0; u < GLuint(uniforms); ++u) {
    GLint size = 0, block = -1;
    GLenum type = 0;
    const std::string name = uniform_name(program, u, &size, &type);
    glGetActiveUniformsiv(program, 1, &u, GL_UNIFORM_BLOCK_INDEX, &block);
    if (block >= 0) continue;  // a block member: set through the block's buffer
    const bool is_texture =
        size == 1 && std::any_of(pass.textures.begin(), pass.textures.end(), [&](const Texture& t) {
          return t.name == name && type == (t.integers.empty() ? GL_SAMPLER_2D : GL_UNSIGNED_INT_SAMPLER_2D);
        });
    if (!is_texture) {
      *error = "uniform \"" + name + "\" of the fragment shader is not set by the pass (a pass sets sampler2D " +
               "and usampler2D textures by name and one uniform block)";
      return false;
    }
  }

  for (size_t i = 0; i < pass.textures.size(); ++i) {
    const Texture& t = pass.textures[i];
    const GLint location = glGetUniformLocation(program, t.name.c_str());
    if (location < 0 && !mentions(pass.fragment_source, t.name)) {
      *error = "texture \"" + t.name + "\" is not a uniform of the fragment shader";
      return false;
    }
    GLuint texture = 0;
    glGenTextures(1, &texture);
    objects.inputs.push_back(texture);
    glActiveTexture(GLenum(GL_TEXTURE0 + i));
    glBindTexture(GL_TEXTURE_2D, texture);
    if (t.integers.empty()) {
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, t.width, t.height);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t.width, t.height, GL_RGBA, GL_FLOAT, t.texels.data());
    } else {
      glPixelStorei(GL_UNPACK_ALIGNMENT, 2);  // rows of 16-bit texels, packed
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_R16UI, t.width, t.height);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t.width, t.height, GL_RED_INTEGER, GL_UNSIGNED_SHORT, t.integers.data());
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (location >= 0) glUniform1i(location, GLint(i));
    if (!gl_ok(("uploading texture \"" + t.name + "\"").c_str(), error)) return false;
  }

  GLint blocks = 0;
  glGetProgramiv(program, GL_ACTIVE_UNIFORM_BLOCKS, &blocks);
  for (GLuint b = 0; b < GLuint(blocks); ++b) {
    char name[256];
    GLsizei length = 0;
    glGetActiveUniformBlockName(program, b, GLsizei(sizeof name), &length, name);
    if (std::string(name, size_t(length)) != pass.uniform_block_name) {
      *error =
          "uniform block \"" + std::string(name, size_t(length)) + "\" of the fragment shader is not set by " +
          (pass.uniform_block_name.empty() ? "the pass" : "the pass (it sets \"" + pass.uniform_block_name + "\")");
      return false;
    }
  }
  if (pass.uniform_block_name.empty()) return true;
  const GLuint block = glGetUniformBlockIndex(program, pass.uniform_block_name.c_str());
  if (block == GL_INVALID_INDEX) {
    if (mentions(pass.fragment_source, pass.uniform_block_name)) return true;  // declared, optimised away
    *error = "uniform block \"" + pass.uniform_block_name + "\" is not declared by the fragment shader";
    return false;
  }
  GLint block_size = 0;
  glGetActiveUniformBlockiv(program, block, GL_UNIFORM_BLOCK_DATA_SIZE, &block_size);
  if (pass.uniform_block_data.size() < size_t(block_size)) {
    *error = "uniform block \"" + pass.uniform_block_name + "\" needs " + std::to_string(block_size) +
             " bytes (std140); the pass gives " + std::to_string(pass.uniform_block_data.size());
    return false;
  }
  glGenBuffers(1, &objects.ubo);
  glBindBuffer(GL_UNIFORM_BUFFER, objects.ubo);
  glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(pass.uniform_block_data.size()), pass.uniform_block_data.data(),
               GL_STATIC_DRAW);
  glUniformBlockBinding(program, block, 0);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, objects.ubo);
  return gl_ok("binding the uniform block", error);
}

// The fragment shader's vec4 outputs must cover locations 0 .. outputs-1 and nothing else: an
// attachment no output writes holds undefined values. Uses program interface queries (GL 4.3,
// ES 3.1); an ES 3.0 context skips the check.
bool check_outputs(const Pass& pass, GLuint program, std::string* error) {
  const bool queries = get_int(GL_MAJOR_VERSION) * 10 + get_int(GL_MINOR_VERSION) >= 31;
  if (!queries) return true;
  GLint count = 0;
  glGetProgramInterfaceiv(program, GL_PROGRAM_OUTPUT, GL_ACTIVE_RESOURCES, &count);
  std::vector<bool> written(size_t(pass.outputs), false);
  for (GLuint r = 0; r < GLuint(count); ++r) {
    const GLenum props[] = {GL_LOCATION, GL_ARRAY_SIZE, GL_TYPE};
    GLint values[3] = {-1, 1, 0};
    glGetProgramResourceiv(program, GL_PROGRAM_OUTPUT, r, 3, props, 3, nullptr, values);
    char name[256];
    GLsizei length = 0;
    glGetProgramResourceName(program, GL_PROGRAM_OUTPUT, r, GLsizei(sizeof name), &length, name);
    const std::string which = "fragment output \"" + std::string(name, size_t(length)) + "\"";
    if (GLenum(values[2]) != GL_FLOAT_VEC4) {
      *error = which + " is not a vec4";
      return false;
    }
    for (GLint k = 0; k < values[1]; ++k) {
      const GLint location = values[0] + k;
      if (location < 0 || location >= pass.outputs) {
        *error = which + " has location " + std::to_string(location) + " but the pass has " +
                 std::to_string(pass.outputs) + " output(s)";
        return false;
      }
      written[size_t(location)] = true;
    }
  }
  for (size_t i = 0; i < written.size(); ++i)
    if (!written[i]) {
      *error = "no fragment output has location " + std::to_string(i) + " (layout(location = " + std::to_string(i) +
               ") out vec4 ...)";
      return false;
    }
  return gl_ok("querying the fragment outputs", error);
}

// The RGBA32F colour attachments, one per output. Done before the inputs are bound: binding the
// targets here goes through the active texture unit and would displace an input texture.
bool make_framebuffer(const Pass& pass, PassObjects& objects, std::string* error) {
  glGenFramebuffers(1, &objects.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, objects.fbo);
  std::vector<GLenum> draw_buffers;
  for (int i = 0; i < pass.outputs; ++i) {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    objects.targets.push_back(texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, pass.width, pass.height);
    const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + i);
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, texture, 0);
    draw_buffers.push_back(attachment);
  }
  glDrawBuffers(GLsizei(draw_buffers.size()), draw_buffers.data());
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    *error = "the RGBA32F framebuffer is incomplete (status " + hex(status) + ")";
    return false;
  }
  // NaN marks any pixel the draw failed to reach, rather than a plausible zero.
  const float nan[4] = {NAN, NAN, NAN, NAN};
  for (int i = 0; i < pass.outputs; ++i) glClearBufferfv(GL_COLOR, i, nan);
  glBindTexture(GL_TEXTURE_2D, 0);
  return gl_ok("setting up the framebuffer", error);
}

// Compiles and links the pass, binds its inputs and an RGBA32F framebuffer, ready to draw.
bool prepare(const Pass& pass, PassObjects& objects, std::string* error) {
  glGetError();  // start clean
  if (!check_pass(pass, error)) return false;

  // The vertex shader must share the fragment shader's GLSL version and profile to link.
  const size_t start = pass.fragment_source.find_first_not_of(" \t\r\n");
  if (start == std::string::npos || pass.fragment_source.compare(start, 8, "#version") != 0) {
    *error = "the fragment shader must start with its #version line";
    return false;
  }
  const std::string version = pass.fragment_source.substr(start, pass.fragment_source.find('\n', start) - start);
  if (!compile(GL_VERTEX_SHADER, vertex_source(version), "vertex shader (generated)", &objects.vertex, error) ||
      !compile(GL_FRAGMENT_SHADER, pass.fragment_source, "fragment shader", &objects.fragment, error))
    return false;

  objects.program = glCreateProgram();
  glAttachShader(objects.program, objects.vertex);
  glAttachShader(objects.program, objects.fragment);
  glLinkProgram(objects.program);
  GLint linked = GL_FALSE;
  glGetProgramiv(objects.program, GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) {
    GLint log_length = 0;
    glGetProgramiv(objects.program, GL_INFO_LOG_LENGTH, &log_length);
    std::string log(size_t(std::max(log_length, 1)), '\0');
    glGetProgramInfoLog(objects.program, GLsizei(log.size()), nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    *error = "program failed to link:\n" + log;
    return false;
  }
  if (!gl_ok("linking", error) || !check_outputs(pass, objects.program, error) ||
      !make_framebuffer(pass, objects, error) || !bind_inputs(pass, objects, error))
    return false;

  glGenVertexArrays(1, &objects.vao);  // core profiles draw only with a VAO bound, even empty
  glBindVertexArray(objects.vao);
  glViewport(0, 0, pass.width, pass.height);
  return gl_ok("binding the vertex array", error);
}

// The process's surfaceless EGLDisplay, initialised on first use and never terminated: the handle
// is the same on every call and eglTerminate is not reference counted, so it would end every
// runner's context; and it unloads Mesa's driver, whose globals are the only references to memory
// it keeps, which LeakSanitizer then reports as leaked. Keeping it also spares each later runner
// the driver's load (about 25 ms).
EGLDisplay surfaceless_display(std::string* error) {
  static std::mutex mutex;
  static EGLDisplay display = kNoDisplay;
  std::lock_guard<std::mutex> lock(mutex);
  if (display != kNoDisplay) return display;
  // Client extensions are queried on no display; NULL means EGL_EXT_client_extensions is missing.
  const char* client = eglQueryString(kNoDisplay, EGL_EXTENSIONS);
  if (!has_word(client, "EGL_EXT_platform_base") || !has_word(client, "EGL_MESA_platform_surfaceless")) {
    *error = "EGL lacks EGL_EXT_platform_base or EGL_MESA_platform_surfaceless (client extensions: " +
             std::string(client ? client : "none") + ")";
    return nullptr;
  }
  const auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  // The surfaceless platform needs no native display: EGL_DEFAULT_DISPLAY, i.e. null.
  const EGLDisplay handle =
      get_platform_display ? get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, nullptr, nullptr) : kNoDisplay;
  if (handle == kNoDisplay) {
    *error = egl_failure("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
    return nullptr;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(handle, &major, &minor)) {
    *error = egl_failure("eglInitialize");
    return nullptr;
  }
  display = handle;
  return display;
}

}  // namespace

std::unique_ptr<Runner> Runner::create(Api api, std::string* error) {
  const EGLDisplay display = surfaceless_display(error);
  if (display == kNoDisplay) return nullptr;
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  for (const char* needed : {"EGL_KHR_create_context", "EGL_KHR_no_config_context", "EGL_KHR_surfaceless_context"})
    if (!has_word(extensions, needed)) {
      *error = std::string("the EGL display lacks ") + needed;
      return nullptr;
    }
  if (!eglBindAPI(api == Api::Es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) {
    *error = egl_failure(api == Api::Es ? "eglBindAPI(EGL_OPENGL_ES_API)" : "eglBindAPI(EGL_OPENGL_API)");
    return nullptr;
  }
  const EGLint desktop_attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  const EGLint es_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
  // eglChooseConfig finds no configs on the surfaceless platform; a context without a config
  // (EGL_KHR_no_config_context) renders into framebuffer objects only, which is all we need.
  const EGLContext context =
      eglCreateContext(display, kNoConfig, kNoContext, api == Api::Es ? es_attributes : desktop_attributes);
  if (context == kNoContext) {
    *error = egl_failure(api == Api::Es ? "eglCreateContext(OpenGL ES 3)" : "eglCreateContext(OpenGL 4.5 core)");
    return nullptr;
  }
  std::unique_ptr<Runner> runner(new Runner(api, display, context));
  if (!runner->make_current(error)) return nullptr;
  runner->renderer_ = gl_string(GL_RENDERER);
  runner->version_ = gl_string(GL_VERSION);

  // Float colour attachments are core in desktop GL; ES 3 needs the extension to render to them.
  if (api == Api::Es && !has_gl_extension("GL_EXT_color_buffer_float")) {
    *error = "OpenGL ES context (" + runner->renderer_ + ", " + runner->version_ +
             ") lacks GL_EXT_color_buffer_float: cannot render to RGBA32F";
    return nullptr;
  }
  // State fixed for the context's life: tightly packed rows, and no dithering of the outputs.
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glDisable(GL_DITHER);
  if (!gl_ok("setting up the context", error)) return nullptr;
  return runner;
}

Runner::Runner(Api api, void* display, void* context) : api_(api), display_(display), context_(context) {}

Runner::~Runner() {
  eglBindAPI(api_ == Api::Es ? EGL_OPENGL_ES_API : EGL_OPENGL_API);
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, kNoSurface, kNoSurface, kNoContext);
  eglDestroyContext(display_, context_);
}

// EGL keeps one current context per thread for OpenGL and OpenGL ES together, found through the
// bound API; binding ours first lets a desktop and an ES runner take turns on one thread.
bool Runner::make_current(std::string* error) const {
  if (!eglBindAPI(api_ == Api::Es ? EGL_OPENGL_ES_API : EGL_OPENGL_API) ||
      !eglMakeCurrent(display_, kNoSurface, kNoSurface, context_)) {
    *error = egl_failure("eglMakeCurrent");
    return false;
  }
  return true;
}

bool Runner::run(const Pass& pass, std::vector<std::vector<glm::vec4>>* outputs, std::string* error) {
  if (!make_current(error)) return false;
  PassObjects objects;
  if (!prepare(pass, objects, error)) return false;
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (!gl_ok("drawing", error)) return false;

  outputs->assign(size_t(pass.outputs), {});
  for (int i = 0; i < pass.outputs; ++i) {
    std::vector<glm::vec4>& out = (*outputs)[size_t(i)];
    out.resize(size_t(pass.width) * size_t(pass.height));
    glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + i));
    glReadPixels(0, 0, pass.width, pass.height, GL_RGBA, GL_FLOAT, out.data());
  }
  return gl_ok("reading the outputs back", error);
}

double Runner::time_pass(const Pass& pass, int frames, std::string* error) {
  if (frames < 1) {
    *error = "time_pass needs at least one frame";
    return -1.0;
  }
  if (!make_current(error)) return -1.0;
  PassObjects objects;
  if (!prepare(pass, objects, error)) return -1.0;
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glFinish();
  if (!gl_ok("drawing (warm-up)", error)) return -1.0;
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f) {
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  if (!gl_ok("drawing", error)) return -1.0;
  return elapsed.count() / frames;
}

void check_leaks_now() {
#ifdef LAMINA_LEAK_SANITIZER
  __lsan_do_leak_check();
#endif
}

}  // namespace lamina::gltest
