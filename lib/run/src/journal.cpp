#include "journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "mosb/checksum.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/read_file.hpp"

namespace mosb::run_internal {

namespace {

// 2: every line carries a checksum, line 1 the executable's SHA-256 (version 1 had neither).
constexpr int kJournalVersion = 2;

[[noreturn]] void io_error(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::io, path + ": " + what + ": " + std::strerror(errno));
}

void write_all(int fd, const std::string& text, const std::string& path) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) io_error(path, "cannot write");
    done += static_cast<std::size_t>(n);
  }
}

// The first key whose value differs between two bindings, for the refusal.
std::string first_difference(const nlohmann::json& recorded, const nlohmann::json& now) {
  for (const auto& [key, value] : now.items())
    if (!recorded.contains(key) || recorded[key] != value)
      return key + " " + (recorded.contains(key) ? recorded[key].dump() : "(none)") + ", not " +
             value.dump();
  return "different settings";
}

}  // namespace

nlohmann::json to_json(const QueryRecord& r) {
  nlohmann::json j;
  j["query"] = r.query;
  j["status"] = std::string(to_string(r.status));
  j["front"] = r.costs;
  j["wall_seconds"] = r.wall_seconds;
  j["cpu_seconds"] = r.cpu_seconds;
  if (r.peak_memory_bytes) j["peak_memory_bytes"] = *r.peak_memory_bytes;
  const auto& s = r.statistics;
  nlohmann::json stats = nlohmann::json::object();
  if (s.runtime_seconds) stats["runtime_seconds"] = *s.runtime_seconds;
  if (s.expanded) stats["expanded"] = *s.expanded;
  if (s.generated) stats["generated"] = *s.generated;
  if (s.peak_memory_bytes) stats["peak_memory_bytes"] = *s.peak_memory_bytes;
  if (s.exit_status) stats["exit_status"] = *s.exit_status;
  if (s.reported_runtime_seconds) stats["reported_runtime_seconds"] = *s.reported_runtime_seconds;
  j["statistics"] = stats;
  if (!r.message.empty()) j["message"] = r.message;
  if (!r.stderr_tail.empty()) j["stderr_tail"] = r.stderr_tail;
  return j;
}

namespace {

using Json = nlohmann::json;

// The line's checksum: XXH3-64 of the object (without `check`) as the journal writes it.
std::string checksum_of(const Json& object) {
  const std::string text = object.dump(-1, ' ', false, Json::error_handler_t::replace);
  return hex64(xxh3_64(text.data(), text.size()));
}

[[noreturn]] void malformed(const std::string& what) {
  throw Error(ErrorCode::invalid_argument, what);
}

const Json& member(const Json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) malformed(std::string("no '") + key + "'");
  return *it;
}

// A count: a JSON unsigned integer (1e30, 2.7 and -1 are not).
std::uint64_t count_of(const Json& value, const char* key) {
  if (!value.is_number_unsigned())
    malformed(std::string("'") + key + "' is not an unsigned integer");
  return value.get<std::uint64_t>();
}

double number_of(const Json& value, const char* key) {
  if (!value.is_number()) malformed(std::string("'") + key + "' is not a number");
  return value.get<double>();
}

std::string string_of(const Json& value, const char* key) {
  if (!value.is_string()) malformed(std::string("'") + key + "' is not a string");
  return value.get<std::string>();
}

void read_statistics(const Json& s, QueryStatistics& out) {
  if (!s.is_object()) malformed("'statistics' is not an object");
  for (const auto& [key, value] : s.items()) {
    const auto statistic = kStatisticNames.parse(key);
    if (!statistic) malformed("'statistics' has no statistic '" + key + "'");
    switch (*statistic) {
      case Statistic::runtime_seconds:
        out.runtime_seconds = number_of(value, "runtime_seconds");
        break;
      case Statistic::reported_runtime_seconds:
        out.reported_runtime_seconds = number_of(value, "reported_runtime_seconds");
        break;
      case Statistic::expanded:
        out.expanded = count_of(value, "expanded");
        break;
      case Statistic::generated:
        out.generated = count_of(value, "generated");
        break;
      case Statistic::peak_memory_bytes:
        out.peak_memory_bytes = count_of(value, "peak_memory_bytes");
        break;
      case Statistic::exit_status:
        out.exit_status = count_of(value, "exit_status");
        break;
    }
  }
}

}  // namespace

