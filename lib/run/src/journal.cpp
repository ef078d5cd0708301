#include "journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "mosb/error.hpp"
#include "mosb/internal/read_file.hpp"

namespace mosb::run_internal {

namespace {

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
  if (::fsync(fd) != 0) io_error(path, "cannot sync");
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

QueryRecord record_from_json(const nlohmann::json& j) {
  QueryRecord r;
  r.query = j.at("query").get<std::uint64_t>();
  const auto status = parse_query_status(j.at("status").get<std::string>());
  if (!status) throw Error("unknown status");
  r.status = *status;
  r.costs = j.at("front").get<std::vector<double>>();
  r.wall_seconds = j.at("wall_seconds").get<double>();
  r.cpu_seconds = j.at("cpu_seconds").get<double>();
  if (j.contains("peak_memory_bytes"))
    r.peak_memory_bytes = j["peak_memory_bytes"].get<std::uint64_t>();
  const auto& s = j.at("statistics");
  if (s.contains("runtime_seconds"))
    r.statistics.runtime_seconds = s["runtime_seconds"].get<double>();
  if (s.contains("expanded")) r.statistics.expanded = s["expanded"].get<std::uint64_t>();
  if (s.contains("generated")) r.statistics.generated = s["generated"].get<std::uint64_t>();
  if (s.contains("peak_memory_bytes"))
    r.statistics.peak_memory_bytes = s["peak_memory_bytes"].get<std::uint64_t>();
  if (s.contains("exit_status")) r.statistics.exit_status = s["exit_status"].get<std::uint64_t>();
  if (s.contains("reported_runtime_seconds"))
    r.statistics.reported_runtime_seconds = s["reported_runtime_seconds"].get<double>();
  r.message = j.value("message", std::string());
  if (j.contains("stderr_tail")) r.stderr_tail = j["stderr_tail"].get<std::vector<std::string>>();
  return r;
}

Journal::Journal(std::string path, const nlohmann::json& binding, bool resume)
    : path_(std::move(path)) {
  struct stat st {};
  const bool exists = ::stat(path_.c_str(), &st) == 0;
  if (exists && !resume)
    throw Error(ErrorCode::invalid_argument,
                path_ +
                    ": a journal of an earlier run exists; continue it with --resume or "
                    "remove it");
  if (exists) {
    read_existing(binding);
    return;
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) io_error(path_, "cannot create the journal");
  nlohmann::json head = {{"journal", "mosb-run"}, {"version", 1}, {"binding", binding}};
  write_all(fd_, head.dump() + "\n", path_);
}

void Journal::read_existing(const nlohmann::json& binding) {
  const std::string text = read_whole_file(path_);
  std::size_t pos = 0, line = 0, complete = 0;
  while (pos < text.size()) {
    const std::size_t newline = text.find('\n', pos);
    if (newline == std::string::npos) break;  // torn last record: ignored, cut below
    ++line;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text.substr(pos, newline - pos));
      if (line == 1) {
        if (j.value("journal", "") != "mosb-run" || !j.contains("binding"))
          throw Error("not a mosb run journal");
        if (j["binding"] != binding)
          throw Error(ErrorCode::invalid_argument, "--resume: the journal is of another run (" +
                                                       first_difference(j["binding"], binding) +
                                                       "); rerun with its settings or remove it");
      } else {
        auto record = record_from_json(j);
        records_[record.query] = std::move(record);
      }
    } catch (const nlohmann::json::exception& e) {
      throw Error(ErrorCode::invalid_argument,
                  path_ + ":" + std::to_string(line) + ": not a journal record (" + e.what() + ")");
    } catch (const Error& e) {
      throw Error(e.code(), path_ + ":" + std::to_string(line) + ": " + e.what());
    }
    pos = newline + 1;
    complete = pos;
  }
  if (line == 0) throw Error(ErrorCode::invalid_argument, path_ + ": empty journal; remove it");
  if (::truncate(path_.c_str(), static_cast<off_t>(complete)) != 0)
    io_error(path_, "cannot cut the torn last record");
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) io_error(path_, "cannot open the journal");
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(const QueryRecord& record) {
  const std::string line =
      to_json(record).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  std::lock_guard lock(mutex_);
  write_all(fd_, line, path_);
  records_[record.query] = record;
}

void Journal::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(path_.c_str());
}

}  // namespace mosb::run_internal
