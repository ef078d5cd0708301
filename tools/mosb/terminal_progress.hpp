// Draws the library's Progress reports on stderr, only when stderr is a terminal: one line per
// stage, rewritten in place (at most ~10 times a second), ended when the stage finishes or
// changes or the display goes out of scope, so a message printed afterwards starts on its own line.
// `mosb run` draws its RunProgress on the same line, at most ~5 times a second.
#pragma once

#include <chrono>
#include <mutex>
#include <string>
#include <string_view>

#include "mosb/experiment.hpp"
#include "mosb/progress.hpp"
#include "mosb/run.hpp"

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

  // Redraws "done/total, status counts, ETA" of a run; the line stays open at the end (end_line).
  void update(const RunProgress& p);
  // Redraws "cells a/b, queries c/d, status counts, ETA, the running cell" of an experiment.
  void update(const ExperimentProgress& p);
  // Ends an open line, so that what is printed next starts on a line of its own.
  void end_line();

 private:
  void update(std::string_view stage, std::uint64_t done, std::uint64_t total);
  // The line of both: PREFIX done/total, the counts but not-run, the ETA from this invocation's
  // rate, then `running` while queries remain.
  void draw_queries(const std::string& prefix, StatusCounts counts, std::uint64_t done,
                    std::uint64_t total, std::uint64_t done_here, double elapsed_seconds,
                    const std::string& running);

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
