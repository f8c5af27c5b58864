// The GLSL back end: output is valid GLSL for every target, complete (every node type has an
// emission), deterministic and readable; numbers carry over exactly; the CLI behaves. Agreement
// with the CPU evaluator on a real GL implementation is tests/glsl/parity.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/glsl/generator.h"
#include "graph/glsl/glsl_text.h"
#include "graph/glsl/kernel_items.h"
#include "graph/glsl/kernel_sources.h"
#include "graph/load.h"
#include "graph/registry.h"
#include "nodes/kernels/kernels.h"
#include "test_support.h"

using namespace lamina;
namespace fs = std::filesystem;

namespace {

// Every material the GLSL tests run over: the examples and the test materials of tests/data/glsl.
std::vector<fs::path> glsl_material_files() {
  std::vector<fs::path> files = test::example_files();
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "tests/data/glsl"))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

struct Compiled {
  CheckedFile checked;
  std::vector<Program> programs;
};

Compiled compile_file(const fs::path& file) {
  Compiled c;
  c.checked = check_file(file.string());
  REQUIRE_MESSAGE(c.checked.ok(), file.string());
  for (const auto& g : c.checked.graphs) c.programs.push_back(compile(*g, file.string()));
  return c;
}

std::string generate(const std::vector<Program>& programs, glsl::Target target, bool uniforms,
                     glsl::Options::Shader shader = glsl::Options::Shader::None) {
  glsl::Options o;
  o.target = target;
  o.uniforms = uniforms;
  o.shader = shader;
  return glsl::generate(programs, o).source;
}

// Runs glslangValidator on `source` as a fragment shader; returns its output, empty when valid.
std::string validate(const std::string& source, const fs::path& dir, const std::string& name) {
  fs::path file = dir / (name + ".frag");
  std::ofstream(file) << source;
  fs::path log = dir / (name + ".log");
  std::string command =
      std::string(LAMINA_GLSLANG_VALIDATOR) + " -S frag '" + file.string() + "' > '" + log.string() + "' 2>&1";
  int rc = std::system(command.c_str());
  return rc == 0 ? std::string() : test::read_file(log) + "(exit " + std::to_string(rc) + ")";
}

// Joins argument lists that the generator wrapped over several lines: "f(\n    a,\n    b)" -> "f(a, b)".
std::string join_wrapped(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if ((text[i] == '(' || text[i] == ',') && i + 1 < text.size() && text[i + 1] == '\n') {
      char c = text[i];
      ++i;  // the newline, then the indentation
      while (i + 1 < text.size() && text[i + 1] == ' ') ++i;
      if (c == ',') out += ' ';
    }
  }
  return out;
}

const glsl::Target kTargets[] = {glsl::Target::Glsl330, glsl::Target::Glsl450, glsl::Target::Es300};

#ifdef LAMINA_SANITIZED
constexpr bool kValidating = false;
#else
constexpr bool kValidating = true;
#endif

}  // namespace

TEST_CASE("glsl: every material compiles for every target in both modes, alone and with the sphere and plane shaders") {
  using Shader = glsl::Options::Shader;
  test::TempDir dir;
  int modules = 0;
  for (const fs::path& file : glsl_material_files()) {
    Compiled c = compile_file(file);
    for (glsl::Target target : kTargets)
      for (bool uniforms : {false, true})
        for (Shader shader : {Shader::None, Shader::Sphere, Shader::Plane}) {
          // The sphere's and the plane's main() read the material as any host does, and the
          // targets differ only in the text around the kernels: the sphere in ES 3.00, the
          // strictest target, in both modes, and the plane there inlined, suffice.
          if (shader == Shader::Sphere && target != glsl::Target::Es300) continue;
          if (shader == Shader::Plane && (uniforms || target != glsl::Target::Es300)) continue;
          const char* suffix = shader == Shader::Sphere ? "_sphere" : shader == Shader::Plane ? "_plane" : "";
          std::string name = file.stem().string() + "_" + glsl::target_name(target) + (uniforms ? "_u" : "") + suffix;
          const std::string source = generate(c.programs, target, uniforms, shader);
          CHECK(!source.empty());
          // The sanitised build generates every module (lamina's code, which the sanitisers watch)
          // and leaves glslangValidator's verdict on the same text to the optimised build.
          if (!kValidating) continue;
          std::string log = validate(source, dir.path(), name);
          CHECK_MESSAGE(log.empty(), name << ":\n" << log);
          ++modules;
        }
  }
  // Per material: every target in both modes, the sphere in ES 3.00 in both, the plane once.
  if (kValidating) CHECK(modules == int(glsl_material_files().size()) * (int(std::size(kTargets)) * 2 + 2 + 1));
}

