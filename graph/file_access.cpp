#include "graph/file_access.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <utility>

#include "graph/diagnostics.h"

namespace lamina {

namespace fs = std::filesystem;

namespace {

// The (device, inode) of every file read, so that no output replaces one of them.
class InputLedger {
 public:
  void add(const struct stat& st) {
    std::lock_guard lock(mutex_);
    files_.insert({st.st_dev, st.st_ino});
  }
  bool contains(const struct stat& st) const {
    std::lock_guard lock(mutex_);
    return files_.count({st.st_dev, st.st_ino}) != 0;
  }

 private:
  mutable std::mutex mutex_;
  std::set<std::pair<dev_t, ino_t>> files_;
};

InputLedger& ledger() {
  static InputLedger instance;
  return instance;
}

// Closes a descriptor on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

// Reads until end of file or until more than `max_bytes` arrived; errno is kept on failure.
bool read_all(int fd, std::uint64_t max_bytes, std::uint64_t expected, std::string& out, bool& too_large) {
  too_large = false;
  out.clear();
  out.reserve(static_cast<size_t>(std::min<std::uint64_t>(expected, max_bytes)));
  char buffer[1 << 16];
  while (true) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (got == 0) return true;
    if (out.size() + static_cast<std::uint64_t>(got) > max_bytes) {
      too_large = true;
      return true;
    }
    out.append(buffer, static_cast<size_t>(got));
  }
}

bool is_inside(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // the empty last element of "a/b/"
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

fs::path absolute_normal(const fs::path& path) { return fs::absolute(path).lexically_normal(); }

std::string too_large_message(std::uint64_t max_bytes) {
  return "more than " + byte_size_text(max_bytes) + ", the most lamina reads from such a file";
}

}  // namespace

std::string system_reason(int error) { return std::strerror(error); }

std::string byte_size_text(std::uint64_t bytes) {
  static const char* const units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double value = static_cast<double>(bytes);
  size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < std::size(units)) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  if (value == static_cast<double>(static_cast<std::uint64_t>(value)))
    std::snprintf(text, sizeof text, "%.0f %s", value, units[unit]);
  else
    std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

AssetPolicy AssetPolicy::with_default_root(const fs::path& top_level_file) const {
  AssetPolicy out = *this;
  if (out.roots.empty()) out.roots.push_back(absolute_normal(top_level_file).parent_path());
  return out;
}

std::string read_input_file(const fs::path& path, std::uint64_t max_bytes) {
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) throw IoError(path.string() + ": cannot open: " + system_reason(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw IoError(path.string() + ": cannot read: " + system_reason(errno));
  if (S_ISDIR(st.st_mode)) throw IoError(path.string() + ": cannot read: " + system_reason(EISDIR));
  const bool regular = S_ISREG(st.st_mode);
  auto too_large = [&] {
    throw Error({Diagnostic{
        Severity::Error, path.string(), "",
        "the file is " + (regular ? std::to_string(st.st_size) + " bytes, " : std::string("longer than that: ")) +
            too_large_message(max_bytes),
        "split it into several files"}});
  };
  if (regular && static_cast<std::uint64_t>(st.st_size) > max_bytes) too_large();
  std::string text;
  bool over = false;
  if (!read_all(fd.get(), max_bytes, regular ? static_cast<std::uint64_t>(st.st_size) : 0, text, over))
    throw IoError(path.string() + ": cannot read: " + system_reason(errno));
  if (over) too_large();
  ledger().add(st);
  return text;
}

Reference resolve_reference(const fs::path& naming_file, std::string_view written, ReferenceScope scope,
                            const AssetPolicy& policy) {
  Reference ref;
  ref.written = std::string(written);
  // Every message starts with the reference as written, so that callers can put what it is in
  // front: "texture file 'x.png' not found".
  const std::string shown = quote_excerpt(ref.written, '\'');
  const char* const relative_hint = "name files by paths relative to the file that names them";
  if (written.empty()) throw ReferenceError("'' is an empty path", relative_hint);
  if (written.size() > kMaxReferenceLength)
    throw ReferenceError(
        shown + " is longer than any path lamina follows (" + std::to_string(kMaxReferenceLength) + " bytes)",
        relative_hint);
  if (written.find('\0') != std::string_view::npos)
    throw ReferenceError(shown + " contains a NUL byte, which no path can hold", relative_hint);
  if (written.find('\\') != std::string_view::npos)
    throw ReferenceError(shown + " contains a backslash", "separate folders with '/'");
  if (written.front() == '/')
    throw ReferenceError(shown + " is an absolute path, which lamina does not follow", relative_hint);
  // RFC 3986 sec. 3.1: scheme ":"; also catches Windows drive letters ("C:").
  const size_t colon = written.find(':');
  if (colon != std::string_view::npos && colon > 0) {
    const std::string_view scheme = written.substr(0, colon);
    const bool is_scheme =
        std::isalpha(static_cast<unsigned char>(scheme[0])) &&
        scheme.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789+-.") ==
            std::string_view::npos;
    if (is_scheme && written.find('/') > colon)
      throw ReferenceError(shown + " is a '" + std::string(scheme) + ":' URI, which lamina does not follow",
                           relative_hint);
  }
  const fs::path folder = absolute_normal(naming_file).parent_path();
  ref.path = (folder / fs::path(std::string(written))).lexically_normal();

  std::vector<fs::path> allowed;
  if (scope == ReferenceScope::NamingFolder) {
    allowed.push_back(folder);
  } else {
    for (const auto& root : policy.roots) allowed.push_back(absolute_normal(root));
    if (allowed.empty()) allowed.push_back(folder);
  }
  auto where = [&] {
    std::string list;
    for (size_t i = 0; i < allowed.size(); ++i) list += (i ? ", " : "") + allowed[i].string();
    return list;
  };
  const std::string outside_hint =
      scope == ReferenceScope::NamingFolder
          ? "a glTF file's buffers and images must lie in its folder or below it"
          : "keep referenced files inside the folder of the file given to lamina, or widen it with --asset-root DIR";
  // Lexically first, before the file system is asked anything about the path.
  bool lexically_inside = false;
  for (const auto& a : allowed) lexically_inside = lexically_inside || is_inside(ref.path, a);
  if (!lexically_inside)
    throw ReferenceError(shown + " leads outside the folders lamina reads from (" + where() + ")", outside_hint);

  if (policy.overlay && policy.overlay->count(ref.path)) {
    ref.resolved = ref.path;
    ref.in_memory = true;
    return ref;
  }
  if (policy.overlay_only)
    throw ReferenceError(shown + " not found (looked for " + ref.path.string() + ")",
                         "paths are relative to the folder of the file that names them");
  std::error_code ec;
  ref.resolved = fs::canonical(ref.path, ec);
  if (ec == std::errc::no_such_file_or_directory)
    throw ReferenceError(shown + " not found (looked for " + ref.path.string() + ")",
                         "paths are relative to the folder of the file that names them");
  if (ec) throw ReferenceError(shown + " cannot be followed (" + ref.path.string() + "): " + ec.message(), "");
  // Then with symbolic links resolved, in the named folders and in what they are links to.
  bool inside = false;
  for (const auto& a : allowed) {
    std::error_code canonical_ec;
    const fs::path real = fs::canonical(a, canonical_ec);
    inside = inside || is_inside(ref.resolved, canonical_ec ? a : real);
  }
  if (!inside)
    throw ReferenceError(shown + " passes through a symbolic link to " + ref.resolved.string() +
                             ", outside the folders lamina reads from (" + where() + ")",
                         outside_hint);
  return ref;
}

std::string read_reference(const Reference& reference, std::uint64_t max_bytes, const AssetPolicy& policy) {
  const std::string shown = quote_excerpt(reference.written, '\'');
  auto too_large = [&](std::uint64_t size) {
    return ReferenceError(shown + " is " + std::to_string(size) + " bytes, " + too_large_message(max_bytes), "");
  };
  if (reference.in_memory) {
    const std::string& bytes = policy.overlay->at(reference.resolved);
    if (bytes.size() > max_bytes) throw too_large(bytes.size());
    return bytes;
  }
  // Non-blocking, so that opening a FIFO does not wait for a writer; no link is followed, since
  // the resolved path has none left.
  const Descriptor fd(::open(reference.resolved.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY | O_NOFOLLOW));
  if (fd.get() < 0)
    throw ReferenceError(shown + " cannot be opened (" + reference.resolved.string() + "): " + system_reason(errno),
                         "");
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw ReferenceError(shown + " cannot be read: " + system_reason(errno), "");
  if (!S_ISREG(st.st_mode))
    throw ReferenceError(shown + " is " + kind_of(st.st_mode) + ", not a regular file",
                         "lamina reads only regular files");
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) throw too_large(static_cast<std::uint64_t>(st.st_size));
  std::string bytes;
  bool over = false;
  if (!read_all(fd.get(), max_bytes, static_cast<std::uint64_t>(st.st_size), bytes, over))
    throw ReferenceError(shown + " cannot be read: " + system_reason(errno), "");
  if (over) throw ReferenceError(shown + " grew while it was read, beyond " + byte_size_text(max_bytes), "");
  ledger().add(st);
  return bytes;
}

bool is_input_file(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  return ledger().contains(st);
}

}  // namespace lamina
