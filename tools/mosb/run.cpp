// `mosb run`: a solver over a query set, one limited and measured process per query, into a
// solution file (spec/RUN.md). The CLI parses options, opens the instance, calls mosb::run_solver
// and prints; the run itself is lib/run.
#include "mosb/run.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/command_template.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/sha256.hpp"

namespace mosb::cli {

namespace {

struct RunArgs {
  std::string instance, output, solver, time_limit = "0", cpu_limit = "0",
                                        output_format = "protocol";
  std::string measurement = "auto", solver_name, solver_version;
  ViewChoice choice;
  std::uint64_t memory_limit = 0;
  double grace = 1;
  unsigned jobs = 1, threads = 1;
  bool pin = false, resume = false, json = false;
};

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int) {
  g_stop.store(true);
}

// "60", "60s", "1.5m", "2h", "500ms": seconds; nullopt when malformed.
std::optional<double> parse_duration(const std::string& text) {
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
  if (scale == 0 || !(value >= 0) || value > 1e9 || text.front() == '+' || text.front() == ' ')
    return std::nullopt;
  return value * scale;
}

CLI::Validator duration() {
  return {[](std::string& text) -> std::string {
            return parse_duration(text) ? "" : "not a duration (60, 60s, 500ms, 2m, 1h)";
          },
          "DURATION", "duration"};
}

// Redraws "done/total, counts, ETA" on stderr (a terminal), at most ~5 times a second.
class ProgressLine {
 public:
  ProgressLine() : enabled_(::isatty(2) == 1) {}
  ~ProgressLine() { end(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  void update(const RunProgress& p) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (p.done != p.total && now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    std::string line = "\r" + std::to_string(p.done) + "/" + std::to_string(p.total);
    for (std::uint8_t s = 0; s <= kLastQueryStatus; ++s)
      if (s != static_cast<std::uint8_t>(QueryStatus::not_run) && p.counts[s] != 0)
        line += ", " + std::to_string(p.counts[s]) + " " +
                std::string(to_string(static_cast<QueryStatus>(s)));
    if (p.done_here != 0 && p.done < p.total)
      line += ", ETA " +
              std::to_string(static_cast<long>(p.elapsed_seconds / p.done_here *
                                               static_cast<double>(p.total - p.done))) +
              " s";
    std::cerr << line << "\x1b[K" << std::flush;
    open_ = true;
  }
  void end() {
    if (open_) std::cerr << "\n";
    open_ = false;
  }

 private:
  bool enabled_;
  bool open_ = false;
  std::chrono::steady_clock::time_point last_{};
};

void print_summary(const RunArgs& a, const RunResult& r) {
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(a.output);
    json.key("queries").value(r.total);
    json.key("ran").value(r.ran);
    json.key("from_journal").value(r.from_journal);
    json.key("statuses").begin_object();
    for (std::uint8_t s = 0; s <= kLastQueryStatus; ++s)
      json.key(to_string(static_cast<QueryStatus>(s))).value(r.counts[s]);
    json.end_object();
    json.key("measurement").value(std::string(to_string(r.measurement)));
    json.key("solver_wall_seconds").value(r.wall_seconds);
    json.key("solver_cpu_seconds").value(r.cpu_seconds);
    json.end_object();
    return;
  }
  std::cout << "wrote " << escape_for_terminal(a.output) << ": " << r.total << " queries (" << r.ran
            << " run, " << r.from_journal << " from the journal):";
  for (std::uint8_t s = 0; s <= kLastQueryStatus; ++s)
    std::cout << ' ' << r.counts[s] << ' ' << to_string(static_cast<QueryStatus>(s))
              << (s < kLastQueryStatus ? "," : "");
  std::cout << "; measured with " << to_string(r.measurement) << ", solvers' wall "
            << r.wall_seconds << " s, cpu " << r.cpu_seconds << " s\n";
}

void report_failed(const QueryRecord& record, const Query& q) {
  std::string line = "mosb: query " + std::to_string(record.query) + " (" +
                     std::to_string(q.start) + " " + std::to_string(q.goal) +
                     "): failed: " + record.message;
  if (!record.stderr_tail.empty()) line += ": " + record.stderr_tail.back();
  std::cerr << escape_for_terminal(line) << "\n";
}

int run_run(const RunArgs& a) {
  if (a.choice.view.empty() && a.choice.objectives.empty())
    throw UsageError("give --view V or --objectives A,B,... (the objectives the solver optimizes)");
  try {
    template_placeholders(split_command(a.solver), run_placeholders());
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  const auto instance = mosb::load(a.instance, VerifyLevel::checksums);
  try {
    solution_selection(instance, a.choice);  // what the file binds to: a usage error, if any
  } catch (const Error& e) {
    if (e.code() != ErrorCode::invalid_argument) throw;
    throw UsageError(e.what());
  }
  RunConfig config;
  config.instance = &instance;
  config.instance_path = a.instance;
  config.choice = a.choice;
  config.solver_template = a.solver;
  config.output_format = a.output_format;
  config.adapter = *converters::solver_output_adapter(a.output_format);  // checked by CLI11
  config.limits = {*parse_duration(a.time_limit), a.memory_limit, a.grace,
                   *parse_duration(a.cpu_limit)};
  config.jobs = a.jobs;
  config.pin = a.pin;
  config.threads = a.threads;
  if (a.measurement != "auto") config.measurement = parse_measurement(a.measurement);
  config.resume = a.resume;
  config.solver_name = a.solver_name;
  config.solver_version = a.solver_version;
  config.output = a.output;
  config.sha256_file = [](const std::string& path) { return sha256_file(path); };
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  ProgressLine progress;
  RunCallbacks callbacks;
  callbacks.progress = [&](const RunProgress& p) { progress.update(p); };
  callbacks.failed = [&](const QueryRecord& r, const Query& q) {
    progress.end();
    report_failed(r, q);
  };
  const RunResult result = run_solver(config, callbacks, g_stop);
  progress.end();
  if (result.interrupted) {
    std::cerr << "mosb: interrupted; " << result.total - result.counts[4] << " queries are in "
              << escape_for_terminal(result.journal) << "; continue with --resume\n";
    return 130;
  }
  print_summary(a, result);
  return 0;
}

}  // namespace

Command add_run(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* sub = app.add_subcommand(
      "run", "Run a solver over a query set, one limited process per query, into a solution file");
  sub->add_option("INSTANCE", a->instance, "the instance (.mosb)")->required();
  add_view_choice_options(sub, a->choice, "the objectives the solver optimizes");
  sub->add_option("--solver", a->solver,
                  "the solver's command line, split like a shell but run without one; "
                  "placeholders {instance} {view} {objectives} {query} {source} {target} {front} "
                  "{fronts} {threads} (spec/RUN.md)")
      ->required();
  sub->add_option("--time-limit", a->time_limit,
                  "wall-clock limit per query (60, 60s, 500ms, 2m, 1h; 0: none)")
      ->check(duration());
  sub->add_option("--cpu-limit", a->cpu_limit,
                  "CPU-time limit per query, user + system of the whole process tree (as "
                  "--time-limit; 0: none); a query over it is a timeout")
      ->check(duration());
  sub->add_option("--memory-limit", a->memory_limit,
                  "memory limit per query for the whole process tree (bytes, or 512M, 4G: "
                  "powers of 1024; 0: none)")
      ->transform(CLI::AsSizeValue(false));
  sub->add_option("--grace", a->grace, "seconds between SIGTERM and SIGKILL on a timeout")
      ->check(non_negative_real());
  sub->add_option("--jobs,-j", a->jobs, "queries run at the same time (default 1)")
      ->check(unsigned_integer(1024))
      ->check(CLI::Range(1u, 1024u));
  sub->add_flag("--pin", a->pin, "pin each job to a CPU of its own (sched_setaffinity)");
  sub->add_option("--threads", a->threads, "what {threads} becomes (default 1)")
      ->check(unsigned_integer(4096));
  sub->add_option("--output-format", a->output_format,
                  "how the solver reports: protocol (spec/RUN.md, default), example-log or "
                  "json-log (PPA*'s log)")
      ->check(CLI::IsMember({"protocol", "example-log", "json-log"}));
  sub->add_option("--measurement", a->measurement,
                  "auto (default), cgroup-v1 or rlimit-poll: how memory is limited and measured")
      ->check(CLI::IsMember({"auto", "cgroup-v1", "rlimit-poll"}));
  sub->add_flag("--resume", a->resume, "continue the run the journal OUTPUT.journal records");
  sub->add_option("--solver-name", a->solver_name, "the solver's name (default: the program's)")
      ->check(printable_text());
  sub->add_option("--solver-version", a->solver_version, "the solver's version")
      ->check(printable_text());
  add_output_option(sub, a->output, "the solution file")->required();
  add_json_flag(sub, a->json);
  return {sub, [a] { return run_run(*a); }};
}

}  // namespace mosb::cli