TEST_CASE("glsl: an untextured stack beyond 32 entries is evaluated by parts, its parameters literals or uniforms") {
  // A select of 12 varnished stacks by a constant index, half covered: 35 entries in 12 parts.
  nlohmann::json file = nlohmann::json::parse(test::select_of_layers(12));
  for (auto& node : file["materials"][0]["nodes"])
    if (node["id"] == "map") {
      node["index"] = 5.5;
      node["coverage"] = 0.5;
    }
  CheckedFile checked = check_text(file.dump(), "tiles.json");
  REQUIRE(checked.ok());
  const std::vector<Program> programs{compile(*checked.graphs[0], "tiles.json")};
  REQUIRE_FALSE(programs[0].textured());
  REQUIRE(glsl::evaluates_by_parts(programs[0]));
  test::TempDir dir;
  for (glsl::Target target : {glsl::Target::Glsl330, glsl::Target::Es300})
    for (bool uniforms : {false, true}) {
      const std::string source = generate(programs, target, uniforms);
      // Inlined, the C++ kernels resolve every part's parameters and share into literals.
      CHECK((source.find("  point.share[11] = ") != std::string::npos) == !uniforms);
      CHECK(source.find("lamina_blend_eval(lamina_tiles_parts") != std::string::npos);
      if (!kValidating) continue;
      const std::string name = std::string("tiles_") + glsl::target_name(target) + (uniforms ? "_u" : "");
      const std::string log = validate(source, dir.path(), name);
      CHECK_MESSAGE(log.empty(), name << ":\n" << log);
    }
}

TEST_CASE("glsl: the validator check can fail: a broken module is rejected") {
  test::TempDir dir;
  Compiled c = compile_file(test::source_dir() / "examples/materials/car_paint.json");
  std::string source = generate(c.programs, glsl::Target::Glsl330, false);
  const std::string call =
      std::string("return ") + glsl::composition_function(c.programs[0].model) + "(lamina_car_paint_count";
  REQUIRE(source.find(call) != std::string::npos);
  source = glsl::replace_all(source, call, "return lamina_stack_evil(lamina_car_paint_count");
  CHECK(!validate(source, dir.path(), "broken").empty());
}

TEST_CASE("glsl: every registered node type has a GLSL emission, named after the user's node") {
  // For every node a material uses, the module names it with its type: `"id" (type`. A new node
  // type without an emission fails here, since no skip list exists.
  std::set<std::string> types_seen;
  for (const fs::path& file : glsl_material_files()) {
    Compiled c = compile_file(file);
    for (size_t m = 0; m < c.programs.size(); ++m) {
      const Graph& graph = *c.checked.graphs[m];
      std::string source = generate({c.programs[m]}, glsl::Target::Glsl330, false);
      for (size_t i = 0; i < graph.size(); ++i) {
        if (!graph.used(i)) continue;
        const std::string& type = graph.decl(i).type;
        types_seen.insert(type);
        std::string needle = "\"" + graph.node(i).id + "\" (" + type;
        CHECK_MESSAGE(source.find(needle) != std::string::npos, file.filename().string() << ": no " << needle);
      }
    }
  }
  for (const NodeDecl& decl : NodeRegistry::builtin().all())
    CHECK_MESSAGE(types_seen.count(decl.type), "no example or tests/data/glsl material uses " << decl.type);
}

TEST_CASE("glsl: the embedded kernels are nodes/kernels/*.glsl verbatim, in kernels.h's order") {
  std::string header = test::read_file(test::source_dir() / "nodes/kernels/kernels.h");
  const std::string include = "#include \"nodes/kernels/";
  std::vector<std::string> order;
  for (size_t at = header.find(include); at != std::string::npos; at = header.find(include, at + 1)) {
    size_t start = at + include.size();
    std::string name = header.substr(start, header.find('"', start) - start);
    if (name.ends_with(".glsl")) order.push_back(name);  // not the table's data (dielectric_albedo.inc)
  }
  auto files = glsl::kernel_files();
  REQUIRE(files.size() == order.size());
  for (size_t i = 0; i < files.size(); ++i) {
    CHECK(files[i].name == order[i]);
    CHECK(std::string(files[i].text) == test::read_file(test::source_dir() / "nodes/kernels" / order[i]));
  }
}

namespace {

// The kernel files as they are on disk, split into pieces.
std::vector<glsl::KernelSource> kernels_on_disk() {
  std::vector<glsl::KernelSource> sources;
  static std::vector<std::string> texts;  // the pieces are views into these
  if (texts.empty())
    for (const glsl::KernelFile& f : glsl::kernel_files())
      texts.push_back(test::read_file(test::source_dir() / "nodes/kernels" / f.name));
  for (size_t i = 0; i < texts.size(); ++i)
    sources.push_back(glsl::split_kernel(glsl::kernel_files()[i].name, texts[i]));
  return sources;
}

}  // namespace

