// The headless GL runner: exact float read-back in every context and GLSL version, MRT, uniform
// blocks, and errors that say where.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "glsl/gl_runner.h"

using glm::vec4;
using lamina::gltest::Api;
using lamina::gltest::Pass;
using lamina::gltest::Runner;
using lamina::gltest::Texture;

namespace {

struct Target {
  Api api;
  const char* header;  // the #version line and whatever precision the version needs
};

// Desktop and ES alternate, so the runners also take turns at being current.
const Target kTargets[] = {
    {Api::Desktop, "#version 330 core\n"},
    {Api::Es, "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n"},
    {Api::Desktop, "#version 450 core\n"},
};

// One runner per API for the whole test case.
class Runners {
 public:
  Runner& get(Api api) {
    std::unique_ptr<Runner>& r = runners_[api];
    if (!r) {
      std::string error;
      r = Runner::create(api, &error);
      REQUIRE_MESSAGE(r, error);
    }
    return *r;
  }

 private:
  std::map<Api, std::unique_ptr<Runner>> runners_;
};

// "" when equal bit for bit (no tolerance: nothing here rounds), else the first difference.
std::string first_mismatch(const std::vector<vec4>& actual, const std::vector<vec4>& expected, int width) {
  if (actual.size() != expected.size())
    return "size " + std::to_string(actual.size()) + " != " + std::to_string(expected.size());
  for (size_t i = 0; i < actual.size(); ++i)
    for (int c = 0; c < 4; ++c)
      if (std::memcmp(&actual[i][c], &expected[i][c], sizeof(float)) != 0)
        return "pixel (" + std::to_string(i % size_t(width)) + ", " + std::to_string(i / size_t(width)) +
               ") component " + std::to_string(c) + ": got " + std::to_string(actual[i][c]) + ", expected " +
               std::to_string(expected[i][c]);
  return "";
}

// Per-pixel values spanning tiny, huge and negative magnitudes, distinct for every pixel.
Texture pattern(const std::string& name, int width, int height) {
  Texture t{name, width, height, {}, {}};
  for (int i = 0; i < width * height; ++i)
    t.texels.push_back(vec4(-0.375f * float(i), 1e-20f * float(i + 1), 3e30f * float(1 + i % 7), -2.5e-3f * float(i)));
  return t;
}

}  // namespace

TEST_CASE("the GL runner reads back exactly the unclamped floats a shader writes, in every context and GLSL version") {
  Runners runners;
  const int width = 67, height = 5;  // not square, not a multiple of any tile size
  for (const Target& target : kTargets) {
    INFO(std::string(target.header));
    Pass pass;
    pass.fragment_source = std::string(target.header) +
                           "uniform sampler2D lamina_in;\n"
                           "layout(location = 0) out vec4 result;\n"
                           "void main() {\n"
                           "  ivec2 p = ivec2(gl_FragCoord.xy);\n"
                           "  result = texelFetch(lamina_in, p, 0) * 2.0 + vec4(vec2(p), 0.0, 1.0);\n"
                           "}\n";
    pass.width = width;
    pass.height = height;
    pass.textures = {pattern("lamina_in", width, height)};

    std::vector<vec4> expected;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        expected.push_back(pass.textures[0].texels[size_t(y * width + x)] * 2.0f + vec4(float(x), float(y), 0, 1));
    std::vector<std::vector<vec4>> out;
    std::string error;
    REQUIRE_MESSAGE(runners.get(target.api).run(pass, &out, &error), error);
    REQUIRE(out.size() == 1);
    const std::string mismatch = first_mismatch(out[0], expected, width);
    CHECK_MESSAGE(mismatch.empty(), mismatch);
    CHECK(out[0][1].y == 4e-20f);               // tiny values survive
    CHECK(out[0][2].z == 3e30f * 3.0f * 2.0f);  // and huge ones
  }
}

