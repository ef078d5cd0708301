#include "mosb/run.hpp"

#include <fcntl.h>
#include <sched.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "journal.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/command_template.hpp"
#include "mosb/error.hpp"
#include "mosb/eval.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/solution_verify.hpp"
#include "mosb/version.hpp"
#include "process.hpp"

namespace mosb {

namespace fs = std::filesystem;
using run_internal::Ending;
using run_internal::Journal;
using run_internal::ProcessOutcome;
using run_internal::ProcessRunner;
using run_internal::ProcessSpec;

namespace {

// The last `count` non-blank lines of a file (at most 4 KiB read), control characters as '?'.
std::vector<std::string> tail_lines(const std::string& path, std::size_t count) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const auto size = static_cast<std::int64_t>(in.tellg());
  const std::int64_t start = std::max<std::int64_t>(0, size - 4096);
  in.seekg(start);
  std::string text(static_cast<std::size_t>(size - start), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    for (char& c : line)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    if (line.find_first_not_of(" ?") != std::string::npos) lines.push_back(line.substr(0, 200));
  }
  if (lines.size() > count) lines.erase(lines.begin(), lines.end() - static_cast<long>(count));
  return lines;
}

// Calls consume(text) for each chunk of the solver's output file `path`, read 64 KiB at a time,
// so mosb holds a chunk of it, never the file. A file over `limit` bytes is refused unread.
template <class Consume>
void read_output(const std::string& path, const std::string& name, std::uint64_t limit,
                 Consume&& consume) {
  // Never through a link, never waiting for a FIFO's writer: query_files_problem refused both
  // already; this is the backstop.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) throw Error(ErrorCode::io, name + ": cannot read: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(name + ": not a regular file");
  }
  if (static_cast<std::uint64_t>(st.st_size) > limit) {
    ::close(fd);
    throw Error(name + ": " + std::to_string(st.st_size) + " bytes, over the output limit of " +
                std::to_string(limit) + " bytes");
  }
  std::vector<char> buffer(std::size_t{64} << 10);
  try {
    read_chunks(fd, path, buffer,
                [&](const char* data, std::size_t size) { consume(std::string_view(data, size)); });
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

}  // namespace

ParsedOutput read_protocol_output(const SolverOutputFiles& files) {
  ParsedOutput out;
  const std::string& front_file = files.front_in_file ? files.front_path : files.stdout_path;
  const std::string name = files.front_in_file ? "{front}" : "stdout";
  ProtocolFrontParser front(files.objectives, files.integer_objectives, name,
                            files.output_bytes / sizeof(double));
  read_output(front_file, name, files.output_bytes,
              [&](std::string_view chunk) { front.feed(chunk); });
  auto parsed = front.finish();
  out.costs = std::move(parsed.costs);
  out.vectors = parsed.vectors;
  ProtocolStatisticsParser statistics("stderr");
  read_output(files.stderr_path, "stderr", files.output_bytes,
              [&](std::string_view chunk) { statistics.feed(chunk); });
  out.statistics = statistics.finish();
  return out;
}

std::string journal_path(const std::string& output) {
  return output + ".journal";
}

namespace {

// What classify needs to know of the run besides the query.
struct Judging {
  const OutputAdapter& adapter;
  const SolutionWriter& writer;
  const std::vector<int>& success_exit_codes;
  bool exact = true;  // the solver claims ε = 0
  Measurement measurement = Measurement::rlimit_poll;
  const ProcessLimits& limits;
};

// What a failure under rlimit-poll may owe to the address-space backstop (spec/RUN.md §4).
std::string backstop_note(const Judging& j) {
  if (j.measurement != Measurement::rlimit_poll || j.limits.memory_bytes == 0) return {};
  return " (under rlimit-poll each process's address space is limited to twice the memory "
         "limit, " +
         std::to_string(j.limits.memory_bytes * 2) +
         " bytes: an allocation it refused may have ended the solver)";
}

// The status, statistics and reason of a solver that exited: its output read by the adapter and
// held to rule 1 of spec/RUN.md §3 (a front without duplicates, and without dominated vectors
// when exact); the solver's own statement that it did not finish is never solved.
QueryRecord judge_output(QueryRecord r, const ProcessOutcome& o, const SolverOutputFiles& files,
                         const Judging& j) {
  const auto failed = [&](std::string message) {
    r.status = QueryStatus::failed;
    r.costs.clear();
    r.statistics = {};
    r.statistics.exit_status = static_cast<std::uint64_t>(o.exit_code);
    r.message = std::move(message);
    r.stderr_tail = tail_lines(files.stderr_path, 5);
    return r;
  };
  ParsedOutput parsed;
  try {
    parsed = j.adapter(files);
  } catch (const Error& e) {
    return failed(std::string("unreadable output: ") + e.what());
  }
  if (parsed.stated_status) {
    if (*parsed.stated_status == QueryStatus::failed)
      return failed("the solver states that it failed: " + parsed.stated);
    r.status = *parsed.stated_status;  // timeout or memory-limit: no front, no statistics
    r.message = "the solver states: " + parsed.stated;
    return r;
  }
  for (std::size_t i = 0; i < parsed.costs.size(); ++i)
    if (auto problem = j.writer.cost_problem(i % files.objectives, parsed.costs[i]))
      return failed("unreadable output: vector " + std::to_string(i / files.objectives + 1) + ": " +
                    *problem);
  if (auto problem = front_problem(parsed.costs, files.objectives, j.exact))
    return failed("not a front (spec/RUN.md section 3, rule 1): " + *problem);
  r.status = parsed.vectors == 0 ? QueryStatus::disconnected : QueryStatus::solved;
  r.costs = std::move(parsed.costs);
  r.statistics.runtime_seconds = o.wall_seconds;
  r.statistics.peak_memory_bytes = o.peak_memory_bytes;
  r.statistics.expanded = parsed.statistics.expanded;
  r.statistics.generated = parsed.statistics.generated;
  r.statistics.reported_runtime_seconds = parsed.statistics.runtime_seconds;
  if (auto problem = j.writer.query_problem(r.query, r.status, r.costs, r.statistics))
    return failed("unusable output: " + *problem);
  return r;
}

// Why the files a query's processes left cannot be read safely, or empty: every entry of its
// directory must be a regular file or a directory. A FIFO would block mosb, a device or a link to
// one (/dev/zero) would never end, a link could make mosb read another file as the query's. The
// query's processes are all gone (§4), so nothing changes the directory after this look.
std::string query_files_problem(const SolverOutputFiles& files) {
  const auto directory = fs::path(files.stdout_path).parent_path();
  std::error_code ec;
  fs::recursive_directory_iterator entries(directory, ec), end;
  for (; !ec && entries != end; entries.increment(ec)) {
    const auto status = entries->symlink_status(ec);
    if (ec || fs::is_regular_file(status) || fs::is_directory(status)) continue;
    const char* kind = fs::is_symlink(status)  ? "a symbolic link"
                       : fs::is_fifo(status)   ? "a FIFO"
                       : fs::is_socket(status) ? "a socket"
                                               : "a device";
    return entries->path().lexically_relative(directory).string() + " is " + kind +
           ", not a regular file: the query's output is not read";
  }
  if (ec) return directory.string() + ": cannot list: " + ec.message();
  return {};
}

// The status and statistics of a finished solver (spec/RUN.md §4–§5).
QueryRecord classify(std::uint64_t q, const ProcessOutcome& o, const SolverOutputFiles& files,
                     const Judging& j) {
  QueryRecord r;
  r.query = q;
  r.wall_seconds = o.wall_seconds;
  r.cpu_seconds = o.cpu_seconds;
  r.peak_memory_bytes = o.peak_memory_bytes;
  const auto unsafe = query_files_problem(files);
  const auto failed = [&](std::uint64_t exit_status, std::string message) {
    r.status = QueryStatus::failed;
    r.statistics.exit_status = exit_status;
    r.message = std::move(message);
    if (unsafe.empty()) r.stderr_tail = tail_lines(files.stderr_path, 5);
    return r;
  };
  switch (o.ending) {
    case Ending::timeout:
      r.status = QueryStatus::timeout;
      return r;
    case Ending::cpu_limit:
      r.status = QueryStatus::timeout;
      r.message = "CPU time limit";
      return r;
    case Ending::memory_limit:
      r.status = QueryStatus::memory_limit;
      return r;
    case Ending::output_limit:
      return failed(128 + SIGKILL, "killed: an output file passed the output limit of " +
                                       std::to_string(j.limits.output_bytes) + " bytes");
    case Ending::not_started:
      return failed(127, o.error);
    case Ending::signaled:
      return failed(128 + static_cast<std::uint64_t>(o.signal),
                    "killed by signal " + std::to_string(o.signal) + backstop_note(j));
    case Ending::interrupted:
      return r;
    case Ending::exited:
      break;
  }
  if (std::find(j.success_exit_codes.begin(), j.success_exit_codes.end(), o.exit_code) ==
      j.success_exit_codes.end())
    return failed(static_cast<std::uint64_t>(o.exit_code),
                  "exit status " + std::to_string(o.exit_code) + backstop_note(j));
  if (!unsafe.empty()) return failed(static_cast<std::uint64_t>(o.exit_code), unsafe);
  return judge_output(std::move(r), o, files, j);
}

std::string format_seconds(double s) {
  std::ostringstream out;
  out << s;
  return out.str();
}

// The solver's program and the files its template names, as the run found them (spec/RUN.md §6,
// "Programs pinned"). A binary is opened once and every query executes that descriptor, so a
// program replaced at its path during the run changes nothing; a script (#!) runs by its path (its
// interpreter opens the path, and a script finds its siblings through $0), so it is watched
// instead, as is every regular file the template names literally (a script given to an
// interpreter, a configuration): a change during the run fails the run, naming the file.
struct WatchedFile {
  std::string path, sha256;
  struct stat found {};
};

class PinnedProgram {
 public:
  PinnedProgram() = default;
  explicit PinnedProgram(const std::string& path) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0)
      throw Error(ErrorCode::invalid_argument, path + ": cannot open: " + std::strerror(errno));
    char magic[4] = {};
    binary_ = ::pread(fd_, magic, sizeof magic, 0) == 4 && std::memcmp(magic,
                                                                       "\x7f"
                                                                       "ELF",
                                                                       4) == 0;
  }
  ~PinnedProgram() {
    if (fd_ >= 0) ::close(fd_);
  }
  PinnedProgram(PinnedProgram&& other) noexcept
      : fd_(std::exchange(other.fd_, -1)), binary_(other.binary_) {}
  PinnedProgram& operator=(PinnedProgram&& other) noexcept {
    std::swap(fd_, other.fd_);
    binary_ = other.binary_;
    return *this;
  }
  // What a query executes: the descriptor of a binary, -1 for a script (run by its path).
  int executable_fd() const { return binary_ ? fd_ : -1; }
  // The path that reads the very file opened (its digest is the pinned program's).
  std::string opened_path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_ = -1;
  bool binary_ = false;
};