TEST_CASE("glsl: every kernel file splits into named declarations and comments that put it back together exactly") {
  for (const glsl::KernelSource& source : kernels_on_disk()) {
    std::string joined;
    size_t line = 1;
    for (const glsl::KernelPiece& piece : source.pieces) {
      CHECK(piece.line == line);
      line += size_t(std::count(piece.text.begin(), piece.text.end(), '\n'));
      joined += piece.text;
      if (piece.kind == glsl::KernelPiece::Kind::Declaration) {
        // One name per declaration, but for common.glsl's block of the kernels' macros.
        CHECK_MESSAGE((piece.defines.size() == 1 || piece.text.find("#ifndef LAMINA_FN") != std::string::npos),
                      source.name << ":" << piece.line);
        CHECK(piece.text.back() == '\n');
      }
    }
    CHECK(joined == test::read_file(test::source_dir() / "nodes/kernels" / source.name));
  }
}

TEST_CASE("glsl: no kernel has a continue or a break, which would keep Mesa from unrolling its loop") {
  // A rolled composition loop runs every entry kind's code for every entry: car_paint's eval was 8x
  // slower on llvmpipe so (nodes/kernels/stack.glsl, the composition's top comment).
  const std::regex jump(R"(\b(continue|break)\s*;)");
  for (const glsl::KernelSource& source : kernels_on_disk())
    for (const glsl::KernelPiece& piece : source.pieces) {
      if (piece.kind != glsl::KernelPiece::Kind::Declaration) continue;
      std::istringstream lines{std::string(piece.text)};
      size_t line = piece.line;
      for (std::string text; std::getline(lines, text); ++line) {
        const std::string code = text.substr(0, text.find("//"));
        CHECK_MESSAGE(!std::regex_search(code, jump), source.name << ":" << line << ": " << text);
      }
    }
}

TEST_CASE("glsl: kernel pruning follows code, not comments, and whole names, not prefixes") {
  const std::string text = R"(// lamina kernels: a test file.

// A heading for what follows: lamina_unused and lamina_helper_more in a comment are no calls.

#ifndef LAMINA_FN
#define LAMINA_FN
#endif

const float HALF = 0.5f;
const float UNUSED_CONSTANT = 2.0f;  // a trailing comment

// Unlike lamina_helper_more, this one calls nothing.
LAMINA_FN float lamina_helper(float x) { return x * HALF; }

/* A block comment that mentions lamina_unused(x). */
LAMINA_FN float lamina_helper_more(float x,
                                   float y) {
  // lamina_unused(x) would be wrong here.
  if (x > 1.0e-5f) {
    return lamina_helper(x) + y;
  }
  return 0.0f;
}

// --- a section

LAMINA_FN float lamina_unused(float x) { return UNUSED_CONSTANT * x; }
)";
  std::vector<glsl::KernelSource> sources{glsl::split_kernel("test.glsl", text)};
  std::vector<std::string> names;
  for (const glsl::KernelPiece& p : sources[0].pieces)
    for (const std::string& n : p.defines) names.push_back(n);
  CHECK(names == std::vector<std::string>{"LAMINA_FN", "HALF", "UNUSED_CONSTANT", "lamina_helper", "lamina_helper_more",
                                          "lamina_unused"});

  // Calling lamina_helper alone: not lamina_helper_more, whose name starts the same way.
  std::string helper = glsl::needed_kernels(sources, "float y = lamina_helper(1.0f);  // not lamina_unused\n");
  CHECK(helper.find("LAMINA_FN float lamina_helper(float x) { return x * HALF; }\n") != std::string::npos);
  CHECK(helper.find("const float HALF = 0.5f;\n") != std::string::npos);
  CHECK(helper.find("#ifndef LAMINA_FN\n#define LAMINA_FN\n#endif\n") != std::string::npos);
  CHECK(helper.find("float lamina_helper_more(") == std::string::npos);
  CHECK(helper.find("float lamina_unused(") == std::string::npos);
  CHECK(helper.find("UNUSED_CONSTANT") == std::string::npos);
  CHECK(helper.find("// --- a section") == std::string::npos);  // its only declaration is not needed
  CHECK(helper.rfind("// ---- kernels: nodes/kernels/test.glsl\n// lamina kernels: a test file.\n", 0) == 0);

  // lamina_helper_more pulls in lamina_helper and HALF, but its comments pull in nothing.
  std::string more = glsl::needed_kernels(sources, "lamina_helper_more(x, y)");
  CHECK(more.find("float lamina_helper(float x)") != std::string::npos);
  CHECK(more.find("/* A block comment that mentions lamina_unused(x). */\nLAMINA_FN float lamina_helper_more(") !=
        std::string::npos);
  CHECK(more.find("float lamina_unused(") == std::string::npos);

  // Everything needed: the file comes back whole, with its blank lines.
  CHECK(glsl::needed_kernels(sources, "lamina_helper_more(lamina_unused(1.0f), 2.0f)") ==
        "// ---- kernels: nodes/kernels/test.glsl\n" + text + "\n");
  // Nothing needed: nothing at all, not even the file's comment.
  CHECK(glsl::needed_kernels(sources, "// lamina_helper\nvec3 f = vec3(HALF_2);\n").empty());

  CHECK(glsl::identifiers("x = 1.0e-5f + .5e+3 * 0x1Fu; // y\n/* z */ #define W w") ==
        std::set<std::string>{"W", "w", "x"});
  CHECK_THROWS_AS(glsl::split_kernel("bad.glsl", "float f() { return 1.0f; } float g;\n"), std::logic_error);
  CHECK_THROWS_AS(glsl::split_kernel("bad.glsl", "float f() { return 1.0f;\n"), std::logic_error);
  CHECK_THROWS_AS(glsl::split_kernel("bad.glsl", "#ifdef X\nfloat f() { return 1.0f; }\n#endif\n"), std::logic_error);
}