TEST_CASE("the GL runner binds 16-bit integer textures to usampler2D and texelFetch returns every integer unchanged") {
  Runners runners;
  const int width = 13, height = 3;  // odd: rows of 16-bit texels are not 4-byte aligned
  Texture codes{"codes", width, height, {}, {}};
  for (int i = 0; i < width * height; ++i) codes.integers.push_back(uint16_t(i == 0 ? 65535 : (i * 2749) % 65536));
  for (const Target& target : kTargets) {
    INFO(std::string(target.header));
    Pass pass;
    pass.fragment_source = std::string(target.header) +
                           "uniform highp usampler2D codes;\n"
                           "layout(location = 0) out vec4 result;\n"
                           "void main() {\n"
                           "  ivec2 p = ivec2(gl_FragCoord.xy);\n"
                           "  result = vec4(float(texelFetch(codes, p, 0).r), 0.0, 0.0, 1.0);\n"
                           "}\n";
    pass.width = width;
    pass.height = height;
    pass.textures = {codes};
    std::vector<vec4> expected;
    for (uint16_t c : codes.integers) expected.push_back(vec4(float(c), 0.0f, 0.0f, 1.0f));
    std::vector<std::vector<vec4>> out;
    std::string error;
    REQUIRE_MESSAGE(runners.get(target.api).run(pass, &out, &error), error);
    const std::string mismatch = first_mismatch(out[0], expected, width);
    CHECK_MESSAGE(mismatch.empty(), mismatch);
  }
}

TEST_CASE("the GL runner reads several outputs back each on its own, and binds textures of any size by name") {
  Runners runners;
  const int width = 7, height = 3;
  for (const Target& target : kTargets) {
    INFO(std::string(target.header));
    Pass pass;
    pass.fragment_source = std::string(target.header) +
                           "uniform sampler2D big;\n"
                           "uniform sampler2D small;\n"
                           "layout(location = 0) out vec4 first;\n"
                           "layout(location = 1) out vec4 second;\n"
                           "void main() {\n"
                           "  ivec2 p = ivec2(gl_FragCoord.xy);\n"
                           "  first = texelFetch(big, p, 0);\n"
                           "  second = -texelFetch(small, p % ivec2(3, 2), 0);\n"
                           "}\n";
    pass.width = width;
    pass.height = height;
    pass.outputs = 2;
    Texture small{"small", 3, 2, {}, {}};
    for (int i = 0; i < 6; ++i) small.texels.push_back(vec4(float(i), 10.0f * float(i), 0.5f, -7.0f));
    pass.textures = {small, pattern("big", width, height)};  // not in declaration order

    std::vector<vec4> expected_second;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        expected_second.push_back(small.texels[size_t((y % 2) * 3 + x % 3)] * -1.0f);  // glm negates to +0
    std::vector<std::vector<vec4>> out;
    std::string error;
    REQUIRE_MESSAGE(runners.get(target.api).run(pass, &out, &error), error);
    REQUIRE(out.size() == 2);
    const std::string first = first_mismatch(out[0], pass.textures[1].texels, width);
    const std::string second = first_mismatch(out[1], expected_second, width);
    CHECK_MESSAGE(first.empty(), first);
    CHECK_MESSAGE(second.empty(), second);
  }
}

TEST_CASE("the GL runner passes a std140 uniform block to the shader and refuses one too short for it") {
  Runners runners;
  for (const Target& target : kTargets) {
    INFO(std::string(target.header));
    Pass pass;
    pass.fragment_source = std::string(target.header) +
                           "layout(std140) uniform LaminaParams {\n"
                           "  vec4 scale;   // offset 0\n"
                           "  float shift;  // 16\n"
                           "  int count;    // 20\n"
                           "  vec3 tint;    // 32; the block is 48 bytes\n"
                           "};\n"
                           "layout(location = 0) out vec4 result;\n"
                           "void main() { result = scale * float(count) + vec4(tint, shift); }\n";
    pass.width = 2;
    pass.height = 2;
    pass.uniform_block_name = "LaminaParams";
    pass.uniform_block_data.resize(48);
    const float scale[4] = {1.5f, -2.0f, 1e-20f, 4e30f}, shift = -0.25f, tint[3] = {3.0f, 5.0f, 7.0f};
    const int count = 3;
    std::memcpy(pass.uniform_block_data.data(), scale, sizeof scale);
    std::memcpy(pass.uniform_block_data.data() + 16, &shift, sizeof shift);
    std::memcpy(pass.uniform_block_data.data() + 20, &count, sizeof count);
    std::memcpy(pass.uniform_block_data.data() + 32, tint, sizeof tint);

    std::vector<std::vector<vec4>> out;
    std::string error;
    Runner& runner = runners.get(target.api);
    REQUIRE_MESSAGE(runner.run(pass, &out, &error), error);
    const vec4 expected = vec4(1.5f, -2.0f, 1e-20f, 4e30f) * 3.0f + vec4(3.0f, 5.0f, 7.0f, -0.25f);
    const std::string mismatch = first_mismatch(out[0], std::vector<vec4>(4, expected), 2);
    CHECK_MESSAGE(mismatch.empty(), mismatch);

    pass.uniform_block_data.resize(32);
    CHECK_FALSE(runner.run(pass, &out, &error));
    CHECK_MESSAGE(error.find("needs 48 bytes") != std::string::npos, error);
  }
}

