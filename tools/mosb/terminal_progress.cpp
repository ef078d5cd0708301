#include "terminal_progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <utility>

#include "commands.hpp"
#include "mosb/internal/utf8.hpp"

namespace mosb::cli {

TerminalProgress::TerminalProgress() : enabled_(::isatty(STDERR_FILENO) == 1) {}

TerminalProgress::~TerminalProgress() {
  end_line();
}

Progress TerminalProgress::callback() {
  if (!enabled_) return {};
  return [this](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    update(stage, done, total);
  };
}

Progress TerminalProgress::bytes_callback() {
  bytes_ = true;
  return callback();
}

void TerminalProgress::set_suffix(std::string suffix) {
  std::lock_guard lock(mutex_);
  suffix_ = std::move(suffix);
}

void TerminalProgress::update(std::string_view stage, std::uint64_t done, std::uint64_t total) {
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  const bool new_stage = stage != stage_;
  const bool finished = total != 0 && done >= total;
  if (!new_stage && !finished && now - last_draw_ < std::chrono::milliseconds(100)) return;
  if (new_stage && line_open_) std::fputc('\n', stderr);
  if (new_stage) stage_start_ = now;
  stage_ = stage;
  last_draw_ = now;
  // "\r" and erase-to-end-of-line redraw the same line.
  if (bytes_) {
    const double seconds = std::chrono::duration<double>(now - stage_start_).count();
    const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0;
    std::fprintf(stderr, "\r\033[Kmosb: %.*s %.1f/%.1f MB (%.0f%%), %.1f MB/s",
                 static_cast<int>(stage.size()), stage.data(), static_cast<double>(done) / 1e6,
                 static_cast<double>(total) / 1e6,
                 total != 0 ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 0.0,
                 rate / 1e6);
    if (rate > 0 && total > done)
      std::fprintf(stderr, ", %.0f s left", static_cast<double>(total - done) / rate);
    std::fputs(suffix_.c_str(), stderr);
  } else if (total != 0)
    std::fprintf(stderr, "\r\033[Kmosb: %.*s %llu/%llu (%.0f%%)", static_cast<int>(stage.size()),
                 stage.data(), static_cast<unsigned long long>(done),
                 static_cast<unsigned long long>(total),
                 100.0 * static_cast<double>(done) / static_cast<double>(total));
  else
    std::fprintf(stderr, "\r\033[Kmosb: %.*s %llu", static_cast<int>(stage.size()), stage.data(),
                 static_cast<unsigned long long>(done));
  line_open_ = !finished;  // a finished stage keeps its line, so a report on stdout follows cleanly
  if (finished) std::fputc('\n', stderr);
  std::fflush(stderr);
}

void TerminalProgress::update(const RunProgress& p) {
  draw_queries("", p.counts, p.done, p.total, p.done_here, p.elapsed_seconds, "");
}

void TerminalProgress::update(const ExperimentProgress& p) {
  draw_queries(
      "cells " + std::to_string(p.cells_done) + "/" + std::to_string(p.cells_total) + ", queries ",
      p.counts, p.queries_done, p.queries_total, p.queries_done_here, p.elapsed_seconds,
      p.cell.empty() ? "" : " (" + escape_for_terminal(p.cell) + ")");
}

void TerminalProgress::draw_queries(const std::string& prefix, StatusCounts counts,
                                    std::uint64_t done, std::uint64_t total,
                                    std::uint64_t done_here, double elapsed_seconds,
                                    const std::string& running) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (done != total && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  std::string line = "\r" + prefix + std::to_string(done) + "/" + std::to_string(total);
  counts[QueryStatus::not_run] = 0;  // not yet run: the rest
  if (const auto text = status_counts_text(counts, true); !text.empty()) line += ", " + text;
  if (done_here != 0 && done < total)
    line += ", ETA " +
            std::to_string(static_cast<long>(elapsed_seconds / static_cast<double>(done_here) *
                                             static_cast<double>(total - done))) +
            " s";
  if (done < total) line += running;
  line += "\x1b[K";  // erase what a longer line before left
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
  line_open_ = true;
}

void TerminalProgress::end_line() {
  std::lock_guard lock(mutex_);
  if (line_open_) std::fputc('\n', stderr);
  line_open_ = false;
}

}  // namespace mosb::cli