namespace {

// The kernel part of a generated module, per kernel file: from its "// ---- kernels:" line to
// the next one or to the first line of generated code.
std::map<std::string, std::string> kernel_chunks(const std::string& module) {
  const std::string marker = "// ---- kernels: nodes/kernels/";
  size_t code = std::min(module.find("// texture/image lookups:"), module.find("// ======"));
  std::map<std::string, std::string> chunks;
  for (size_t at = module.find(marker); at < code;) {
    size_t name_end = module.find('\n', at);
    std::string name = module.substr(at + marker.size(), name_end - at - marker.size());
    size_t next = std::min(module.find(marker, name_end), code);
    chunks[name] = module.substr(name_end + 1, next - name_end - 1);
    at = next;
  }
  return chunks;
}

}  // namespace

TEST_CASE("glsl: a module embeds only the kernel pieces its materials need, each verbatim and in order") {
  std::vector<glsl::KernelSource> disk = kernels_on_disk();
  for (const fs::path& file : glsl_material_files()) {
    Compiled c = compile_file(file);
    for (glsl::Options::Shader shader :
         {glsl::Options::Shader::None, glsl::Options::Shader::Sphere, glsl::Options::Shader::Plane}) {
      std::string source = generate(c.programs, glsl::Target::Glsl330, false, shader);
      std::map<std::string, std::string> chunks = kernel_chunks(source);
      REQUIRE(!chunks.empty());
      std::string material_code =
          source.substr(std::min(source.find("// texture/image lookups:"), source.find("// ======")));
      std::set<std::string> emitted, used = glsl::identifiers(material_code), declared;
      // What the back end's macros name (LAMINA_FILM_FRESNEL: the film's kernel, in a module with a film).
      for (size_t at = source.find("#define LAMINA_"); at != std::string::npos;
           at = source.find("#define LAMINA_", at + 1))
        for (const std::string& name : glsl::identifiers(source.substr(at, source.find('\n', at) - at)))
          used.insert(name);
      for (const glsl::KernelSource& k : disk) {
        for (const glsl::KernelPiece& piece : k.pieces) declared.insert(piece.defines.begin(), piece.defines.end());
        auto chunk = chunks.find(k.name);
        if (chunk == chunks.end()) continue;
        // Walk the chunk: after blank lines, the next text must be a piece of the file, verbatim,
        // later in the file than the one before.
        const std::string& text = chunk->second;
        size_t at = 0, piece = 0;
        while (at < text.size()) {
          if (text[at] == '\n') {
            ++at;
            continue;
          }
          while (piece < k.pieces.size() && (k.pieces[piece].kind == glsl::KernelPiece::Kind::Space ||
                                             text.compare(at, k.pieces[piece].text.size(), k.pieces[piece].text) != 0))
            ++piece;
          REQUIRE_MESSAGE(piece < k.pieces.size(), file.filename().string() << ", " << k.name << ": not verbatim at\n"
                                                                            << text.substr(at, 200));
          at += k.pieces[piece].text.size();
          emitted.insert(k.pieces[piece].defines.begin(), k.pieces[piece].defines.end());
          for (const std::string& u : k.pieces[piece].uses)
            if (std::find(k.pieces[piece].defines.begin(), k.pieces[piece].defines.end(), u) ==
                k.pieces[piece].defines.end())
              used.insert(u);
          ++piece;
        }
      }
      // Closed: every kernel name the code or an emitted piece uses is emitted. Needed: every
      // emitted name is used by the material code or by another emitted piece.
      for (const std::string& name : used)
        CHECK_MESSAGE((declared.count(name) == 0 || emitted.count(name) == 1), file.filename().string()
                                                                                   << ": " << name);
      for (const std::string& name : emitted)
        CHECK_MESSAGE(used.count(name) == 1, file.filename().string() << ": " << name);
    }
  }
}

TEST_CASE("glsl: only a module with a thin film embeds the film's kernel, so the others' conductors never inline it") {
  // A film over a base (substrate/thin_film) reaches every conductor's Fresnel term; coated flakes'
  // film reaches the flakes alone.
  for (const fs::path& file : glsl_material_files()) {
    CAPTURE(file);
    Compiled c = compile_file(file);
    bool film = false, flake_film = false;
    for (const Program& p : c.programs)
      for (const StackEntry& e : p.stack) {
        const bool coated = e.model == kernels::LAMINA_SUBSTRATE_FLAKE_PAINT;
        film = film || (kernels::lamina_is_film(e.fresnel) && !coated);
        flake_film = flake_film || (kernels::lamina_is_film(e.fresnel) && coated);
      }
    const std::string source = generate(c.programs, glsl::Target::Glsl330, false);
    CHECK((source.find("vec3 lamina_fresnel_film(") != std::string::npos) == (film || flake_film));
    CHECK((source.find("#define LAMINA_FILM_FRESNEL lamina_fresnel_film\n") != std::string::npos) == film);
    CHECK((source.find("#define LAMINA_FLAKE_FILM lamina_fresnel_film\n") != std::string::npos) == flake_film);
  }
}

