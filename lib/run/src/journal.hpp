// The journal of a run (spec/RUN.md §5): OUTPUT.journal, one JSON object per line. Line 1 is the
// binding; every other line is one finished query, written whole, flushed and fsync'd before the
// next query is recorded. A last line without its newline is a record torn by a kill: ignored and
// cut off before the next append.
#pragma once

#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "mosb/run.hpp"

namespace mosb::run_internal {

class Journal {
 public:
  // Creates `path` holding `binding`; or, with `resume`, reads the records of an existing journal
  // (one with another binding is refused). Without `resume` an existing journal is refused.
  Journal(std::string path, const nlohmann::json& binding, bool resume);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  const std::map<std::uint64_t, QueryRecord>& records() const { return records_; }
  void append(const QueryRecord& record);  // thread-safe
  void remove();

 private:
  void read_existing(const nlohmann::json& binding);

  std::string path_;
  int fd_ = -1;
  std::mutex mutex_;
  std::map<std::uint64_t, QueryRecord> records_;
};

nlohmann::json to_json(const QueryRecord& record);
QueryRecord record_from_json(const nlohmann::json& j);  // throws nlohmann::json::exception

}  // namespace mosb::run_internal
