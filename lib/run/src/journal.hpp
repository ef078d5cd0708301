// The journal of a run (spec/RUN.md §6): OUTPUT.journal, one JSON object per line, each with its
// own checksum (`check`: XXH3-64 of the line's object without it), so a hand edit or a torn
// write is detected, never believed. Line 1 is the binding and the solver executable's SHA-256;
// every other line is one finished query, written whole by one write, or (with
// --allow-new-executable) the SHA-256 of a new executable. A record is fsync'd by sync(), while
// the next query runs, and when the journal closes: a killed run loses none (they are in the page
// cache), a machine that fails only those of the queries that had just ended. A last line without
// its newline is a record torn by a kill: ignored and cut off before the next append.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mosb/run.hpp"

namespace mosb::run_internal {

// What a run asks of a journal it continues: every record's problem (a query outside the run, a
// status its front or statistics do not fit, a value the solution file cannot hold), or nullopt.
using RecordCheck = std::function<std::optional<std::string>(const QueryRecord&)>;

struct JournalBinding {
  nlohmann::json settings;        // instance, view, objectives, query set, solver, limits, ...
  std::string executable_sha256;  // the solver executable's SHA-256 (empty: not computed)
  bool allow_new_executable = false;
};

class Journal {
 public:
  // Creates `path` holding `binding`; or, with `resume`, reads an existing journal and checks
  // every line before anything runs: checksums, the binding (one with other settings is refused;
  // another executable unless binding.allow_new_executable), and every record (well-formed,
  // `check` passes, one per query). Without `resume` an existing journal is refused. Refusals are
  // mosb::Error (invalid_argument) naming the journal and the line.
  Journal(std::string path, const JournalBinding& binding, bool resume, const RecordCheck& check);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  const std::map<std::uint64_t, QueryRecord>& records() const { return records_; }
  // The executables' SHA-256 in the order the journal recorded them (one, unless a run continued
  // with --allow-new-executable).
  const std::vector<std::string>& executables() const { return executables_; }
  void append(const QueryRecord& record);  // thread-safe
  // Makes the records appended so far durable (fsync), off the path from one query to the next:
  // a job calls it while its next solver runs. Thread-safe; a failure is thrown by the next append.
  void sync() noexcept;
  void remove();

 private:
  void read_existing(const JournalBinding& binding, const RecordCheck& check);
  void write_line(nlohmann::json line);  // with its checksum

  std::string path_;
  int fd_ = -1;
  std::atomic<bool> unsynced_{false};  // a record was written since the last fsync
  std::atomic<int> sync_error_{0};     // errno of a failed fsync
  std::mutex mutex_;
  std::map<std::uint64_t, QueryRecord> records_;
  std::vector<std::string> executables_;
};

nlohmann::json to_json(const QueryRecord& record);
// Throws mosb::Error naming what is malformed (a wrong type, a count that is not an unsigned
// integer, an unknown status, not-run).
QueryRecord record_from_json(const nlohmann::json& j);

}  // namespace mosb::run_internal
