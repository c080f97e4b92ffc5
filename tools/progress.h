// Progress on stderr for the commands: only on a terminal and only once the
// work has taken over a second; the line is cleared when done, so nothing
// of it stays in a terminal's scrollback or reaches a redirected stderr.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace dbss::tools {

class Progress {
 public:
  explicit Progress(const char* command)
      : command_(command), start_(std::chrono::steady_clock::now()), tty_(::isatty(2) == 1) {}
  ~Progress() { done(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void show(const std::string& what) {
    if (!tty_ || std::chrono::steady_clock::now() - start_ < std::chrono::seconds(1)) return;
    std::fprintf(stderr, "\r\033[K%s: %s...", command_, what.c_str());
    std::fflush(stderr);
    shown_ = true;
  }
  // Clears the line; nothing more is shown after.
  void done() {
    if (shown_) std::fputs("\r\033[K", stderr);
    shown_ = false;
    tty_ = false;
  }

 private:
  const char* command_;
  std::chrono::steady_clock::time_point start_;
  bool tty_, shown_ = false;
};

}  // namespace dbss::tools