TEST_CASE("the GL runner reports a shader that does not compile with the line number and text of the error") {
  Runners runners;
  for (const Target& target : kTargets) {
    INFO(std::string(target.header));
    const std::string header = target.header;
    const int header_lines = int(std::count(header.begin(), header.end(), '\n'));
    Pass pass;
    pass.fragment_source = header +
                           "layout(location = 0) out vec4 result;\n"
                           "void main() {\n"
                           "  result = vec4(1.0) +;\n"
                           "}\n";
    pass.width = pass.height = 1;
    std::vector<std::vector<vec4>> out;
    std::string error;
    CHECK_FALSE(runners.get(target.api).run(pass, &out, &error));
    const std::string line = std::to_string(header_lines + 3);
    INFO(error);
    CHECK(error.find("fragment shader failed to compile") != std::string::npos);
    CHECK(error.find(":" + line) != std::string::npos);  // the compiler's own log names the line
    CHECK(error.find(std::string(5 - line.size(), ' ') + line + " |   result = vec4(1.0) +;") != std::string::npos);
  }
}

TEST_CASE("the GL runner refuses by name inputs the shader does not declare and uniforms the pass does not set") {
  Runners runners;
  Runner& runner = runners.get(Api::Desktop);
  Pass pass;
  pass.fragment_source =
      "#version 330 core\n"
      "uniform sampler2D lamina_in;\n"
      "layout(location = 0) out vec4 result;\n"
      "void main() { result = texelFetch(lamina_in, ivec2(0), 0); }\n";
  pass.width = pass.height = 1;
  std::vector<std::vector<vec4>> out;
  std::string error;

  CHECK_FALSE(runner.run(pass, &out, &error));  // lamina_in would silently read unit 0
  CHECK_MESSAGE(error.find("\"lamina_in\"") != std::string::npos, error);

  pass.textures = {{"lamina_in", 1, 1, {vec4(1.0f)}, {}}, {"lamina_ni", 1, 1, {vec4(2.0f)}, {}}};
  CHECK_FALSE(runner.run(pass, &out, &error));  // a misspelt name
  CHECK_MESSAGE(error.find("\"lamina_ni\" is not a uniform") != std::string::npos, error);

  pass.textures.pop_back();
  pass.outputs = 2;  // the shader writes only location 0
  CHECK_FALSE(runner.run(pass, &out, &error));
  CHECK_MESSAGE(error.find("location 1") != std::string::npos, error);

  pass.outputs = 1;
  REQUIRE_MESSAGE(runner.run(pass, &out, &error), error);
  CHECK(out[0][0] == vec4(1.0f));
}

TEST_CASE("the GL runner runs both contexts on Mesa llvmpipe and times a pass") {
  Runners runners;
  for (Api api : {Api::Desktop, Api::Es}) {
    Runner& runner = runners.get(api);
    INFO(runner.renderer() << ", " << runner.version());
    CHECK(runner.renderer().find("llvmpipe") != std::string::npos);
    CHECK(runner.version().find(api == Api::Es ? "OpenGL ES 3." : "4.5") != std::string::npos);
  }
  Pass pass;
  pass.fragment_source =
      "#version 330 core\n"
      "layout(location = 0) out vec4 result;\n"
      "void main() { result = gl_FragCoord; }\n";
  pass.width = 64;
  pass.height = 64;
  std::string error;
  const double seconds = runners.get(Api::Desktop).time_pass(pass, 3, &error);
  // A duration, not a bound on it: speed is measured by the benchmarks, never asserted in tests.
  CHECK_MESSAGE(seconds > 0.0, error);
  CHECK(std::isfinite(seconds));
}
