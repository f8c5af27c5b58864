// lamina's fuzz targets: each takes one input (the bytes of a file) through a path a command
// takes, and states what must hold for any input. The libFuzzer programs of tests/fuzz call them
// (fuzz_main.cpp); the ordinary test suite replays the seed corpora and every input that ever
// failed (tests/fuzz/regressions) through the same functions.
//
// A target returns normally for every input, valid or not. It throws Finding when an invariant does
// not hold; any other exception escaping it is a finding too (a crash of the command).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace lamina::fuzz {

class Finding : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

using TargetFunction = void (*)(std::string_view input);

struct Target {
  std::string name;  // the program is fuzz_<name>; its corpus folders are named after it
  TargetFunction run = nullptr;
  std::string dictionary;  // file under tests/fuzz/dictionaries, or "" for none
};

// Every target, in the order tools/run_fuzz.sh runs them.
const std::vector<Target>& targets();
const Target* find_target(std::string_view name);

// Material file: read, check, write back and read again, compile, evaluate and sample.
void run_material(std::string_view input);
// Material file: every valid material through the GLSL generator, each target and form.
void run_glsl(std::string_view input);
// Scene file, with the examples' material files, meshes and images as files beside it.
void run_scene(std::string_view input);
// .gltf or .glb (told apart by content) through lamina import, buffers and images in memory.
void run_gltf_import(std::string_view input);
// .gltf or .glb as a scene's mesh file.
void run_mesh(std::string_view input);
// Encoded image (any format lamina decodes) through the texture decoder.
void run_image(std::string_view input);

// The seed corpus of a target, from tests/fuzz/seeds.txt: files of the repository.
std::vector<std::filesystem::path> seed_files(const std::filesystem::path& source_dir, std::string_view target);

}  // namespace lamina::fuzz
