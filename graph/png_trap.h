// libpng reports a fatal error by calling its error handler, which must not return: lamina's keeps
// the message and jumps back to the setjmp of the function that called libpng, which then fails
// with that message. Warnings are recoverable (the image still decodes or encodes) and dropped, so
// that libpng never prints on standard error. Used by the PNG reader and writer alike.
#pragma once

#include <png.h>

#include <csetjmp>
#include <string>

namespace lamina {

// The error pointer given to png_create_*_struct. A state that also carries I/O derives from it.
struct PngTrap {
  std::string error;
  std::jmp_buf jump;
};

inline void png_trap_error(png_structp png, png_const_charp message) {
  auto* trap = static_cast<PngTrap*>(png_get_error_ptr(png));
  trap->error = message;
  std::longjmp(trap->jump, 1);
}

inline void png_drop_warning(png_structp, png_const_charp) {}

}  // namespace lamina