TEST_CASE("glsl: a module holds the kernels its stack needs, and a texture kernel exactly when a node runs it") {
  // The stack's composition (lamina_stack_eval) is one loop over every kind, so the leaf kernels of
  // every stack kind come with it; a texture operation's kernel comes only with that operation.
  namespace k = kernels;
  for (const fs::path& file : glsl_material_files()) {
    Compiled c = compile_file(file);
    for (const Program& p : c.programs) {
      auto has_substrate = [&](int model) {
        return std::any_of(p.stack.begin(), p.stack.end(),
                           [&](const StackEntry& e) { return e.kind == k::LAMINA_SUBSTRATE && e.model == model; });
      };
      auto has_layer =
          std::any_of(p.stack.begin(), p.stack.end(), [](const StackEntry& e) { return e.kind == k::LAMINA_LAYER; });
      // A layer's interface is read through the model's own composition.
      const char* interface_kernel =
          p.model == k::LAMINA_MODEL_ENERGY_CONSERVING ? "lamina_boundary_reflection" : "lamina_interface_eval";
      auto has_op = [&](const char* type) {
        return std::any_of(p.ops.begin(), p.ops.end(), [&](const TextureOp& op) { return op.decl->type == type; });
      };
      struct Expected {
        const char* function;
        bool needed;
        bool exact;  // absent when not needed, too
      };
      const Expected expected[] = {
          {"oren_nayar", has_substrate(k::LAMINA_SUBSTRATE_OREN_NAYAR), false},
          {"lamina_lambert_eval", has_substrate(k::LAMINA_SUBSTRATE_LAMBERT), false},
          {"lamina_conductor_eval", has_substrate(k::LAMINA_SUBSTRATE_CONDUCTOR), false},
          {interface_kernel, has_layer, false},
          {"checker_value", has_op("texture/checker"), true},
          {"remap_value", has_op("math/remap"), true},
          {"smoothstep_value", has_op("math/smoothstep") || has_op("texture/patina"),
           true},  // the patina weight uses it
          {"lamina_bilinear_texels", has_op("texture/image"), true},
          {"srgb_to_linear", false, true},    // images are decoded on the host
          {"srgb_from_linear", false, true},  // only the sphere shader encodes for display
      };
      for (bool uniforms : {false, true}) {
        std::set<std::string> names = glsl::identifiers(generate({p}, glsl::Target::Glsl450, uniforms));
        for (const Expected& e : expected) {
          const bool present = names.count(e.function) > 0;
          if (e.needed) CHECK_MESSAGE(present, p.name << ": " << std::string(e.function));
          if (!e.needed && e.exact) CHECK_MESSAGE(!present, p.name << ": " << std::string(e.function));
        }
      }
    }
  }
  // Car paint has no texture, so no texture kernel occurs at all.
  Compiled car = compile_file(test::source_dir() / "examples/materials/car_paint.json");
  const std::string car_source = generate(car.programs, glsl::Target::Glsl330, false);
  for (const char* function : {"checker_value", "remap_value", "smoothstep_value", "lamina_bilinear_texels"})
    CHECK(car_source.find(function) == std::string::npos);
}

TEST_CASE("glsl: output is deterministic and readable") {
  Compiled c = compile_file(test::source_dir() / "examples/materials/patina_map_copper.json");
  for (glsl::Target target : kTargets) {
    std::string a = generate(c.programs, target, true), b = generate(c.programs, target, true);
    CHECK(a == b);
  }
  std::string s = generate(c.programs, glsl::Target::Es300, false);
  CHECK(s.rfind("#version 300 es\n", 0) == 0);  // ES wants the #version on the first line
  CHECK(s.find("// Generated by lamina " LAMINA_VERSION) != std::string::npos);
  CHECK(s.find("material \"patina_map_copper\" from ") != std::string::npos);
  CHECK(s.find("precision highp float;") != std::string::npos);
  CHECK(s.find("uniform sampler2D lamina_patina_map_copper_image_patina;") != std::string::npos);
  // One statement per line and no line longer than 160 characters in the generated part.
  std::string generated = s.substr(s.find("// ======"));
  std::istringstream lines(generated);
  size_t longest = 0;
  for (std::string line; std::getline(lines, line);) {
    longest = std::max(longest, line.size());
    if (line.find("//") == std::string::npos && line.find("for (") == std::string::npos) {
      size_t semis = size_t(std::count(line.begin(), line.end(), ';'));
      CHECK_MESSAGE(semis <= 1, line);
    }
  }
  CHECK(longest <= 160);
  // The public functions, with declarations that may wrap over several lines joined back.
  std::string joined = join_wrapped(s);
  for (const char* fn : {"vec3 lamina_patina_map_copper_eval(vec3 wi, vec3 wo, vec2 uv)",
                         "float lamina_patina_map_copper_pdf(vec3 wi, vec3 wo, vec2 uv)",
                         "vec3 lamina_patina_map_copper_sample(vec3 wo, vec2 u, float u_layer, vec2 uv, out vec3 wi, "
                         "out float pdf)"})
    CHECK_MESSAGE(joined.find(fn) != std::string::npos, fn);
}

