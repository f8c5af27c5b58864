#include "graph/image_codec.h"

#include <dlfcn.h>

#include <filesystem>

#include "graph/file_access.h"

namespace lamina {

namespace {

// The module sits beside the object that holds this function: liblamina.so in the build tree and
// once installed, or the program itself when liblamina is linked statically.
std::filesystem::path module_folder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&module_folder), &info) == 0 || info.dli_fname == nullptr) return {};
  return std::filesystem::path(info.dli_fname).parent_path();
}

struct Loaded {
  const ImageCodec* codec = nullptr;
  std::string error;
};

Loaded load() {
  const std::filesystem::path folder = module_folder();
  // A static program's folder is bin/; the module is installed in lib/ (the same place as the
  // library's RPATH names).
  std::vector<std::filesystem::path> candidates = {folder / LAMINA_IMAGE_MODULE,
                                                   folder / ".." / LAMINA_INSTALL_LIBDIR / LAMINA_IMAGE_MODULE};
  std::string reasons;
  for (const std::filesystem::path& path : candidates) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) continue;
    // Local: OpenImageIO's symbols stay out of the program's namespace. Never closed: the codec
    // is used until the program ends.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      reasons += "; " + path.string() + ": " + (why ? why : "dlopen failed");
      continue;
    }
    auto entry = reinterpret_cast<LaminaImageCodecEntry>(dlsym(handle, "lamina_image_codec"));
    if (entry == nullptr) {
      reasons += "; " + path.string() + ": it has no entry point lamina_image_codec";
      continue;
    }
    return {entry(), {}};
  }
  return {nullptr, "cannot load lamina's image module " + std::string(LAMINA_IMAGE_MODULE) + " (it reads " +
                       "JPEG, OpenEXR, HDR and TIFF images, writes figures and draws text) from " + folder.string() +
                       (reasons.empty() ? ": not found" : reasons)};
}

}  // namespace

const ImageCodec& image_codec() {
  static const Loaded loaded = load();  // thread-safe, once
  if (loaded.codec == nullptr) throw IoError(loaded.error);
  return *loaded.codec;
}

}  // namespace lamina
