// A progress bar with the time left, for the commands whose work takes a while (lamina render,
// lamina preview): redrawn on one line of standard error when that is a terminal, silent otherwise.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace lamina::cli {

class Progress {
 public:
  Progress() : shown_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}
  void operator()(double done) {
    if (!shown_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int percent = int(done * 100.0);
    if (percent == last_ && done < 1.0) return;
    last_ = percent;
    const int width = 30, filled = int(done * width);
    std::string bar(size_t(filled), '#');
    bar.resize(size_t(width), '.');
    const double left = done > 0.0 ? elapsed * (1.0 - done) / done : 0.0;
    std::fprintf(stderr, "\r[%s] %3d%%  %.0f s, %.0f s left ", bar.c_str(), percent, elapsed, left);
    if (done >= 1.0) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  bool shown_;
  std::chrono::steady_clock::time_point start_;
  int last_ = -1;
};

}  // namespace lamina::cli