TEST_CASE("glsl: inlined constants are the CPU's resolved floats to the bit") {
  Compiled c = compile_file(test::source_dir() / "examples/materials/car_paint.json");
  std::string s = generate(c.programs, glsl::Target::Glsl330, false);
  // roughness_deg 1 -> m = tan(1 deg) computed by the shared kernel; the literal reads back exactly.
  float m = kernels::lamina_slope(1.0f, true);
  CHECK(s.find("params[0].m = " + glsl::float_literal(m) + ";") != std::string::npos);
  CHECK(std::stof(glsl::float_literal(m)) == m);
  // The aluminium's n relative to the varnish's index 1.5 above it, divided in float as the CPU does.
  const std::string n = "params[1].n = vec3(" + glsl::float_literal(1.94f / 1.5f) + ", " +
                        glsl::float_literal(1.0f / 1.5f) + ", " + glsl::float_literal(0.6f / 1.5f) + ");";
  CHECK_MESSAGE(s.find(n) != std::string::npos, n);
  CHECK(s.find("uniform lamina_car_paint_block") == std::string::npos);
}

TEST_CASE("glsl: float literals are the shortest exact decimals") {
  CHECK(glsl::float_literal(1.5f) == "1.5f");
  CHECK(glsl::float_literal(1.0f) == "1.0f");
  CHECK(glsl::float_literal(-0.25f) == "-0.25f");
  CHECK(glsl::float_literal(1e-5f) == "1e-05f");
  CHECK(glsl::float_literal(0.1f) == "0.1f");
  for (float x : {0.1f, 1.0f / 3.0f, 3.14159265f, 1e-30f, 6.02e23f, 0.0174550649f})
    CHECK(std::stof(glsl::float_literal(x)) == x);
  CHECK_THROWS(glsl::float_literal(INFINITY));
  CHECK_THROWS(glsl::float_literal(NAN));
}

TEST_CASE("glsl: names stay legal GLSL whatever the ids: no double underscores, no clashes") {
  CHECK(glsl::name_part("a__b") == "a_b");
  CHECK(glsl::name_part("_x_") == "x");
  CHECK(glsl::name_part("___") == "x");
  glsl::NameTable t;
  CHECK(t.unique("a") == "a");
  CHECK(t.unique("a") == "a_2");
  CHECK(t.unique("a") == "a_3");

  // Nodes named a_b and a__b, and one named like a kernel output, still give a valid module.
  const char* text = R"({"format": 1, "materials": [{"name": "odd__name_", "surface": "@a_b", "nodes": [
    {"id": "a_b", "type": "mix", "weight": "@checker_value.value", "a": "@a__b", "b": "@x"},
    {"id": "checker_value", "type": "texture/checker"},
    {"id": "a__b", "type": "substrate/lambert", "albedo": [0.5, 0.5, 0.5]},
    {"id": "x", "type": "substrate/lambert", "albedo": "@checker_value.color"}]}]})";
  CheckedFile checked = check_text(text, "odd.json");
  REQUIRE(checked.ok());
  std::vector<Program> programs{compile(*checked.graphs[0], "odd.json")};
  test::TempDir dir;
  for (glsl::Target target : kTargets)
    for (bool uniforms : {false, true}) {
      std::string s = generate(programs, target, uniforms);
      std::string body = s.substr(s.find("// ======"));
      // Comments quote the user's ids; code must not contain "__".
      std::istringstream lines(body);
      for (std::string line; std::getline(lines, line);) {
        std::string code = line.substr(0, line.find("//"));
        CHECK_MESSAGE(code.find("__") == std::string::npos, line);
      }
      CHECK(validate(s, dir.path(), std::string("odd_") + glsl::target_name(target) + (uniforms ? "_u" : "")).empty());
    }
}

