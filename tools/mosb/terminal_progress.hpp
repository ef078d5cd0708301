// Draws the library's Progress reports on stderr, only when stderr is a terminal: one line per
// stage, rewritten in place (at most ~10 times a second), ended when the stage finishes or
// changes or the display goes out of scope, so a message printed afterwards starts on its own line.
#pragma once

#include <chrono>
#include <mutex>
#include <string>
#include <string_view>

#include "mosb/progress.hpp"

namespace mosb::cli {

class TerminalProgress {
 public:
  TerminalProgress();  // enabled when stderr is a terminal
  ~TerminalProgress();
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  // Empty when stderr is not a terminal, so the library does not even count.
  Progress callback();
  // The same for stages that count bytes: megabytes, the rate since the stage began and the time
  // left at that rate.
  Progress bytes_callback();
  // Text drawn after the figures of a bytes stage from its next update on (say, files done).
  void set_suffix(std::string suffix);

 private:
  void update(std::string_view stage, std::uint64_t done, std::uint64_t total);
  void end_line();

  bool enabled_;
  bool bytes_ = false;
  std::chrono::steady_clock::time_point stage_start_{};
  std::string suffix_;
  std::mutex mutex_;
  std::string stage_;
  bool line_open_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace mosb::cli
