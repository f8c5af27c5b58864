// Every limit lamina puts on its input, in one place: what `lamina validate` checks, what every
// command agrees on, and what the README's "Limits and safety" section lists. Each bounds the
// memory or time a file can make lamina spend, or a back end's fixed capacity.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lamina {

// JSON documents (material and scene files, glTF JSON and the JSON chunk of a .glb): arrays and
// objects nest at most this deep. Checked by a linear scan before any tree is built, so that no
// recursive code (building, copying, freeing a document) can exhaust the stack. A material needs
// 6 levels, a glTF file about 10.
inline constexpr int kMaxJsonDepth = 128;

// Every number of a node parameter: magnitude at most this (besides the parameter's own range),
// so that it is exact enough in single precision and no sum or difference of two overflows.
inline constexpr double kMaxNodeNumber = 1.0e9;

// Material names and node ids: they become GLSL identifiers (GLSL ES allows 1024 characters in
// one, lamina prefixes and suffixes them) and the labels of sample-sheet spheres.
inline constexpr size_t kMaxIdentifierLength = 64;

// A reference to another file (a texture, material file, mesh, glTF buffer or image URI): Linux's
// PATH_MAX, beyond which no path can be opened anyway.
inline constexpr size_t kMaxReferenceLength = 4096;

// Material and scene files, and the JSON of a glTF file.
inline constexpr std::uint64_t kMaxJsonFileBytes = std::uint64_t{64} << 20;  // 64 MiB
// A .glb, a glTF buffer (.bin) and an image file.
inline constexpr std::uint64_t kMaxBinaryFileBytes = std::uint64_t{1} << 30;  // 1 GiB

// Decoded images: width x height at most this, by default (8192 x 8192). Checked on the file's
// header before any pixel is decoded; `--max-image-pixels` raises or lowers it.
inline constexpr std::uint64_t kDefaultMaxImagePixels = std::uint64_t{1} << 26;
// Each side of an image, whatever the budget (OpenImageIO's sizes are ints).
inline constexpr std::uint64_t kMaxImageSide = std::uint64_t{1} << 20;
// A stored pixel: at most as many channels, of at most as many bits, as a decoded texel (4 floats),
// so that a decoder's buffers never outgrow the image they decode.
inline constexpr std::uint64_t kMaxImageChannels = 4;
inline constexpr std::uint64_t kMaxImageSampleBits = 32;
// A PNG's ancillary chunk (text, colour profile) as read and as decompressed.
inline constexpr size_t kMaxPngChunkBytes = size_t{8} << 20;

// A scene: the distinct shapes its objects use (a built-in shape per distinct size and
// tessellation, a mesh file once however often it is placed) have at most this many vertices in
// all, so that a small scene cannot make lamina tessellate gigabytes of geometry.
inline constexpr size_t kMaxSceneVertices = size_t{1} << 23;  // 8,388,608

// A material's stack as the back ends hold it (the CPU evaluator's fixed arrays; GLSL unrolls the
// same): stack nodes (layers, mixes, interfaces' layers and substrates reached from the surface),
// lobes (one per interface and substrate, per path through the mixes) and texture registers.
inline constexpr int kMaxStackNodes = 64;
inline constexpr int kMaxLobes = 64;
inline constexpr int kMaxSlots = 256;
// The compiled stack's entries: one per stack node as reached along each path from the surface
// (a stack both sides of a mix share appears once per side). Every mix entry has two children, so
// there are fewer than two entries per lobe.
inline constexpr int kMaxStackEntries = 2 * kMaxLobes;
// Not a limit but a cliff: GLSL compilers unroll no loop of more than this many iterations
// (Mesa's NIR: max_unroll_iterations, 32 for llvmpipe and most of its hardware drivers, applies
// even to the loops it otherwise forces open because they index an array by their counter). The
// composition loops over a stack's entries; up to this many it runs unrolled, every index
// constant; beyond, the loops stay loops that index the stack's arrays by a variable, and on
// llvmpipe the module takes minutes to compile instead of seconds. `lamina validate` and `lamina
// glsl` warn about a stack beyond it.
inline constexpr int kGlslUnrolledEntries = 32;

// substrate/thin_film's film: at most 10 um thick (the spectral fold is right at any thickness, and
// no colour is left long before), of index 1 to 3 (titanium dioxide, among the densest films, is
// below 2.9 in the visible).
inline constexpr double kMaxFilmThicknessNm = 10000.0;
inline constexpr double kMaxFilmIor = 3.0;

}  // namespace lamina