TEST_CASE("glsl: uniform mode lays out std140 blocks and packs the file's values") {
  Compiled c = compile_file(test::source_dir() / "tests/data/glsl/every_node.json");
  glsl::Options o;
  o.uniforms = true;
  glsl::Module module = glsl::generate(c.programs, o);
  const glsl::MaterialInterface& mi = module.materials.front();
  CHECK(mi.block == "lamina_every_node_block");
  std::map<std::string, const glsl::UniformField*> by_name;
  size_t end = 0;
  for (const glsl::UniformField& f : mi.uniforms) {
    by_name[f.name] = &f;
    size_t align = f.type == "float" ? 4 : f.type == "vec2" ? 8 : 16;
    CHECK(f.offset % align == 0);
    CHECK(f.offset >= end);  // no overlap
    end = f.offset + (f.type == "float" ? 4 : f.type == "vec2" ? 8 : 12);
  }
  CHECK(mi.block_size % 16 == 0);
  CHECK(mi.block_size >= end);
  // The shared interface node "blinn_coat" gives one member, used by both layers.
  REQUIRE(by_name.count("blinn_coat_ior"));
  CHECK(by_name.count("blinn_coat_ior_2") == 0);
  CHECK(by_name["blinn_coat_ior"]->value == std::vector<float>{1.6f});
  REQUIRE(by_name.count("ggx_coat_alpha"));
  REQUIRE(by_name.count("tiles_scale"));
  CHECK(by_name["tiles_scale"]->type == "vec2");
  std::vector<std::byte> bytes = glsl::pack_uniforms(mi);
  REQUIRE(bytes.size() == mi.block_size);
  float ior = 0.0f;
  std::memcpy(&ior, bytes.data() + by_name["blinn_coat_ior"]->offset, 4);
  CHECK(ior == 1.6f);
  std::string json = glsl::interface_json(module, o);
  CHECK(json.find("\"name\": \"lamina_every_node_block\"") != std::string::npos);
  CHECK(json.find("\"value\": 1.6,") != std::string::npos);
  CHECK(module.source.find("layout(std140) uniform lamina_every_node_block {") != std::string::npos);
  CHECK(module.source.find("lamina_every_node_u.blinn_coat_ior") != std::string::npos);
}

TEST_CASE(
    "glsl: the CLI writes a module and, with --uniforms or a table, its side file, and bad input writes nothing") {
  test::TempDir dir;
  fs::path car = test::source_dir() / "examples/materials/car_paint.json";
  auto r =
      test::run_cli("glsl '" + car.string() + "' --target es300 --uniforms --shader sphere -o out.frag", dir.path());
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(dir.path() / "out.frag"));
  CHECK(fs::exists(dir.path() / "out.uniforms.json"));
  CHECK(test::read_file(dir.path() / "out.frag").find("void main()") != std::string::npos);

  r = test::run_cli("glsl '" + car.string() + "' --target 460 -o bad.frag", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("'460' is not a target (330, 450 or es300)") != std::string::npos);
  CHECK(!fs::exists(dir.path() / "bad.frag"));

  fs::path broken = dir.path() / "broken.json";
  std::ofstream(broken) << R"({"format": 1, "materials": [{"name": "b", "surface": "@s", "nodes": [
    {"id": "s", "type": "substrate/lambert", "albedo": [1.5, 0, 0]}]}]})";
  r = test::run_cli("glsl broken.json -o broken.frag", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("broken.json") != std::string::npos);
  CHECK(r.err.find("/materials/0/nodes/0/albedo") != std::string::npos);
  CHECK(!fs::exists(dir.path() / "broken.frag"));

  r = test::run_cli("glsl '" + car.string() + "' --material nope -o none.frag", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(!fs::exists(dir.path() / "none.frag"));

  // The default model reads the dielectric albedo table: on standard output its side file needs a name.
  r = test::run_cli("glsl '" + car.string() + "' -o -", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("dielectric albedo table") != std::string::npos);
  CHECK(r.err.find("--interface") != std::string::npos);
  r = test::run_cli("glsl '" + car.string() + "' -o - --interface table.json", dir.path());
  CHECK(r.exit_code == 0);
  CHECK(r.out.rfind("#version 330 core\n", 0) == 0);
  CHECK(test::read_file(dir.path() / "table.json").find("\"lamina_dielectric_albedo_table\"") != std::string::npos);
  // The seeds' model reads none, so the module alone goes to standard output.
  r = test::run_cli("glsl '" + car.string() + "' --model weidlich_wilkie -o -", dir.path());
  CHECK(r.exit_code == 0);
  CHECK(r.out.rfind("#version 330 core\n", 0) == 0);
  CHECK(r.out.find("lamina_dielectric_albedo_table") == std::string::npos);
  r = test::run_cli("glsl '" + car.string() + "' --model kubelka_munk -o model.glsl", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--model") != std::string::npos);
  CHECK(!fs::exists(dir.path() / "model.glsl"));
}

TEST_CASE("glsl: the CLI names the side file after OUT, refuses to drop it, and writes both files or neither") {
  test::TempDir dir;
  fs::path car = test::source_dir() / "examples/materials/car_paint.json";
  // OUT's extension is replaced: car.glsl -> car.uniforms.json.
  auto r = test::run_cli("glsl '" + car.string() + "' --uniforms -o car.glsl", dir.path());
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(dir.path() / "car.glsl"));
  CHECK(fs::exists(dir.path() / "car.uniforms.json"));
  CHECK(!fs::exists(dir.path() / "car.glsl.uniforms.json"));

  // The module on standard output: --uniforms needs --interface for the side file.
  r = test::run_cli("glsl '" + car.string() + "' --uniforms -o -", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("--interface") != std::string::npos);
  r = test::run_cli("glsl '" + car.string() + "' --uniforms -o - --interface side.json", dir.path());
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("layout(std140) uniform lamina_car_paint_block") != std::string::npos);
  CHECK(test::read_file(dir.path() / "side.json").find("\"lamina_car_paint_block\"") != std::string::npos);

  // A side file that cannot be written: exit 1, and neither the module nor a temporary file is left.
  r = test::run_cli("glsl '" + car.string() + "' --uniforms -o alone.glsl --interface missing_dir/side.json",
                    dir.path());
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("missing_dir/side.json") != std::string::npos);
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir.path())) left.push_back(entry.path().filename().string());
  std::sort(left.begin(), left.end());
  CHECK(left == std::vector<std::string>{"car.glsl", "car.uniforms.json", "side.json"});

  r = test::run_cli("glsl '" + car.string() + "' --uniforms -o same.glsl --interface ./same.glsl", dir.path());
  CHECK(r.exit_code == 2);
  CHECK(!fs::exists(dir.path() / "same.glsl"));
}

