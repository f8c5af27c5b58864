#include "fuzz_targets.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "graph/compile.h"
#include "graph/cpu/evaluator.h"
#include "graph/cpu/image.h"
#include "graph/glsl/generator.h"
#include "graph/gltf/import.h"
#include "graph/json_read.h"
#include "graph/json_write.h"
#include "graph/load.h"
#include "graph/scene/mesh_file.h"
#include "graph/scene/primitives.h"
#include "graph/scene/scene.h"
#include "nodes/kernels/kernels.h"

namespace fs = std::filesystem;

namespace lamina::fuzz {

namespace {

// The folder every fuzz input pretends to live in. It exists nowhere: the policies below resolve
// references in their overlay alone, so that no input can make a target read the file system.
const fs::path kFolder = "/lamina-fuzz";

// Small enough that a decoded image costs little per execution; the budget's check is the same code
// whatever its value.
constexpr std::uint64_t kFuzzImagePixels = std::uint64_t{1} << 16;

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every file under each repository folder, placed under kFolder at its path relative to that
// folder (the first folder wins where two hold the same name).
std::shared_ptr<const FileOverlay> overlay_of(const std::vector<std::string>& folders) {
  auto overlay = std::make_shared<FileOverlay>();
  for (const auto& folder : folders) {
    const fs::path root = fs::path(LAMINA_SOURCE_DIR) / folder;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.file_size() > (1u << 20)) continue;
      overlay->emplace(kFolder / fs::relative(entry.path(), root), read_bytes(entry.path()));
    }
  }
  return overlay;
}

AssetPolicy policy_with(const std::vector<std::string>& folders) {
  AssetPolicy policy;
  policy.roots = {kFolder};
  policy.max_image_pixels = kFuzzImagePixels;
  policy.overlay = overlay_of(folders);
  policy.overlay_only = true;
  return policy;
}

// Material files find the examples' textures beside them ("textures/patina_mask.png").
const AssetPolicy& material_policy() {
  static const AssetPolicy policy = policy_with({"examples/materials"});
  return policy;
}

// Scenes find the examples' material files and textures, and the test meshes, where the examples
// and the scene corpora name them.
const AssetPolicy& scene_policy() {
  static const AssetPolicy policy = policy_with({"examples", "tests/data/scenes", "tests/data/bad_scenes"});
  return policy;
}

// glTF files find the buffers and images of tests/data/gltf beside them.
const AssetPolicy& gltf_policy() {
  static const AssetPolicy policy = policy_with({"tests/data/gltf"});
  return policy;
}

void require(bool condition, const std::string& what) {
  if (!condition) throw Finding(what);
}

