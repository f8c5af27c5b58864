// Every file a command writes goes through write_outputs: outputs are complete or absent, files
// written together stand or fall together, an input is never replaced, and what -o names is never
// replaced by something else.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lamina::cli {

struct OutputFile {
  std::filesystem::path path;
  std::string text;
};

// Writes `files` together. Returns an exit code, after printing "lamina: ..." on failure:
//   kExitOk       every file written;
//   kExitInvalid  nothing written: a target is a directory, a file this process read as input
//                 (the same file by device and inode, however it is spelled), or named twice;
//   kExitIo       nothing changed: a write, sync or rename failed (with the system's reason), and
//                 the files already put in place were taken back, their previous content restored.
// How: each regular (or new) target gets a uniquely named temporary file in its own folder (a
// user's OUT.tmp is never touched), written, synced and given the target's mode (new files: 0666
// less the umask); a target that existed is kept as a hard link until every rename succeeded. A
// symbolic link is written through: its final target is replaced, the link stays. A character
// device, FIFO or socket (/dev/null, a pipe) is written in place, last, and cannot be taken back.
int write_outputs(const std::vector<OutputFile>& files);

// write_outputs' checks alone, for a command to run once its inputs are read and before its long
// work (a figure, a fit), so that a refused output fails at once; write_outputs checks again.
int check_outputs(const std::vector<std::filesystem::path>& paths);

// Writes a command's result (a GLSL module for `-o -`) to standard output, remembering the
// system's reason when it does not arrive.
void write_standard_output(std::string_view text);

// Standard output flushed and checked: a command that printed its result exits 0 only when the
// result arrived (`> /dev/full` is an I/O error, exit 1, with the system's reason).
int finish_standard_output();

}  // namespace lamina::cli