TEST_CASE("glsl: the header names the material file, not the path it was given by, and lists std140 without tabs") {
  test::TempDir dir;
  fs::copy_file(test::source_dir() / "tests/data/glsl/every_node.json", dir.path() / "every_node.json");
  fs::create_directory(dir.path() / "sub");
  auto a = test::run_cli("glsl every_node.json --uniforms -o - --interface a.json", dir.path());
  auto b = test::run_cli("glsl ../every_node.json --uniforms -o - --interface b.json", dir.path() / "sub");
  auto c = test::run_cli("glsl '" + (dir.path() / "every_node.json").string() + "' --uniforms -o - --interface c.json",
                         dir.path());
  REQUIRE(a.exit_code == 0);
  CHECK(a.out == b.out);
  CHECK(a.out == c.out);
  CHECK(a.out.find("// material \"every_node\" from every_node.json\n") != std::string::npos);
  CHECK(a.out.find('\t') == std::string::npos);
  // The block's members in aligned columns: offset, type, name = the file's value.
  CHECK(a.out.find("//   offset  type   member = value in the file\n") != std::string::npos);
  CHECK(a.out.find("  vec2   tiles_scale = 4.0 3.0\n") != std::string::npos);
  CHECK(a.out.find("  float  blinn_coat_ior = 1.6\n") != std::string::npos);
}

TEST_CASE("glsl: an untextured material's constant parameters set every member of LaminaParams") {
  // The struct's members as stack.glsl declares them: a member the generator forgets is left
  // undefined in GLSL (a thin film's index and thickness were once).
  const std::string kernel = test::read_file(test::source_dir() / "nodes/kernels/stack.glsl");
  const size_t start = kernel.find("struct LaminaParams {");
  REQUIRE(start != std::string::npos);
  const size_t end = kernel.find("\n};", start);
  std::set<std::string> members;
  std::istringstream lines(kernel.substr(start, end - start));
  std::string line;
  const std::regex member(R"(^  [a-z0-9]+ ([a-z_0-9]+);)");
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_search(line, m, member)) members.insert(m[1].str());
  }
  REQUIRE(members.size() > 20);
  for (const char* name : {"car_paint.json", "fluorescent_card.json"}) {
    Compiled c = compile_file(test::source_dir() / "examples/materials" / name);
    REQUIRE_FALSE(c.programs[0].textured());
    const std::string source = generate({c.programs[0]}, glsl::Target::Glsl330, false);
    for (const std::string& m : members)
      CHECK_MESSAGE(source.find("params[0]." + m + " = ") != std::string::npos, name << ": " << m);
  }
}

TEST_CASE("glsl: a fluorescent material's module has functions for coloured light and the adjoint, others none") {
  for (const fs::path& file : glsl_material_files()) {
    Compiled c = compile_file(file);
    for (const Program& p : c.programs) {
      const bool glows = std::any_of(p.stack.begin(), p.stack.end(), [](const StackEntry& e) {
        return e.kind == kernels::LAMINA_SUBSTRATE && e.model == kernels::LAMINA_SUBSTRATE_FLUORESCENT;
      });
      const std::string source = generate({p}, glsl::Target::Glsl330, false);
      CHECK_MESSAGE(
          (source.find("_eval_light(vec3 wi, vec3 wo, vec3 light, LaminaPoint point)") != std::string::npos) == glows,
          p.name);
      CHECK_MESSAGE((source.find("_eval_adjoint(vec3 wi, vec3 wo, vec3 weight, LaminaPoint point)") !=
                     std::string::npos) == glows,
                    p.name);
      // And only its module keeps the light's split and the matrices (LAMINA_FLUORESCENCE).
      CHECK_MESSAGE((source.find("#define LAMINA_FLUORESCENCE true\n") != std::string::npos) == glows, p.name);
    }
  }
}
