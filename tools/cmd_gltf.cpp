// lamina gltf IN.json -o OUT.gltf|OUT.glb: a scene, or a material file as a sample sheet of
// spheres, to glTF 2.0 with the LAMINA_materials_layered extension and a fitted PBR fallback.
#include <cstdio>
#include <iostream>

#include "graph/gltf/export.h"
#include "graph/json_read.h"
#include "graph/scene/scene.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace {

struct GltfOptions {
  std::string input;
  std::string output;
  bool report = false;
  int bake_size = 0;  // auto
  int fit_states = gltf::FallbackOptions{}.max_states;
  int columns = 4;
  InputOptions input_options;
};

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string percent(float value) { return fixed(100.0 * double(value), 1) + "%"; }

void print_report(const gltf::Export& result) {
  std::cout << "fallback fit (relative albedo error at 0 and 80 degrees, of it at 0 degrees the share beyond any "
               "glTF material where the lamina material reflects more than it receives, RMS residual over the "
               "fit's direction pairs, and the CIE 1976 lightness and colour (a*b*) differences of the mean colour on "
               "lamina plot's sphere; worst over texture states):\n";
  std::printf("  %-24s %6s %8s %9s %7s %7s %7s %7s %5s %5s  %s\n", "material", "states", "metallic", "roughness",
              "albedo0", "beyond", "albedo80", "rms", "dL*", "dab", "extensions");
  for (const auto& m : result.materials) {
    const auto& f = m.fallback;
    std::string extensions;
    if (f.uses_clearcoat) extensions += " clearcoat";
    if (f.uses_ior) extensions += " ior";
    if (f.uses_specular) extensions += " specular";
    if (f.base_color || f.metallic_roughness || f.clearcoat) extensions += " +baked textures";
    std::string states = std::to_string(f.states.size()) + (f.interpolated ? "~" : "");
    if (f.bake_size > 0) extensions += " (" + std::to_string(f.bake_size) + " px)";
    std::string metallic = f.metallic_roughness ? "tex" : fixed(f.params.metallic, 2);
    std::string roughness = f.metallic_roughness ? "tex" : fixed(f.params.roughness, 2);
    std::printf("  %-24s %6s %8s %9s %7s %7s %8s %7s %5s %5s %s\n", m.name.c_str(), states.c_str(), metallic.c_str(),
                roughness.c_str(), percent(f.worst.albedo_normal).c_str(), percent(f.worst.unreachable_normal).c_str(),
                percent(f.worst.albedo_grazing).c_str(), percent(f.worst.rms).c_str(),
                fixed(f.worst.lightness, 1).c_str(), fixed(f.worst.colour, 1).c_str(),
                extensions.empty() ? " -" : extensions.c_str());
  }
  std::cout << std::flush;
}

int run_gltf(const GltfOptions& o) {
  const std::filesystem::path output(o.output);
  if (output.extension() != ".gltf" && output.extension() != ".glb") {
    print_problem("-o: '" + o.output + "' must end in .gltf or .glb (the extension picks the container)");
    return kExitInvalid;
  }
  if (o.bake_size < 0 || o.bake_size > 4096) {
    std::cerr << "lamina: --bake-size: expected 1 to 4096 texels, or 0 for a size chosen per material, found "
              << o.bake_size << "\n";
    return kExitInvalid;
  }
  Scene scene;
  Diagnostics diagnostics;
  if (int code = read_scene_input(o.input, o.input_options, o.columns, scene, diagnostics); code != kExitOk)
    return code;
  if (!print_diagnostics(diagnostics)) return kExitInvalid;
  if (int code = check_outputs({output}); code != kExitOk) return code;  // before the fit

  gltf::ExportOptions options;
  options.fallback.bake_size = o.bake_size;
  options.fallback.max_states = o.fit_states;
  gltf::Export result;
  try {
    result = gltf::export_scene(scene, output, options);
  } catch (const IoError& e) {
    print_problem(e.what());
    return kExitIo;
  } catch (const Error& e) {
    for (const auto& d : e.diagnostics()) std::cerr << format(d) << "\n";
    return kExitInvalid;
  }
  for (const auto& note : result.notes) print_problem("note: " + note);
  // The side files first, so that the .gltf never names a buffer that is not there.
  std::vector<OutputFile> files;
  for (auto it = result.files.rbegin(); it != result.files.rend(); ++it)
    files.push_back({it->path, std::string(it->bytes.begin(), it->bytes.end())});
  if (int code = write_outputs(files); code != kExitOk) return code;
  if (o.report) print_report(result);
  std::cout << "wrote " << printable(output.string()) << " (" << scene.objects.size() << " object"
            << (scene.objects.size() == 1 ? "" : "s") << ", " << result.materials.size() << " material"
            << (result.materials.size() == 1 ? "" : "s") << ")\n";
  return kExitOk;
}

}  // namespace

void add_gltf(CLI::App& app, Runner& runner) {
  auto o = std::make_shared<GltfOptions>();
  auto* cmd = app.add_subcommand(
      "gltf", "Convert a scene, or a material file as a sheet of spheres, to glTF 2.0 with a fitted PBR fallback");
  cmd->add_option("input", o->input, "a scene file, or a material file")->required();
  cmd->add_option("-o,--output", o->output, "OUT.gltf (with OUT.bin next to it) or OUT.glb (self-contained)")
      ->required();
  cmd->add_flag("--report", o->report, "print each material's fallback fit and its errors");
  add_input_options(*cmd, o->input_options);
  cmd->add_option("--bake-size", o->bake_size,
                  "texels per side of fallback textures baked from texture nodes; 0 (the default): per material, "
                  "twice its finest detail over uv as a power of two from 64 to 512 (README, glTF)")
      ->capture_default_str();
  cmd->add_option("--fit-states", o->fit_states,
                  "fits per textured material: its distinct texture states up to this many, representative ones "
                  "beyond, the texels between interpolated (fewer: a faster export, a coarser fallback)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  add_sheet_columns_option(*cmd, o->columns);
  cmd->callback([o, &runner] { runner = [o] { return run_gltf(*o); }; });
}

}  // namespace lamina::cli