// Every problem names its file, points into it, says something, and prints as one line.
void check_diagnostics(const Diagnostics& diagnostics) {
  for (const auto* list : {&diagnostics.errors(), &diagnostics.warnings()}) {
    for (const Diagnostic& d : *list) {
      const std::string line = format(d);
      require(!d.file.empty(), "a diagnostic without a file: " + line);
      require(!d.message.empty(), "a diagnostic without a message: " + line);
      require(d.pointer.empty() || d.pointer.front() == '/',
              "a diagnostic pointer that is not a JSON pointer: " + line);
      const bool one_line = std::all_of(line.begin(), line.end(), [](char c) {
        return static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) != 0x7f;
      });
      require(one_line, "a diagnostic prints a control character: " + printable(line));
      // Messages quote what they need of the input, not all of it.
      require(line.size() < 16384, "a diagnostic of " + std::to_string(line.size()) + " bytes: " + line.substr(0, 200));
    }
  }
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool non_negative(glm::vec3 v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

glm::vec3 direction(float theta_deg, float phi_deg) {
  const float t = glm::radians(theta_deg), p = glm::radians(phi_deg);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// What every valid material must give anywhere: finite, non-negative values and densities, lobe
// probabilities that sum to one, samples that are unit directions above the surface.
void probe(const cpu::Evaluator& evaluator, const std::string& name) {
  const float thetas[] = {0.0f, 31.0f, 67.0f, 89.9f};
  const glm::vec2 uvs[] = {{0.0f, 0.0f}, {0.37f, 0.81f}, {-3.5f, 7.25f}};
  for (glm::vec2 uv : uvs) {
    ShadingContext ctx;
    ctx.uv = uv;
    for (float to : thetas) {
      const glm::vec3 wo = direction(to, 10.0f);
      const std::vector<float> weights = evaluator.lobe_weights(ctx, wo);
      if (!weights.empty()) {
        float sum = 0.0f;
        for (float w : weights) {
          require(std::isfinite(w) && w >= 0.0f, name + ": a lobe weight is negative or not finite");
          sum += w;
        }
        // All 0 where wo reaches no lobe (behind every tilted entry's horizon), else a distribution.
        require(sum == 0.0f || std::abs(sum - 1.0f) < 1e-3f, name + ": lobe weights do not sum to 1");
      }
      for (float ti : thetas) {
        for (float phi : {190.0f, 100.0f}) {
          const glm::vec3 wi = direction(ti, phi);
          const cpu::EvalPdf ep = evaluator.eval_pdf(ctx, wi, wo);
          require(finite(ep.f) && non_negative(ep.f), name + ": f is negative or not finite");
          require(std::isfinite(ep.pdf) && ep.pdf >= 0.0f, name + ": pdf is negative or not finite");
        }
      }
      for (float u_lobe : {0.1f, 0.5f, 0.9f}) {
        for (glm::vec2 u : {glm::vec2(0.2f, 0.3f), glm::vec2(0.77f, 0.05f), glm::vec2(0.999f, 0.6f)}) {
          const cpu::Sample s = evaluator.sample(ctx, wo, u, u_lobe);
          require(std::isfinite(s.pdf) && s.pdf >= 0.0f, name + ": a sample's pdf is negative or not finite");
          if (s.pdf > 0.0f) {
            require(finite(s.wi) && std::abs(glm::length(s.wi) - 1.0f) < 1e-3f && s.wi.z >= 0.0f,
                    name + ": a sampled direction is not a unit vector above the surface");
            require(finite(s.f) && non_negative(s.f), name + ": a sample's f is negative or not finite");
          }
        }
      }
      const glm::vec3 albedo = evaluator.albedo(ctx, wo, 16);
      require(finite(albedo) && non_negative(albedo), name + ": the albedo is negative or not finite");
    }
  }
}

// The input as a material file in the fuzz folder, checked; its programs when it is valid.
std::vector<Program> checked_programs(std::string_view input, bool round_trip) {
  const std::string file = (kFolder / "material.json").string();
  CheckedFile checked = check_text(input, file, material_policy());
  check_diagnostics(checked.diagnostics);
  if (!checked.ok()) return {};
  if (round_trip) {
    Diagnostics again;
    const Document back = read_document(write_document(checked.document), file, again);
    require(again.ok() && back.same_content(checked.document), "a valid document does not read back as written");
  }
  std::vector<Program> programs;
  for (size_t m = 0; m < checked.graphs.size(); ++m) {
    require(checked.graphs[m].has_value(), "a valid document without a graph for material " + std::to_string(m));
    programs.push_back(compile(*checked.graphs[m], file, checked.document.policy));
  }
  return programs;
}

void check_mesh(const TriangleMesh& mesh, const std::string& what) {
  const size_t n = mesh.positions.size();
  require(mesh.normals.size() == n && mesh.tangents.size() == n && mesh.uvs.size() == n,
          what + ": attribute arrays of different lengths");
  require(mesh.indices.size() % 3 == 0, what + ": an index count that is not a multiple of 3");
  for (uint32_t i : mesh.indices) require(i < n, what + ": an index beyond the vertices");
  for (const glm::vec3& p : mesh.positions) require(finite(p), what + ": a position that is not finite");
}

}  // namespace

void run_material(std::string_view input) {
  const std::vector<Program> programs = checked_programs(input, true);
  for (const Program& program : programs) probe(cpu::Evaluator(program), program.name);
}

void run_glsl(std::string_view input) {
  const std::vector<Program> programs = checked_programs(input, false);
  if (programs.empty()) return;
  for (glsl::Target target : {glsl::Target::Glsl330, glsl::Target::Glsl450, glsl::Target::Es300}) {
    for (bool uniforms : {false, true}) {
      glsl::Options options;
      options.target = target;
      options.uniforms = uniforms;
      options.shader = uniforms ? glsl::Options::Shader::Sphere : glsl::Options::Shader::Plane;
      const glsl::Module module = glsl::generate(programs, options);
      require(module.materials.size() == programs.size(), "the GLSL module does not hold every material");
      require(module.source.find("#version") == 0, "the GLSL module does not start with #version");
      require(!glsl::interface_json(module, options).empty(), "an empty uniform interface");
      for (const auto& material : module.materials)
        require(glsl::pack_uniforms(material).size() == material.block_size,
                "packed uniforms differ from the block size");
      for (const glsl::TableBinding& t : module.tables)
        require(t.texels.size() == size_t(t.width) * size_t(t.height) && !t.texels.empty(),
                "a table whose texels do not fill it");
    }
  }
}

void run_scene(std::string_view input) {
  Diagnostics diagnostics;
  const Scene scene = read_scene(input, (kFolder / "scene.json").string(), diagnostics, scene_policy());
  check_diagnostics(diagnostics);
  if (!diagnostics.ok()) return;
  // The scene's vertex budget (tested by the hostile suite) allows millions of vertices; a fuzzer
  // tessellates only scenes that stay cheap, so that it runs many inputs.
  size_t vertices = 0;
  for (const SceneObject& object : scene.objects)
    if (object.shape != ShapeType::Mesh) vertices += shape_vertices(object);
  if (vertices > (size_t{1} << 16)) return;
  for (const SceneObject& object : scene.objects) check_mesh(object_mesh(object, scene.policy), object.name);
}

void run_gltf_import(std::string_view input) {
  Diagnostics diagnostics;
  const gltf::ImportResult result = gltf::import_gltf_bytes(input, kFolder / "asset.gltf", diagnostics, gltf_policy());
  check_diagnostics(diagnostics);
  if (!diagnostics.ok()) return;
  // What import would write must validate where it is written: the material file with the
  // extracted images beside it.
  const fs::path out = kFolder / "imported";
  auto overlay = std::make_shared<FileOverlay>();
  for (const auto& texture : result.textures)
    overlay->emplace(out / texture.file_name, std::string(texture.bytes.begin(), texture.bytes.end()));
  AssetPolicy policy;
  policy.roots = {out};
  policy.max_image_pixels = kFuzzImagePixels;
  policy.overlay = overlay;
  policy.overlay_only = true;
  const CheckedFile again = check_text(write_document(result.document), (out / "material.json").string(), policy);
  std::string first;
  if (!again.ok()) first = format(again.diagnostics.errors().front());
  require(again.ok(), "an imported document does not validate: " + first);
}

void run_mesh(std::string_view input) {
  try {
    check_mesh(load_mesh_bytes(input, kFolder / "mesh.gltf", gltf_policy()), "mesh");
  } catch (const Error& e) {
    Diagnostics diagnostics;
    for (const Diagnostic& d : e.diagnostics()) diagnostics.error(d.file, d.pointer, d.message, d.hint);
    require(!e.diagnostics().empty(), "a mesh error without a diagnostic");
    check_diagnostics(diagnostics);
  } catch (const ReferenceError& e) {
    require(std::string_view(e.what()).size() > 0, "a reference error without a message");
  }
}

void run_image(std::string_view input) {
  // The format comes from the bytes alone; the length's parity picks the transfer curve.
  const bool srgb = input.size() % 2 == 1;
  std::shared_ptr<const LinearImage> image;
  try {
    image = decode_linear_image(input, srgb, kFuzzImagePixels);
  } catch (const ImageError& e) {
    const std::string message = e.what();
    require(!message.empty(), "an image error without a message");
    return;
  }
  const ImageHeader header = read_image_header(input);
  require(image->width > 0 && image->height > 0, "a decoded image without pixels");
  require(static_cast<std::uint64_t>(image->width) == header.width &&
              static_cast<std::uint64_t>(image->height) == header.height,
          "a decoded image whose size is not the one its header declares");
  const auto pixels = static_cast<std::uint64_t>(image->width) * static_cast<std::uint64_t>(image->height);
  require(pixels <= kFuzzImagePixels, "a decoded image beyond the pixel budget");
  require(image->texels.size() == pixels, "texels that do not match the image's size");
  for (const glm::vec4& t : image->texels)
    require(finite(glm::vec3(t)) && std::isfinite(t.a), "a decoded texel that is not finite");
}

const std::vector<Target>& targets() {
  static const std::vector<Target> list = {
      {"material", run_material, "material.dict"},
      {"glsl", run_glsl, "material.dict"},
      {"scene", run_scene, "scene.dict"},
      {"gltf_import", run_gltf_import, "gltf.dict"},
      {"mesh", run_mesh, "gltf.dict"},
      {"image", run_image, ""},
  };
  return list;
}

const Target* find_target(std::string_view name) {
  for (const Target& t : targets())
    if (t.name == name) return &t;
  return nullptr;
}

std::vector<fs::path> seed_files(const fs::path& source_dir, std::string_view target) {
  // Each line of seeds.txt: a target, a folder of the repository and a file extension.
  std::ifstream list(source_dir / "tests" / "fuzz" / "seeds.txt");
  std::vector<fs::path> files;
  std::string line;
  while (std::getline(list, line)) {
    std::istringstream words(line);
    std::string name, folder, extension;
    if (line.empty() || line.front() == '#' || !(words >> name >> folder >> extension) || name != target) continue;
    for (const auto& entry : fs::directory_iterator(source_dir / folder))
      if (entry.is_regular_file() && entry.path().extension() == extension) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace lamina::fuzz
