// A structure-aware mutator for lamina's JSON inputs (material files, scenes, glTF): it edits the
// parsed tree (a number becomes a boundary value, a node type another registered type, a link points
// at another node, a node is duplicated, a member dropped or added) and writes it back, so that most
// mutants get past the parser and reach the checker, the compiler and the evaluator. Byte flips
// alone rarely do.
//
// A GLB is mutated through its JSON chunk and written back as a well-formed container; lying
// lengths come from the byte-level mutations libFuzzer interleaves with these.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace lamina::fuzz {

// The words a mutation may write: object keys, string values and numbers that mean something to
// the reader of that format (node types and their parameters, enum choices, glTF enumerants...).
struct Vocabulary {
  std::vector<std::string> keys;
  std::vector<std::string> strings;
  std::vector<double> numbers;
};

// From lamina's registry and field tables, so that a new node type or parameter is fuzzed at once.
Vocabulary material_vocabulary();
Vocabulary scene_vocabulary();
Vocabulary gltf_vocabulary();
const Vocabulary* vocabulary_for(const std::string& target);  // nullptr: a target without one

// The libFuzzer dictionary of a vocabulary (tests/fuzz/dictionaries/*.dict): every key and string
// as a quoted JSON string, sorted, one per line.
std::string dictionary_text(const Vocabulary& vocabulary);

// One to four tree edits of `text`; false (text unchanged) when it is not JSON (or a GLB whose JSON
// chunk is) that lamina's nesting limit lets through, or when the result would exceed `max_size`.
bool mutate_json(std::string& text, const Vocabulary& vocabulary, std::mt19937& rng, size_t max_size);

}  // namespace lamina::fuzz