WatchedFile watched_file(const std::string& path, const RunConfig& c) {
  WatchedFile file;
  file.path = path;
  if (::stat(path.c_str(), &file.found) != 0)
    throw Error(ErrorCode::invalid_argument, path + ": cannot read: " + std::strerror(errno));
  if (c.sha256_file) file.sha256 = c.sha256_file(path);
  return file;
}

// The program (when a script) and every regular file the template's words name literally.
std::vector<WatchedFile> watched_files(const std::vector<std::string>& words,
                                       const std::string& executable, bool script,
                                       const RunConfig& c) {
  std::vector<WatchedFile> out;
  if (script) out.push_back(watched_file(executable, c));
  for (std::size_t w = 1; w < words.size(); ++w) {
    struct stat st {};
    if (words[w].find('{') != std::string::npos || ::stat(words[w].c_str(), &st) != 0 ||
        !S_ISREG(st.st_mode))
      continue;
    if (std::none_of(out.begin(), out.end(),
                     [&](const WatchedFile& f) { return f.path == words[w]; }))
      out.push_back(watched_file(words[w], c));
  }
  return out;
}

// Throws naming the first watched file that is no longer what the run started with.
void check_unchanged(const std::vector<WatchedFile>& files) {
  for (const auto& file : files) {
    struct stat now {};
    const bool same = ::stat(file.path.c_str(), &now) == 0 && now.st_dev == file.found.st_dev &&
                      now.st_ino == file.found.st_ino && now.st_size == file.found.st_size &&
                      now.st_mtim.tv_sec == file.found.st_mtim.tv_sec &&
                      now.st_mtim.tv_nsec == file.found.st_mtim.tv_nsec;
    if (!same)
      throw Error(ErrorCode::invalid_argument,
                  file.path +
                      " changed during the run: its queries may come from two versions "
                      "of it, so no solution file is written (the journal is kept; "
                      "remove it to run them again)");
  }
}

