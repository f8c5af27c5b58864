// The text of nodes/kernels/*.glsl, embedded at build time (cmake/embed_kernels.cmake), in the
// order kernels.h includes them: the GLSL back end embeds the pieces of them a module needs
// (kernel_items.h) after its prelude.
#pragma once

#include <span>
#include <string>

namespace lamina::glsl {

struct KernelFile {
  const char* name;  // e.g. "fresnel.glsl"
  std::string text;  // joined from the pieces the build embeds (cmake/embed_kernels.cmake)
};

std::span<const KernelFile> kernel_files();

}  // namespace lamina::glsl
