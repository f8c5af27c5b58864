// Every file lamina reads goes through here: the files named on the command line (or given to the
// library), and the files those name (textures, material files of a scene, mesh files, environment
// images, glTF buffers and images). One policy for all of them:
//
// - A reference is a relative path, resolved against the folder of the file that names it. Absolute
//   paths, URI schemes ("file:", "http:"), backslashes and NUL are refused.
// - It must stay inside the allowed folders, after '..' and after symbolic links are resolved: for
//   a glTF buffer or image, the glTF file's own folder (glTF 2.0 sec. 3.3 names resources by
//   relative URIs); for lamina's own files (materials, scenes), the asset roots: by default the
//   folder of the file named on the command line, widened with --asset-root.
// - Only regular files are read (a FIFO, device or directory is refused before anything is read
//   from it: opening never blocks), and no more than a size limit (graph/limits.h).
//
// Why the asset roots: a material or scene that came from elsewhere could otherwise name any image
// the user can read, and `lamina gltf` would copy it into its output.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "graph/limits.h"

namespace lamina {

// A file that cannot be read at all (exit code 1, not a user mistake in the content); the message
// names the file and carries the operating system's reason.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A reference that cannot be followed: a user mistake of the file that wrote it, reported at the
// reference's JSON pointer (exit code 2).
class ReferenceError : public std::runtime_error {
 public:
  ReferenceError(std::string message, std::string hint) : std::runtime_error(message), hint_(std::move(hint)) {}
  const std::string& hint() const { return hint_; }

 private:
  std::string hint_;
};

// Files that exist only in memory, by absolute lexical path: lamina import checks the material
// file it is about to write together with the images it will write beside it.
using FileOverlay = std::map<std::filesystem::path, std::string>;

// Where references may lead and what a decoded image may cost. Copied into every document read
// with it, so that compiling or exporting the document later follows the same rules.
struct AssetPolicy {
  // Folders that references of lamina files may reach (absolute or relative to the working
  // directory). Empty: the folder of the file being read, filled in by with_default_root.
  std::vector<std::filesystem::path> roots;
  std::uint64_t max_image_pixels = kDefaultMaxImagePixels;
  std::shared_ptr<const FileOverlay> overlay;
  bool overlay_only = false;  // references resolve in the overlay alone: the file system is not asked

  // This policy, with the folder of `top_level_file` as its root when it has none.
  AssetPolicy with_default_root(const std::filesystem::path& top_level_file) const;
};

// Reads a file named on the command line or given to the library: anything the user may read as a
// stream (a regular file, a FIFO from process substitution, a character device), never a directory.
// Throws IoError when it cannot be read; lamina::Error (the file, pointer "") when it holds more than
// `max_bytes`, a user mistake.
std::string read_input_file(const std::filesystem::path& path, std::uint64_t max_bytes);

enum class ReferenceScope {
  AssetRoots,    // lamina files: inside one of the policy's roots
  NamingFolder,  // glTF URIs: inside the folder of the file that names it
};

struct Reference {
  std::string written;             // as the file wrote it (decoded, for a URI)
  std::filesystem::path path;      // the naming file's folder / written, lexically normal (messages)
  std::filesystem::path resolved;  // symbolic links resolved: what is opened
  bool in_memory = false;          // found in the policy's overlay
};

// Resolves `written`, as the file `naming_file` wrote it, under the policy. Throws ReferenceError
// saying why a reference is refused or names nothing. Outside the allowed folders nothing is
// looked up, so a refused reference does not tell whether its file exists.
Reference resolve_reference(const std::filesystem::path& naming_file, std::string_view written, ReferenceScope scope,
                            const AssetPolicy& policy);

// The bytes of a resolved reference: a regular file of at most `max_bytes`. Throws ReferenceError
// (not a regular file, too large, cannot be opened or read, with the system's reason).
std::string read_reference(const Reference& reference, std::uint64_t max_bytes, const AssetPolicy& policy);

// Whether `path` is (the same file as) a file this process has read through the functions above:
// outputs must never replace an input.
bool is_input_file(const std::filesystem::path& path);

// "No such file or directory", "Permission denied", ... for errno value `error`.
std::string system_reason(int error);

// "12.5 MiB", "1 GiB": a byte count for messages.
std::string byte_size_text(std::uint64_t bytes);

}  // namespace lamina
