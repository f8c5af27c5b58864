#include "tools/output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <iostream>
#include <optional>
#include <random>

#include "graph/file_access.h"
#include "tools/commands.h"

namespace lamina::cli {

namespace fs = std::filesystem;

namespace {

struct Target {
  fs::path requested;    // as the command line named it
  fs::path destination;  // symbolic links followed
  bool exists = false;
  bool special = false;  // a device, FIFO or socket: written in place
  mode_t mode = 0;
  fs::path temporary, backup;
  bool renamed = false;
};

// The file a path finally names: symbolic links followed, as open() would (a dangling link names
// its target, which the write creates).
std::optional<fs::path> follow_links(const fs::path& path, int& error) {
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::error_code ec;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) {
      error = ec.value();
      return std::nullopt;
    }
    p = (link.is_absolute() ? link : p.parent_path() / link).lexically_normal();
  }
  error = ELOOP;
  return std::nullopt;
}

// A name in `folder` that no file has: ".NAME.lamina-XXXXXX" (hidden, and never a user's OUT.tmp).
std::string unique_suffix() {
  static std::mt19937_64 random{std::random_device{}()};
  static const char digits[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string s;
  for (int i = 0; i < 8; ++i) s += digits[random() % 36];
  return s;
}

bool write_all(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    done += size_t(n);
  }
  return true;
}

mode_t new_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

int failed(const Target& t, int error) {
  print_problem("cannot write " + t.requested.string() + ": " + system_reason(error));
  return kExitIo;
}

// Takes back what the renames did: previous files restored, new ones removed; temporaries and
// backups removed.
void roll_back(std::vector<Target>& targets) {
  for (Target& t : targets) {
    if (t.renamed) {
      if (!t.backup.empty())
        ::rename(t.backup.c_str(), t.destination.c_str());
      else
        ::unlink(t.destination.c_str());
    } else if (!t.backup.empty()) {
      ::unlink(t.backup.c_str());
    }
    if (!t.temporary.empty() && !t.renamed) ::unlink(t.temporary.c_str());
  }
}

// The check phase of write_outputs: every target resolved, and refused (kExitInvalid, nothing
// written) when it is a directory, an input of this command, or named twice.
int resolve_targets(const std::vector<fs::path>& paths, std::vector<Target>& targets) {
  for (const fs::path& path : paths) {
    Target t;
    t.requested = path;
    int error = 0;
    const auto destination = follow_links(path, error);
    if (!destination) return failed(t, error);
    t.destination = *destination;
    struct stat st {};
    if (::stat(t.destination.c_str(), &st) == 0) {
      t.exists = true;
      t.mode = st.st_mode & 07777;
      if (S_ISDIR(st.st_mode)) {
        print_problem(t.requested.string() + " is a directory; name the file to write");
        return kExitInvalid;
      }
      t.special = !S_ISREG(st.st_mode);
      if (is_input_file(t.destination)) {
        print_problem(t.requested.string() + " is also an input of this command; refusing to replace it");
        return kExitInvalid;
      }
      for (const Target& other : targets) {
        struct stat so {};
        if (::stat(other.destination.c_str(), &so) == 0 && so.st_dev == st.st_dev && so.st_ino == st.st_ino) {
          print_problem(t.requested.string() + " and " + other.requested.string() + " are the same file");
          return kExitInvalid;
        }
      }
    } else if (errno != ENOENT) {
      return failed(t, errno);
    }
    for (const Target& other : targets)
      if (fs::absolute(other.destination).lexically_normal() == fs::absolute(t.destination).lexically_normal()) {
        print_problem(t.requested.string() + " and " + other.requested.string() + " are the same file");
        return kExitInvalid;
      }
    if (!t.exists) t.mode = new_file_mode();
    targets.push_back(std::move(t));
  }
  return kExitOk;
}

}  // namespace

int check_outputs(const std::vector<fs::path>& paths) {
  std::vector<Target> targets;
  return resolve_targets(paths, targets);
}

int write_outputs(const std::vector<OutputFile>& files) {
  std::vector<fs::path> paths;
  for (const OutputFile& f : files) paths.push_back(f.path);
  std::vector<Target> targets;
  // First every check, before anything is written.
  if (int code = resolve_targets(paths, targets); code != kExitOk) return code;

  // Then each regular file's content, beside its destination.
  for (size_t i = 0; i < targets.size(); ++i) {
    Target& t = targets[i];
    if (t.special) continue;
    const fs::path folder = t.destination.has_parent_path() ? t.destination.parent_path() : fs::path(".");
    const std::string name = "." + t.destination.filename().string() + ".lamina-";
    int fd = -1;
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
      t.temporary = folder / (name + unique_suffix());
      fd = ::open(t.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600);
      if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0) {
      const int error = errno;
      t.temporary.clear();
      roll_back(targets);
      return failed(t, error);
    }
    const bool ok = write_all(fd, files[i].text) && ::fchmod(fd, t.mode) == 0 && ::fsync(fd) == 0;
    const int error = errno;
    if (::close(fd) != 0 || !ok) {
      roll_back(targets);
      return failed(t, ok ? errno : error);
    }
  }

  // Every previous file kept as a hard link, then the renames in order.
  for (Target& t : targets) {
    if (t.special || !t.exists) continue;
    for (int attempt = 0; attempt < 100; ++attempt) {
      const fs::path backup = t.destination.parent_path() /
                              ("." + t.destination.filename().string() + ".lamina-previous-" + unique_suffix());
      if (::link(t.destination.c_str(), backup.c_str()) == 0) {
        t.backup = backup;
        break;
      }
      if (errno != EEXIST) break;  // a file system without hard links: no way back for this one
    }
  }
  for (Target& t : targets) {
    if (t.special) continue;
    if (::rename(t.temporary.c_str(), t.destination.c_str()) != 0) {
      const int error = errno;
      roll_back(targets);
      return failed(t, error);
    }
    t.renamed = true;
  }

  // Devices and pipes last, in place.
  for (size_t i = 0; i < targets.size(); ++i) {
    Target& t = targets[i];
    if (!t.special) continue;
    const int fd = ::open(t.destination.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    const bool ok = fd >= 0 && write_all(fd, files[i].text);
    const int error = errno;
    if (fd >= 0 && ::close(fd) != 0 && ok) {
      roll_back(targets);
      return failed(t, errno);
    }
    if (!ok) {
      roll_back(targets);
      return failed(t, error);
    }
  }
  for (const Target& t : targets)
    if (!t.backup.empty()) ::unlink(t.backup.c_str());
  return kExitOk;
}

namespace {
int standard_output_error = 0;  // the first reason a write to standard output failed
}  // namespace

void write_standard_output(std::string_view text) {
  std::cout.flush();
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() && standard_output_error == 0)
    standard_output_error = errno;
}

int finish_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool flushed = std::fflush(stdout) == 0;
  const int error = standard_output_error != 0 ? standard_output_error : errno;
  if (!flushed || std::ferror(stdout) || !std::cout) {
    print_problem("cannot write standard output: " + (error ? system_reason(error) : std::string("write error")));
    return kExitIo;
  }
  return kExitOk;
}

}  // namespace lamina::cli