// Everything fixed for the whole run.
struct Plan {
  std::string view, query_set;
  std::vector<std::string> objective_names;
  std::vector<bool> integer_objectives;
  std::vector<Query> queries;
  std::vector<std::string> words;
  bool front_in_file = false, fronts_used = false;
  std::string executable, executable_sha256;
  PinnedProgram program;
  std::vector<WatchedFile> files;
  bool exact = true;  // the solver claims ε = 0
  Measurement measurement = Measurement::rlimit_poll;
  run_internal::Isolation isolation = run_internal::Isolation::subreaper;
  Seal seal = Seal::sealed;
  std::vector<int> cpus;  // --pin: the CPUs this process may use
};

Plan make_plan(const RunConfig& c, const View& selection, const SolutionWriter& writer) {
  Plan p;
  p.view = selection.name;  // empty: bound to the objectives alone (spec/SOLUTIONS.md §2)
  p.query_set = selection.query_set;
  const auto stored = c.instance->queries(p.query_set);
  p.queries.assign(stored.begin(), stored.end());
  p.objective_names = writer.objective_names();
  for (const auto i : selection.objectives)
    p.integer_objectives.push_back(!format::is_float(c.instance->objective(i).type));
  p.exact = parse_epsilon(c.epsilon).num == 0;
  p.words = split_command(c.solver_template);
  const auto used = template_placeholders(p.words, run_placeholders());
  p.front_in_file = std::find(used.begin(), used.end(), "front") != used.end();
  p.fronts_used = std::find(used.begin(), used.end(), "fronts") != used.end();
  p.executable = template_executable(c.solver_template);
  p.program = PinnedProgram(p.executable);
  if (c.sha256_file) p.executable_sha256 = c.sha256_file(p.program.opened_path());
  p.files = watched_files(p.words, p.executable, p.program.executable_fd() < 0, c);
  p.measurement = c.measurement ? *c.measurement : run_internal::detect_measurement();
  p.isolation = run_internal::detect_isolation();
  p.seal = c.seal;
  if (p.seal == Seal::sealed)
    if (const auto refusal = run_internal::seal_refusal(); !refusal.empty())
      throw Error(ErrorCode::invalid_argument,
                  "this system cannot seal a query (a mount and network namespace: " + refusal +
                      "); run with isolation 'none' to let the solver reach the whole "
                      "filesystem and network, which the file then records");
  cpu_set_t set;
  if (::sched_getaffinity(0, sizeof set, &set) == 0)
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
      if (CPU_ISSET(cpu, &set)) p.cpus.push_back(cpu);
  return p;
}