QueryRecord record_from_json(const Json& j) {
  if (!j.is_object()) malformed("not a JSON object");
  QueryRecord r;
  r.query = count_of(member(j, "query"), "query");
  const auto status = parse_query_status(string_of(member(j, "status"), "status"));
  if (!status) malformed("'status' is no status");
  if (*status == QueryStatus::not_run) malformed("a record of a query that did not run");
  r.status = *status;
  const Json& front = member(j, "front");
  if (!front.is_array()) malformed("'front' is not an array");
  r.costs.reserve(front.size());
  for (const auto& value : front) r.costs.push_back(number_of(value, "front"));
  r.wall_seconds = number_of(member(j, "wall_seconds"), "wall_seconds");
  r.cpu_seconds = number_of(member(j, "cpu_seconds"), "cpu_seconds");
  if (j.contains("peak_memory_bytes"))
    r.peak_memory_bytes = count_of(j["peak_memory_bytes"], "peak_memory_bytes");
  read_statistics(member(j, "statistics"), r.statistics);
  if (j.contains("message")) r.message = string_of(j["message"], "message");
  if (j.contains("stderr_tail")) {
    if (!j["stderr_tail"].is_array()) malformed("'stderr_tail' is not an array");
    for (const auto& line : j["stderr_tail"])
      r.stderr_tail.push_back(string_of(line, "stderr_tail"));
  }
  return r;
}

Journal::Journal(std::string path, const JournalBinding& binding, bool resume,
                 const RecordCheck& check)
    : path_(std::move(path)) {
  struct stat st {};
  const bool exists = ::stat(path_.c_str(), &st) == 0;
  if (exists && !resume)
    throw Error(ErrorCode::invalid_argument,
                {path_ + ": a journal of an earlier run exists; continue it with ",
                 setting("resume"), " or remove it"});
  if (exists) {
    read_existing(binding, check);
    return;
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) io_error(path_, "cannot create the journal");
  executables_ = {binding.executable_sha256};
  write_line({{"journal", "mosb-run"},
              {"version", kJournalVersion},
              {"binding", binding.settings},
              {"executable_sha256", binding.executable_sha256}});
  if (::fsync(fd_) != 0) io_error(path_, "cannot sync");
}

namespace {

// Line 1: a journal of this version and of this run, and whether its executable is this one.
void check_head(const Json& head, const JournalBinding& binding, bool& new_executable) {
  if (!head.is_object() || head.value("journal", "") != "mosb-run" || !head.contains("binding"))
    malformed("not a mosb run journal");
  if (head.value("version", 0) != kJournalVersion)
    malformed("a journal of another version of mosb run (" + head.value("version", Json()).dump() +
              ", this one writes " + std::to_string(kJournalVersion) +
              "): it cannot be checked; remove it and run again");
  if (head["binding"] != binding.settings)
    throw Error(ErrorCode::invalid_argument,
                {setting("resume"), ": the journal is of another run (" +
                                        first_difference(head["binding"], binding.settings) +
                                        "); rerun with its settings or remove it"});
  const std::string recorded = string_of(member(head, "executable_sha256"), "executable_sha256");
  new_executable = recorded != binding.executable_sha256;
}

}  // namespace