nlohmann::json binding_of(const RunConfig& c, const Plan& p) {
  nlohmann::json binding = {{"instance_digest", c.instance->digest()},
                            {"view", p.view},
                            {"objectives", p.objective_names},
                            {"query_set", p.query_set},
                            {"queries", p.queries.size()},
                            {"solver", c.solver_template},
                            {"output_format", c.output_format},
                            {"time_limit_seconds", c.limits.wall_seconds},
                            {"cpu_limit_seconds", c.limits.cpu_seconds},
                            {"memory_limit_bytes", c.limits.memory_bytes},
                            {"output_limit_bytes", c.limits.output_bytes},
                            {"success_exit_codes", c.success_exit_codes},
                            {"epsilon", c.epsilon},
                            {"threads", c.threads}};
  if (c.shard) binding["shard"] = c.shard->text();
  if (c.id_base != 0) binding["id_base"] = c.id_base;
  if (!c.parameters.empty()) binding["parameters"] = c.parameters;
  // The files the template names: a resumed run whose script or configuration changed is refused
  // (the program itself is bound through its own digest, see --allow-new-executable).
  for (const auto& file : p.files)
    if (file.path != p.executable) binding["files"][file.path] = file.sha256;
  return binding;
}

}  // namespace

namespace {

std::string temporary_base() {
  const char* base = std::getenv("TMPDIR");
  return base && *base ? base : "/tmp";
}

// Removes the `mosb-run-PID-XXXXXX` directories that a run killed by a signal it could not catch
// (kill -9) left, once process PID is gone; only this user's (the sticky /tmp allows no more).
void sweep_temporaries() {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(temporary_base(), ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("mosb-run-")) continue;
    const long pid = std::atol(name.c_str() + 9);
    struct stat st {};
    if (pid <= 0 || ::lstat(entry.path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) ||
        st.st_uid != ::getuid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
      continue;
    fs::remove_all(entry.path(), ec);
  }
}

// A per-run temporary directory, `mosb-run-PID-XXXXXX`, removed with everything in it; one a
// killed run left is swept by the next (sweep_temporaries).
class TempDir {
 public:
  TempDir() {
    std::string pattern = temporary_base() + "/mosb-run-" + std::to_string(::getpid()) + "-XXXXXX";
    if (!::mkdtemp(pattern.data()))
      throw Error(ErrorCode::io,
                  pattern + ": cannot create a temporary directory: " + std::strerror(errno));
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class Runner {
 public:
  Runner(const RunConfig& c, const RunCallbacks& cb, const Plan& p, const SolutionWriter& w,
         Journal& j, const std::atomic<bool>& stop)
      : c_(c), cb_(cb), p_(p), writer_(w), journal_(j), stop_(stop) {
    adapter_ = c.adapter ? c.adapter : OutputAdapter(read_protocol_output);
    judging_ = std::make_unique<Judging>(
        Judging{adapter_, writer_, c.success_exit_codes, p.exact, p.measurement, c.limits});
    for (std::uint64_t q = 0; q < p.queries.size(); ++q) {
      if (c.shard && !c.shard->contains(q)) continue;
      ++progress_.total;
      const auto it = j.records().find(q);
      if (it == j.records().end())
        todo_.push_back(q);
      else
        ++progress_.counts[it->second.status];
    }
    progress_.done = progress_.total - todo_.size();
  }

  std::uint64_t pending() const { return todo_.size(); }

  // Runs the pending queries on `jobs` job slots. A query mosb itself cannot run (files, cgroup,
  // fork) ends the run: no slot starts another, and the earliest such failure is rethrown.
  void run(unsigned jobs, RunResult& result) {
    started_ = std::chrono::steady_clock::now();
    parallel_for_with_state(
        todo_.size(), jobs, [this](unsigned job) { return JobSlot(temp_.path(), job, stop_); },
        [this](JobSlot& slot, std::size_t i) {
          if (!stop_.load()) run_query(slot, todo_[i]);
        });
    result.ran = ran_;
    result.wall_seconds = wall_;
    result.cpu_seconds = cpu_;
  }

 private:
  // One of the run's --jobs: its directory for the solver's output files and its process runner,
  // made and destroyed on the slot's own thread (PR_SET_PDEATHSIG ties a solver's waiting process
  // to the thread that forked it).
  struct JobSlot {
    JobSlot(const std::string& temp, unsigned job_index, const std::atomic<bool>& stop)
        : job(job_index),
          dir(created_directory(temp + "/job" + std::to_string(job_index))),
          runner(stop) {}
    ~JobSlot() { remove_finished(); }
    JobSlot(const JobSlot&) = delete;
    JobSlot& operator=(const JobSlot&) = delete;
    static std::string created_directory(std::string path) {
      fs::create_directories(path);
      return path;
    }
    void remove_finished() {
      std::error_code ignored;
      if (!finished.empty()) fs::remove_all(finished, ignored);
      finished.clear();
    }
    unsigned job;
    std::string dir;
    ProcessRunner runner;
    // The directory of the slot's last query, read and recorded: removed while the next solver
    // runs (removing a solver's files takes longer than a small query's whole record), or when
    // the slot ends. Nothing of that query is left to write in it, and its name is never reused.
    std::string finished;
  };

  std::map<std::string, std::string> values(std::uint64_t q, const SolverOutputFiles& f) const {
    std::string objectives;
    for (const auto& name : p_.objective_names)
      objectives += (objectives.empty() ? "" : ",") + name;
    return {{"instance", c_.instance_path},
            {"view", p_.view},
            {"objectives", objectives},
            {"query", std::to_string(q)},
            {"source", std::to_string(std::uint64_t{p_.queries[q].start} + c_.id_base)},
            {"target", std::to_string(std::uint64_t{p_.queries[q].goal} + c_.id_base)},
            {"front", f.front_path},
            {"fronts", f.fronts_dir},
            {"threads", std::to_string(c_.threads)}};
  }

  // The query's own files, in a directory made for it and removed after: nothing a process of
  // another query does (one that outlived its query, had isolation failed) reaches them.
  SolverOutputFiles files_of(std::uint64_t q, const std::string& dir) const {
    SolverOutputFiles files;
    files.stdout_path = dir + "/stdout";
    files.stderr_path = dir + "/stderr";
    files.front_path = dir + "/front.txt";
    files.fronts_dir = dir + "/fronts";
    files.front_in_file = p_.front_in_file;
    files.query = p_.queries[q];
    files.objectives = p_.objective_names.size();
    files.integer_objectives = p_.integer_objectives;
    files.output_bytes = c_.limits.output_bytes;
    return files;
  }

  void run_query(JobSlot& slot, std::uint64_t q) {
    const unsigned job = slot.job;
    const std::string dir = slot.dir + "/q" + std::to_string(q);
    if (::mkdir(dir.c_str(), 0700) != 0)
      throw Error(ErrorCode::io, dir + ": cannot create: " + std::strerror(errno));
    const SolverOutputFiles files = files_of(q, dir);
    if (p_.fronts_used) fs::create_directories(files.fronts_dir);
    ProcessSpec spec;
    spec.executable = p_.executable;
    spec.executable_fd = p_.program.executable_fd();
    spec.argv = expand_command(p_.words, values(q, files));
    spec.stdout_path = files.stdout_path;
    spec.stderr_path = files.stderr_path;
    spec.watched_files = {files.stdout_path, files.stderr_path, files.front_path,
                          files.fronts_dir + "/0.txt"};
    if (c_.pin && !p_.cpus.empty()) spec.cpu = p_.cpus[job % p_.cpus.size()];
    spec.group_name = "mosb-run-" + std::to_string(::getpid()) + "-" + std::to_string(job);
    spec.isolation = p_.isolation;
    spec.seal = p_.seal;
    spec.queries_directory = slot.dir;
    spec.while_running = [this, &slot] {
      journal_.sync();
      slot.remove_finished();
    };
    const ProcessOutcome outcome = slot.runner.run(spec, c_.limits, p_.measurement);
    slot.remove_finished();  // when the solver did not start
    slot.finished = dir;
    if (outcome.ending == Ending::interrupted || stopped_with_mosb(outcome))
      return;  // no record: --resume runs it again
    const QueryRecord record = classify(q, outcome, files, *judging_);
    journal_.append(record);
    std::lock_guard lock(mutex_);
    ++ran_;
    wall_ += outcome.wall_seconds;
    cpu_ += outcome.cpu_seconds;
    ++progress_.done;
    ++progress_.done_here;
    ++progress_.counts[record.status];
    progress_.elapsed_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    if (record.status == QueryStatus::failed && cb_.failed) cb_.failed(record, p_.queries[q]);
    if (cb_.progress) cb_.progress(progress_);
  }

  // Whether a solver that a stop signal killed from outside (SIGTERM, SIGINT, SIGHUP or SIGKILL,
  // or a wrapper's exit status 128 + one of them) died with this run: a scheduler cancelling,
  // preempting or timing out a job signals every process of it, the solver possibly before
  // mosb run. Such a query is recorded only when no stop request follows within half a second;
  // else it stays unrecorded, like an interrupted one, and --resume runs it again.
  bool stopped_with_mosb(const ProcessOutcome& o) const {
    const auto stop_signal = [](int n) {
      return n == SIGTERM || n == SIGINT || n == SIGHUP || n == SIGKILL;
    };
    const bool killed =
        (o.ending == Ending::signaled && stop_signal(o.signal)) ||
        (o.ending == Ending::exited && o.exit_code > 128 && stop_signal(o.exit_code - 128));
    if (!killed) return false;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    while (!stop_.load() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return stop_.load();
  }

  const RunConfig& c_;
  const RunCallbacks& cb_;
  const Plan& p_;
  const SolutionWriter& writer_;
  Journal& journal_;
  const std::atomic<bool>& stop_;
  OutputAdapter adapter_;
  std::unique_ptr<Judging> judging_;
  TempDir temp_;
  std::vector<std::uint64_t> todo_;
  std::mutex mutex_;
  RunProgress progress_;
  std::chrono::steady_clock::time_point started_;
  std::uint64_t ran_ = 0;
  double wall_ = 0, cpu_ = 0;
};

// A file name or command line as metadata, which is UTF-8: bytes that are not kept escaped.
std::string metadata_text(const std::string& bytes) {
  return is_valid_utf8(bytes) ? bytes : escape_for_terminal(bytes);
}

SolverInfo solver_info(const RunConfig& c, const Plan& p, unsigned jobs,
                       const std::vector<std::string>& executables) {
  SolverInfo info;
  info.epsilon = c.epsilon;
  info.name = c.solver_name.empty() ? metadata_text(fs::path(p.words.front()).filename().string())
                                    : c.solver_name;
  info.version = c.solver_version;
  info.machine = describe_machine();
  auto& m = info.parameters;
  m["run.template"] = metadata_text(c.solver_template);
  m["run.executable"] = metadata_text(p.executable);
  if (!executables.empty()) {
    std::string digests;  // more than one: a run continued with --allow-new-executable
    for (const auto& digest : executables) digests += (digests.empty() ? "" : " | ") + digest;
    m["run.executable_sha256"] = digests;
  }
  for (const auto& file : p.files)
    if (file.path != p.executable)
      m["run.file." + std::to_string(&file - p.files.data())] =
          metadata_text(file.path) + " sha256 " + file.sha256;
  m["run.output_format"] = c.output_format;
  m["run.time_limit_seconds"] = format_seconds(c.limits.wall_seconds);
  m["run.cpu_limit_seconds"] = format_seconds(c.limits.cpu_seconds);
  m["run.memory_limit_bytes"] = std::to_string(c.limits.memory_bytes);
  m["run.grace_seconds"] = format_seconds(c.limits.grace_seconds);
  m["run.jobs"] = std::to_string(jobs);
  m["run.pin"] = c.pin ? "yes" : "no";
  m["run.threads"] = std::to_string(c.threads);
  m["run.measurement"] = std::string(to_string(p.measurement));
  m["run.measurement.detail"] = run_internal::describe_measurement(p.measurement);
  m["run.isolation"] = std::string(run_internal::kIsolationNames.name(p.isolation));
  m["run.seal"] = std::string(kSealNames.name(p.seal));
  m["run.output_limit_bytes"] = std::to_string(c.limits.output_bytes);
  if (c.success_exit_codes != std::vector<int>{0}) {
    std::string codes;
    for (const int code : c.success_exit_codes)
      codes += (codes.empty() ? "" : ",") + std::to_string(code);
    m["run.success_exit_codes"] = codes;
  }
  m["run.runtime_seconds"] =
      "wall-clock seconds measured by mosb; the solver's own report is reported_runtime_seconds";
  m["run.mosb_version"] = std::string(kVersion);
  if (c.shard) m["run.shard"] = c.shard->text();
  if (c.id_base != 0) m["run.id_base"] = std::to_string(c.id_base);
  for (const auto& [key, value] : c.parameters) m[key] = value;
  return info;
}

// Reaps any descendant still a zombie of this process (after every solver has ended).
void reap_all() {
  while (::waitpid(-1, nullptr, WNOHANG) > 0) {
  }
}

}  // namespace

namespace {

[[noreturn]] void refuse_packed(const std::string& path) {
  throw Error(ErrorCode::invalid_argument,
              path +
                  ": a packed instance (mosb pack, mosb suite build): a solver maps the file and "
                  "cannot read it; unpack it first (mosb unpack " +
                  path +
                  " -o FILE), or run on a store's unpacked copy (mosb store instance "
                  "STORE NAME)");
}

}  // namespace

GraphReader open_run_instance(const std::string& path) {
  try {
    return GraphReader::open(path, VerifyLevel::checksums);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::packed) throw;
    refuse_packed(path);
  }
}

namespace {

// A journal record a run may take: a query of this run (in its shard), whose status, front and
// statistics a solution file can hold, and whose front is one (spec/RUN.md §3, rule 1).
std::optional<std::string> record_problem(const QueryRecord& r, const RunConfig& c,
                                          const Plan& plan, const SolutionWriter& writer) {
  if (r.query >= plan.queries.size())
    return "not a query of set '" + plan.query_set + "' (" + std::to_string(plan.queries.size()) +
           " queries)";
  if (c.shard && !c.shard->contains(r.query)) return "not a query of shard " + c.shard->text();
  if (auto problem = writer.query_problem(r.query, r.status, r.costs, r.statistics)) return problem;
  return front_problem(r.costs, plan.objective_names.size(), plan.exact);
}

}  // namespace

namespace {

// A record's reason without what differs from query to query: locations ("unreadable output:
// stdout:3:9: 3 values, the view has 2 objectives" -> "unreadable output: 3 values, the view has
// 2 objectives") and the directories of absolute paths (each query's own); or its status when it
// states none.
std::string failure_reason(const QueryRecord& record) {
  if (record.message.empty()) return std::string(to_string(record.status));
  // A location is a word PATH:LINE: or PATH:LINE:COLUMN: followed by a blank.
  const auto is_location = [](std::string_view word) {
    if (word.size() < 3 || word.back() != ':') return false;
    word.remove_suffix(1);
    int numbers = 0;
    for (; numbers < 2; ++numbers) {
      const auto colon = word.rfind(':');
      if (colon == std::string_view::npos) break;
      const auto digits = word.substr(colon + 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos) break;
      word = word.substr(0, colon);
    }
    return numbers > 0;
  };
  std::string out;
  std::string_view text = record.message;
  while (!text.empty()) {
    const auto blank = text.find(' ');
    const auto word = text.substr(0, blank == std::string_view::npos ? text.size() : blank + 1);
    const auto bare = blank == std::string_view::npos ? word : word.substr(0, word.size() - 1);
    if (blank != std::string_view::npos && is_location(bare)) {
      // dropped
    } else if (bare.size() > 1 && bare.front() == '/' && bare.back() == ':') {
      // An absolute path names a file of the query's own directory: its name alone.
      out += word.substr(word.rfind('/', bare.size() - 1) + 1);
    } else {
      out += word;
    }
    text.remove_prefix(word.size());
  }
  return out;
}

}  // namespace

RunResult run_solver(const RunConfig& c, const RunCallbacks& callbacks,
                     const std::atomic<bool>& stop) {
  if (!c.instance) throw Error(ErrorCode::invalid_argument, "run_solver: no instance");
  // Recorded in the solution file's metadata, which is UTF-8: refused before any solver starts.
  if (!is_valid_utf8(c.solver_name) || !is_valid_utf8(c.solver_version))
    throw Error(ErrorCode::invalid_argument,
                {"the solver's name or version is not valid UTF-8 (", setting("solver_name"), ", ",
                 setting("solver_version"), ")"});
  // The caller's reader is the one open of the instance (open_run_instance verified it): a packed
  // file is refused before any solver starts, without a second read of the payload.
  if (format::is_packed(c.instance->header())) refuse_packed(c.instance_path);
  check_output_is_not_input(c.output, {c.instance_path});
  const unsigned jobs = std::max(1u, c.jobs);
  const auto selection = solution_selection(*c.instance, c.choice);
  SolutionWriter writer(*c.instance, selection);
  const Plan plan = make_plan(c, selection, writer);
  check_output_is_not_input(c.output, {plan.executable});
  run_internal::prepare_process_runner();
  sweep_temporaries();
  RunResult result;
  result.measurement = plan.measurement;
  result.query_set_size = plan.queries.size();
  if (c.shard && c.shard->count == 0)
    throw Error(ErrorCode::invalid_argument, {setting("shard"), ": 0 shards"});
  result.total = c.shard ? c.shard->size(result.query_set_size) : result.query_set_size;
  result.journal = journal_path(c.output);
  const run_internal::JournalBinding binding{binding_of(c, plan), plan.executable_sha256,
                                             c.allow_new_executable};
  Journal journal(result.journal, binding, c.resume,
                  [&](const QueryRecord& r) { return record_problem(r, c, plan, writer); });
  Runner runner(c, callbacks, plan, writer, journal, stop);
  result.from_journal = result.total - runner.pending();
  runner.run(jobs, result);
  reap_all();
  for (const auto& [q, record] : journal.records()) {
    ++result.counts[record.status];
    if (record.status != QueryStatus::not_run && !is_completed(record.status))
      ++result.failures[failure_reason(record)];
  }
  result.counts[QueryStatus::not_run] += result.total - journal.records().size();
  if (stop.load()) {
    result.interrupted = true;
    return result;
  }
  check_unchanged(plan.files);
  for (const auto& [q, record] : journal.records())
    writer.set_query(q, record.status, record.costs, record.statistics);
  writer.set_solver(solver_info(c, plan, jobs, journal.executables()));
  writer.write(c.output);
  journal.remove();
  return result;
}

std::optional<std::pair<std::string, std::uint64_t>> most_common_failure(
    const FailureReasons& reasons) {
  const auto most =
      std::max_element(reasons.begin(), reasons.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  if (most == reasons.end()) return std::nullopt;
  return *most;
}

std::optional<double> parse_duration(std::string_view view) {
  const std::string text(view);
  // Decimal only: std::stod would also take "+1", " 1", "inf", "nan" and hex ("0x1p4").
  if (text.empty() || !((text.front() >= '0' && text.front() <= '9') || text.front() == '.') ||
      text.find_first_of("xX") != std::string::npos)
    return std::nullopt;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const std::string unit = text.substr(used);
  double scale = 0;
  if (unit.empty() || unit == "s") scale = 1;
  if (unit == "ms") scale = 1e-3;
  if (unit == "m" || unit == "min") scale = 60;
  if (unit == "h") scale = 3600;
  if (scale == 0 || !(value >= 0) || !(value * scale <= 1e9)) return std::nullopt;
  return value * scale;
}

std::optional<std::uint64_t> parse_memory_size(std::string_view text) {
  std::uint64_t value = 0;
  std::size_t i = 0;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
    const auto digit = static_cast<std::uint64_t>(text[i] - '0');
    if (value > (UINT64_MAX - digit) / 10) return std::nullopt;
    value = value * 10 + digit;
  }
  if (i == 0) return std::nullopt;
  auto unit = text.substr(i);
  // "B" alone (bytes), or after the multiplier: "KB", "KiB".
  if (unit.size() == 3 && (unit.ends_with("iB") || unit.ends_with("ib")))
    unit.remove_suffix(2);
  else if (unit.size() <= 2 && (unit.ends_with("B") || unit.ends_with("b")))
    unit.remove_suffix(1);
  int shift = 0;
  if (unit.size() == 1) {
    const auto at = std::string_view("KMGT").find(static_cast<char>(unit.front() & ~0x20));
    if (at == std::string_view::npos) return std::nullopt;
    shift = 10 * static_cast<int>(at + 1);
  } else if (!unit.empty()) {
    return std::nullopt;
  }
  if (shift > 0 && value > (UINT64_MAX >> shift)) return std::nullopt;
  return value << shift;
}

}  // namespace mosb