void Journal::read_existing(const JournalBinding& binding, const RecordCheck& check) {
  const std::string text = read_whole_file(path_);
  std::size_t pos = 0, line = 0, complete = 0;
  std::map<std::uint64_t, std::size_t> line_of;  // query -> its record's line
  while (pos < text.size()) {
    const std::size_t newline = text.find('\n', pos);
    if (newline == std::string::npos) break;  // torn last record: ignored, cut below
    ++line;
    try {
      Json j = Json::parse(text.substr(pos, newline - pos));
      if (!j.is_object() || !j.contains("check") || !j["check"].is_string())
        malformed("no checksum: not a line mosb run wrote");
      const std::string stored = j["check"].get<std::string>();
      j.erase("check");
      if (checksum_of(j) != stored)
        malformed("its checksum does not match: the line was changed after mosb run wrote it");
      if (line == 1) {
        bool new_executable = false;
        check_head(j, binding, new_executable);
        executables_ = {j["executable_sha256"].get<std::string>()};
      } else if (j.contains("executable_sha256")) {
        executables_.push_back(string_of(j["executable_sha256"], "executable_sha256"));
      } else {
        auto record = record_from_json(j);
        if (const auto earlier = line_of.find(record.query); earlier != line_of.end())
          malformed("a second record of query " + std::to_string(record.query) + " (line " +
                    std::to_string(earlier->second) + " has the first)");
        if (auto problem = check(record))
          malformed("query " + std::to_string(record.query) + ": " + *problem);
        line_of[record.query] = line;
        records_[record.query] = std::move(record);
      }
    } catch (const Json::exception& e) {
      throw Error(ErrorCode::invalid_argument,
                  path_ + ":" + std::to_string(line) + ": not a journal line (" + e.what() + ")");
    } catch (const Error& e) {
      throw e.with_context(path_ + ":" + std::to_string(line) + ": ");
    }
    pos = newline + 1;
    complete = pos;
  }
  if (line == 0) throw Error(ErrorCode::invalid_argument, path_ + ": empty journal; remove it");
  const bool new_executable = executables_.back() != binding.executable_sha256;
  if (new_executable && !binding.allow_new_executable)
    throw Error(ErrorCode::invalid_argument,
                {path_ + ": ", setting("resume"),
                 ": the solver's executable changed (SHA-256 " + executables_.back() +
                     " recorded, " + binding.executable_sha256 +
                     " now): the file would mix two programs' fronts; rerun with ",
                 setting("allow_new_executable"), " to record both, or remove the journal"});
  if (::truncate(path_.c_str(), static_cast<off_t>(complete)) != 0)
    io_error(path_, "cannot cut the torn last record");
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) io_error(path_, "cannot open the journal");
  if (new_executable) {
    executables_.push_back(binding.executable_sha256);
    write_line({{"executable_sha256", binding.executable_sha256}});
    if (::fsync(fd_) != 0) io_error(path_, "cannot sync");
  }
}

Journal::~Journal() {
  if (fd_ < 0) return;
  sync();
  ::close(fd_);
}

void Journal::write_line(Json line) {
  line["check"] = checksum_of(line);
  write_all(fd_, line.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n", path_);
}

void Journal::append(const QueryRecord& record) {
  std::lock_guard lock(mutex_);
  if (const int error = sync_error_.load(); error != 0) {
    errno = error;
    io_error(path_, "cannot sync");
  }
  write_line(to_json(record));
  unsynced_ = true;
  records_[record.query] = record;
}

void Journal::sync() noexcept {
  if (unsynced_.exchange(false) && ::fsync(fd_) != 0) sync_error_ = errno;
}

void Journal::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(path_.c_str());
}

}  // namespace mosb::run_internal

namespace mosb {

std::uint64_t journaled_queries(const std::string& journal) {
  std::error_code ec;
  if (!std::filesystem::exists(journal, ec)) return 0;
  const std::string text = read_whole_file(journal);
  std::uint64_t records = 0;
  std::size_t pos = text.find('\n');  // line 1 is the binding
  while (pos != std::string::npos && pos + 1 < text.size()) {
    const std::size_t begin = pos + 1;
    pos = text.find('\n', begin);
    if (pos == std::string::npos) break;  // torn
    const auto line =
        nlohmann::json::parse(text.begin() + static_cast<std::ptrdiff_t>(begin),
                              text.begin() + static_cast<std::ptrdiff_t>(pos), nullptr, false);
    records += line.is_object() && line.contains("query");
  }
  return records;
}

}  // namespace mosb
