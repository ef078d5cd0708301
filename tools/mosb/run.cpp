// `mosb run`: a solver over a query set, one limited and measured process per query, into a
// solution file (spec/RUN.md); with --shard only one shard's queries, and with --slurm DIR a SLURM
// job array of shards (§8). The CLI parses options, opens the instance, calls mosb::run_solver or
// the mosb/slurm.hpp functions and prints; the run itself is lib/run.
#include "mosb/run.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/command_template.hpp"
#include "mosb/converters/profile.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/converters/solver_resolver.hpp"
#include "mosb/experiment.hpp"
#include "mosb/internal/number_text.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/sha256.hpp"
#include "mosb/slurm.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct RunArgs {
  std::string instance, output, solver, time_limit = "0", cpu_limit = "0",
                                        output_format = "protocol";
  std::string measurement, solver_name, solver_version, epsilon = "0";
  std::string isolation;  // add_isolation_option's default
  ViewChoice choice;
  std::uint64_t memory_limit = 0, max_output = kDefaultOutputBytes;
  bool allow_new_executable = false;
  double grace = 1;
  unsigned jobs = 1, threads = 1;
  bool pin = false, resume = false, json = false;
  std::string shard;  // --shard i/N
  // --profile NAME|FILE and what it takes
  std::string profile, executable, export_cache;
  std::vector<std::string> profile_options;
  double scale = 0;
  bool list_profiles = false;
  SlurmArgs slurm;  // --slurm DIR and its options
  std::optional<std::uint64_t> shards;
  CLI::App* app = nullptr;  // for which options were given
};

void print_summary(const RunArgs& a, const RunResult& r) {
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("file").value(a.output);
    json.key("queries").value(r.total);
    if (!a.shard.empty()) json.key("shard").value(a.shard);
    json.key("ran").value(r.ran);
    json.key("from_journal").value(r.from_journal);
    json.key("statuses");
    json_status_counts(json, r.counts);
    json.key("measurement").value(std::string(to_string(r.measurement)));
    json.key("solver_wall_seconds").value(r.wall_seconds);
    json.key("solver_cpu_seconds").value(r.cpu_seconds);
    json.end_object();
    return;
  }
  std::cout << "wrote " << escape_for_terminal(a.output) << ": "
            << (a.shard.empty() ? std::string()
                                : "shard " + a.shard + ", " + std::to_string(r.total) + " of the " +
                                      std::to_string(r.query_set_size) + " queries")
            << (a.shard.empty() ? std::to_string(r.total) + " queries" : std::string()) << " ("
            << r.ran << " run, " << r.from_journal
            << " from the journal): " << status_counts_text(r.counts, false);
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

// What an option of `mosb run` is to a run on SLURM.
enum class Role {
  run,     // defines the run: every SLURM task passes it on; run.json has it for --resume/--status
  local,   // a run here only (-o, --shard): each task has its own
  plan,    // plans the job array (--shards, ...): with --slurm DIR only, recorded in run.json
  submit,  // with --slurm DIR only, new or resumed
  action,  // says what to do (--slurm, --resume, --status, --json, --help)
};

using Arguments = std::vector<std::string>;

// Every option of `mosb run`, in one table: what it is to a SLURM run and, for the options that
// define the run, how a SLURM task is given it (nothing: its default). The table's order is the
// order of the tasks' arguments. add_run refuses to register an option the table lacks.
struct RunOption {
  const char* name;
  Role role;
  void (*pass_on)(const RunArgs&, Arguments&) = nullptr;  // Role::run only
};

void pass(Arguments& out, const char* name, const std::string& value) {
  if (!value.empty()) out.insert(out.end(), {name, value});
}

const RunOption kRunOptionTable[] = {
    {"INSTANCE", Role::run, [](const RunArgs&, Arguments&) {}},  // the script's, made absolute
    {"--view", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--view", a.choice.view); }},
    {"--objectives", Role::run,
     [](const RunArgs& a, Arguments& out) {
       std::string list;
       for (const auto& name : a.choice.objectives) list += (list.empty() ? "" : ",") + name;
       pass(out, "--objectives", list);
     }},
    {"--queries", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--queries", a.choice.queries); }},
    {"--solver", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--solver", a.solver); }},
    {"--time-limit", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--time-limit", a.time_limit); }},
    {"--cpu-limit", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--cpu-limit", a.cpu_limit); }},
    {"--memory-limit", Role::run,
     [](const RunArgs& a, Arguments& out) {
       pass(out, "--memory-limit", std::to_string(a.memory_limit));
     }},
    {"--grace", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--grace", shortest_text(a.grace)); }},
    {"--jobs", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--jobs", std::to_string(a.jobs)); }},
    {"--pin", Role::run,
     [](const RunArgs& a, Arguments& out) {
       if (a.pin) out.emplace_back("--pin");
     }},
    {"--threads", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--threads", std::to_string(a.threads)); }},
    {"--output-format", Role::run,
     [](const RunArgs& a, Arguments& out) {
       if (a.profile.empty()) pass(out, "--output-format", a.output_format);  // else the profile's
     }},
    {"--measurement", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--measurement", a.measurement); }},
    {"--isolation", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--isolation", a.isolation); }},
    {"--solver-name", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--solver-name", a.solver_name); }},
    {"--solver-version", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--solver-version", a.solver_version); }},
    {"--epsilon", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--epsilon", a.epsilon); }},
    {"--max-output", Role::run,
     [](const RunArgs& a, Arguments& out) {
       pass(out, "--max-output", std::to_string(a.max_output));
     }},
    {"--allow-new-executable", Role::run,
     [](const RunArgs& a, Arguments& out) {
       if (a.allow_new_executable) out.emplace_back("--allow-new-executable");
     }},
    {"--profile", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--profile", a.profile); }},
    {"--executable", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--executable", a.executable); }},
    {"--profile-option", Role::run,
     [](const RunArgs& a, Arguments& out) {
       for (const auto& option : a.profile_options) pass(out, "--profile-option", option);
     }},
    {"--scale", Role::run,
     [](const RunArgs& a, Arguments& out) {
       if (a.scale > 0) pass(out, "--scale", shortest_text(a.scale));
     }},
    // Each task exports (or finds) the text in its node's cache unless the run names one.
    {"--export-cache", Role::run,
     [](const RunArgs& a, Arguments& out) { pass(out, "--export-cache", a.export_cache); }},
    {"--output", Role::local},
    {"--shard", Role::local},
    {"--shards", Role::plan},
    {"--queries-per-task", Role::plan},
    {"--throttle", Role::plan},
    {"--account", Role::plan},
    {"--partition", Role::plan},
    {"--submit", Role::submit},
    {"--slurm", Role::action},
    {"--resume", Role::action},
    {"--status", Role::action},
    {"--json", Role::action},
    {"--list-profiles", Role::action},
    {"--help", Role::action},
};

const RunOption* find_run_option(const std::string& name) {
  for (const auto& option : kRunOptionTable)
    if (name == option.name) return &option;
  return nullptr;
}

bool given(const RunArgs& a, const char* name) {
  return a.app->get_option_no_throw(name) && a.app->count(name) > 0;
}

// Refuses the first given option whose role is one of `roles`.
void refuse(const RunArgs& a, std::initializer_list<Role> roles, const std::string& why) {
  for (const auto& option : kRunOptionTable)
    if (std::find(roles.begin(), roles.end(), option.role) != roles.end() && given(a, option.name))
      throw UsageError(std::string(option.name) + ": " + why);
}

// The options that define the run, as every SLURM task is given them.
Arguments task_options(const RunArgs& a) {
  Arguments out;
  for (const auto& option : kRunOptionTable)
    if (option.role == Role::run) option.pass_on(a, out);
  return out;
}

// The solver the options name, as the solver resolver takes it.
SolverSpec solver_spec(const RunArgs& a) {
  SolverSpec spec;
  spec.solver_template = a.solver;
  spec.output_format = a.output_format;
  spec.profile = a.profile;
  spec.executable = a.executable;
  spec.options = a.profile_options;
  spec.scale = a.scale;
  spec.export_cache = a.export_cache;
  spec.epsilon = a.epsilon;
  spec.name = a.solver_name;
  spec.version = a.solver_version;
  return spec;
}

// What the options of a run require, before the instance is opened; the solver checked by the
// solver resolver.
void check_run_options(const RunArgs& a) {
  if (a.instance.empty()) throw UsageError("INSTANCE is required");
  if (!a.profile.empty()) {
    for (const char* option : {"--solver", "--output-format"})
      if (given(a, option))
        throw UsageError(std::string(option) + ": not with --profile (the profile says it)");
    if (a.executable.empty()) throw UsageError("--profile: give --executable PATH (the solver)");
  } else {
    for (const char* option : {"--executable", "--profile-option", "--scale", "--export-cache"})
      if (given(a, option)) throw UsageError(std::string(option) + ": only with --profile");
    if (a.solver.empty()) throw UsageError("--solver is required (or --profile)");
  }
  if (a.choice.view.empty() && a.choice.objectives.empty())
    throw UsageError("give --view V or --objectives A,B,... (the objectives the solver optimizes)");
  try {
    converters::check_solver(solver_spec(a));
  } catch (const Error& e) {
    // A template that does not parse or run is a usage error; a profile's problems (its file,
    // its options) say which themselves.
    if (e.code() == ErrorCode::io || !a.profile.empty()) throw;
    throw UsageError(error_text(e));
  }
}

// The instance's selection: a usage error when the choice does not fit it.
View checked_selection(const GraphReader& instance, const ViewChoice& choice) {
  try {
    return solution_selection(instance, choice);  // what the file binds to
  } catch (const Error& e) {
    if (e.code() != ErrorCode::invalid_argument) throw;
    throw UsageError(error_text(e));
  }
}

// The run the options describe, on `instance` (which must outlive the config).
RunConfig run_config(const RunArgs& a, const GraphReader& instance) {
  RunConfig config;
  config.instance = &instance;
  config.instance_path = a.instance;
  config.choice = a.choice;
  config.limits = {*parse_duration(a.time_limit), a.memory_limit, a.grace,
                   *parse_duration(a.cpu_limit), a.max_output};
  config.allow_new_executable = a.allow_new_executable;
  config.jobs = a.jobs;
  config.pin = a.pin;
  config.threads = a.threads;
  config.measurement = chosen_measurement(a.measurement);
  config.seal = parse_isolation(a.isolation);
  config.resume = a.resume;
  config.output = a.output;
  config.sha256_file = [](const std::string& path) { return sha256_file(path); };
  converters::configure_solver(config, solver_spec(a));
  return config;
}

int run_run(const RunArgs& a) {
  refuse(a, {Role::plan, Role::submit}, "only with --slurm DIR");
  if (given(a, "--status")) throw UsageError("--status: only with --slurm DIR");
  check_run_options(a);
  if (a.output.empty()) throw UsageError("--output is required (or --slurm DIR)");
  std::optional<Shard> shard;
  if (!a.shard.empty()) {
    shard = parse_shard(a.shard);
    if (!shard) throw UsageError("--shard " + a.shard + ": not i/N with 1 <= i <= N");
  }
  const auto instance = open_run_instance(a.instance);
  checked_selection(instance, a.choice);
  RunConfig config = run_config(a, instance);
  config.shard = shard;
  const auto& stop = install_stop_handlers();
  TerminalProgress progress;
  RunCallbacks callbacks;
  callbacks.progress = [&](const RunProgress& p) { progress.update(p); };
  callbacks.failed = [&](const QueryRecord& r, const Query& q) {
    progress.end_line();
    report_failed(r, q);
  };
  const RunResult result = run_solver(config, callbacks, stop);
  progress.end_line();
  if (result.interrupted) {
    std::cerr << "mosb: interrupted; " << result.total - result.counts[QueryStatus::not_run]
              << " queries are in " << escape_for_terminal(result.journal)
              << "; continue with --resume\n";
    return 130;
  }
  print_summary(a, result);
  // A shard is a part: whether any query completed is the merged run's question.
  return shard ? 0 : no_query_completed(result.counts, result.failures);
}

// `mosb run ... --slurm DIR`: writes DIR (run.json, run.sbatch), then submits or prints sbatch.
int run_slurm_new(const RunArgs& a) {
  refuse(a, {Role::local}, "not with --slurm DIR (task i writes DIR/shard-i.sol)");
  check_run_options(a);
  const auto instance = open_run_instance(a.instance);
  const View selection = checked_selection(instance, a.choice);
  try {  // a shard count that does not fit the query set is a usage error
    slurm_shard_count(instance.queries(selection.query_set).size(), a.shards,
                      a.slurm.queries_per_task);
  } catch (const Error& e) {
    throw UsageError(error_text(e));
  }
  SlurmRequest request;
  request.directory = a.slurm.directory;
  request.run_options = task_options(a);
  request.shards = a.shards;
  request.queries_per_task = a.slurm.queries_per_task;
  request.throttle = a.slurm.throttle;
  request.account = a.slurm.account;
  request.partition = a.slurm.partition;
  const SlurmRun run = plan_slurm_run(run_config(a, instance), request);
  create_slurm_directory(run);
  std::vector<std::uint64_t> all(run.shards);
  for (std::uint64_t i = 0; i < run.shards; ++i) all[i] = i + 1;
  const auto time = slurm_time_seconds(run);
  const auto mib = slurm_memory_mib(run);
  std::optional<std::string> job;
  if (a.slurm.submit) {
    try {
      job = submit_shards(run, all);
    } catch (const Error& e) {
      throw Error(e.code(), error_text(e) + "; " + run.directory +
                                " is written: submit it with mosb run --slurm " + run.directory +
                                " --resume --submit");
    }
  }
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("directory").value(run.directory);
    json.key("script").value(run.directory + "/run.sbatch");
    json.key("queries").value(run.queries);
    json.key("shards").value(run.shards);
    json.key("time").value(time ? std::optional(slurm_time_text(*time)) : std::nullopt);
    json.key("mem_mib").value(mib);
    json.key("sbatch").value(sbatch_command_text(run, all));
    json.key("job").value(job);
    json.end_object();
    return 0;
  }
  std::cout << "wrote " << escape_for_terminal(run.directory) << "/run.sbatch: " << run.shards
            << " shards of the " << run.queries << " queries (at most "
            << (run.queries + run.shards - 1) / run.shards << " a task), --time "
            << (time ? slurm_time_text(*time) : std::string("(the partition's default)"))
            << ", --mem " << (mib ? std::to_string(*mib) + "M" : std::string("(the default)"))
            << "\n";
  if (job)
    std::cout << "submitted array job " << *job << " (" << run.shards << " tasks)\n";
  else
    std::cout << "submit with: " << escape_for_terminal(sbatch_command_text(run, all)) << "\n";
  return 0;
}

void print_status_json(const SlurmRun& run, const SlurmStatus& status,
                       const std::vector<std::uint64_t>* resubmitted,
                       const std::optional<std::string>& job) {
  JsonWriter json(std::cout);
  json.begin_object();
  json.key("directory").value(run.directory);
  json.key("queries").value(run.queries);
  json.key("shards").value(run.shards);
  std::uint64_t done = 0;
  for (const auto& s : status.shards) done += s.file == ShardFile::done;
  json.key("done").value(done);
  json.key("complete").value(done == run.shards);
  json.key("jobs").begin_array();
  for (const auto& j : status.jobs) json.value(j);
  json.end_array();
  json.key("scheduler").begin_array();
  for (const auto& source : status.sources) json.value(source);
  json.end_array();
  json.key("shard_states").begin_array();
  for (const auto& s : status.shards) {
    json.begin_object();
    json.key("shard").value(s.index);
    json.key("queries").value(s.queries);
    json.key("file").value(std::string(to_string(s.file)));
    json.key("recorded").value(s.recorded);
    if (!s.problem.empty()) json.key("problem").value(s.problem);
    if (s.file == ShardFile::done) {
      json.key("statuses");
      json_status_counts(json, s.counts);
    }
    json.key("job");
    if (s.job.empty())
      json.null();
    else
      json.value(s.job);
    json.key("state");
    if (s.state.empty())
      json.null();
    else
      json.value(s.state);
    json.end_object();
  }
  json.end_array();
  if (resubmitted) {
    json.key("resubmit").begin_array();
    for (const auto i : *resubmitted) json.value(i);
    json.end_array();
    json.key("sbatch");
    if (resubmitted->empty())
      json.null();
    else
      json.value(sbatch_command_text(run, *resubmitted));
    json.key("job").value(job);
  }
  json.end_object();
}

void print_status_text(const SlurmRun& run, const SlurmStatus& status) {
  std::cout << escape_for_terminal(run.directory) << ": " << run.shards << " shards of the "
            << run.queries << " queries of query set " << escape_for_terminal(run.query_set)
            << " of " << escape_for_terminal(run.instance);
  if (!status.jobs.empty()) {
    std::cout << "; array job" << (status.jobs.size() > 1 ? "s" : "");
    for (const auto& j : status.jobs) std::cout << ' ' << j;
  }
  std::cout << "\n";
  std::array<std::uint64_t, 4> files{};
  for (const auto& s : status.shards) {
    ++files[static_cast<std::size_t>(s.file)];
    std::cout << "shard " << s.index << "/" << run.shards << ": " << to_string(s.file);
    switch (s.file) {
      case ShardFile::done:
        std::cout << " (" << status_counts_text(s.counts, true) << ")";
        break;
      case ShardFile::partial:
        std::cout << " (" << s.recorded << " of " << s.queries << " queries in the journal)";
        break;
      case ShardFile::missing:
        std::cout << " (" << s.queries << " queries)";
        break;
      case ShardFile::damaged:
        std::cout << " (" << escape_for_terminal(s.problem) << ")";
        break;
    }
    if (!s.state.empty()) std::cout << ", task " << s.job << " " << s.state;
    std::cout << "\n";
  }
  std::cout << "summary: " << files[0] << " done, " << files[1] << " partial, " << files[2]
            << " missing, " << files[3] << " damaged";
  if (status.sources.empty() && !status.jobs.empty())
    std::cout << " (no scheduler state: squeue and sacct are absent or did not answer)";
  std::cout << "\n";
  if (files[0] == run.shards)
    std::cout << "merge with: mosb solutions merge "
              << escape_for_terminal(shell_quote(run.directory)) << "/shard-*.sol -o all.sol\n";
}

// `mosb run --slurm DIR --status` and `--resume`.
int run_slurm_existing(const RunArgs& a) {
  refuse(a, {Role::run, Role::local, Role::plan},
         "not with --slurm DIR --resume or --status (DIR/run.json has the run)");
  if (a.slurm.status && a.resume) throw UsageError("--status: not with --resume");
  if (a.slurm.status && a.slurm.submit) throw UsageError("--submit: not with --status");
  const SlurmRun run = read_slurm_directory(a.slurm.directory, kRunKind);
  const SlurmStatus status = slurm_status(run);
  if (a.slurm.status) {
    if (a.json)
      print_status_json(run, status, nullptr, std::nullopt);
    else
      print_status_text(run, status);
    return 0;
  }
  const auto [resubmit, queued] = shards_to_resubmit(status.shards);
  std::optional<std::string> job;
  if (a.slurm.submit && !resubmit.empty()) job = submit_shards(run, resubmit);
  if (a.json) {
    print_status_json(run, status, &resubmit, job);
    return 0;
  }
  if (!queued.empty())
    std::cout << "still in the queue, not resubmitted: shard" << (queued.size() > 1 ? "s " : " ")
              << slurm_array_list(queued) << "\n";
  if (resubmit.empty()) {
    std::cout << "nothing to resubmit: " << run.shards - queued.size() << " of " << run.shards
              << " shards are done\n";
  } else if (job) {
    std::cout << "resubmitted shard" << (resubmit.size() > 1 ? "s " : " ")
              << slurm_array_list(resubmit) << " of " << run.shards << " as array job " << *job
              << "\n";
  } else {
    std::cout << "resubmit shard" << (resubmit.size() > 1 ? "s " : " ")
              << slurm_array_list(resubmit) << " of " << run.shards
              << " with: " << escape_for_terminal(sbatch_command_text(run, resubmit)) << "\n";
  }
  return 0;
}

// `mosb run --list-profiles`: the shipped profiles, one a line.
int list_profiles(const RunArgs& a) {
  std::vector<converters::SolverProfile> profiles;
  for (const auto& shipped : converters::shipped_profiles())
    profiles.push_back(converters::load_profile(std::string(shipped.name)));
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_array();
    for (const auto& p : profiles) {
      json.begin_object();
      json.key("name").value(p.name);
      json.key("description").value(p.description);
      json.key("repository").value(p.repository);
      json.key("input").value(std::string(converters::kInputFormNames.name(p.input.form)));
      json.key("output").value(p.output.format);
      json.key("options").begin_object();
      for (const auto& option : p.options) json.key(option.name).value(option.default_value);
      json.end_object();
      json.end_object();
    }
    json.end_array();
    return 0;
  }
  for (const auto& p : profiles) {
    std::cout << p.name << ": " << p.description << "\n";
    for (const auto& option : p.options) {
      std::string values;
      for (const auto& v : option.values) values += (values.empty() ? "" : "|") + v;
      std::cout << "  --profile-option " << option.name << "="
                << (values.empty() ? "VALUE" : values) << " (default " << option.default_value
                << ")\n";
    }
  }
  return 0;
}

int run_command(const RunArgs& a) {
  if (a.list_profiles) {
    for (const auto& option : kRunOptionTable)
      if (option.role != Role::action && given(a, option.name))
        throw UsageError(std::string(option.name) + ": not with --list-profiles");
    return list_profiles(a);
  }
  if (a.slurm.directory.empty()) return run_run(a);
  if (a.resume || a.slurm.status) return run_slurm_existing(a);
  return run_slurm_new(a);
}

}  // namespace

// Longer than 80 lines on purpose: one statement per option of `mosb run`, in --help's order, so
// the option list reads as one (kRunOptionTable says what each is to a SLURM run).
Command add_run(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* sub = app.add_subcommand(
      "run", "Run a solver over a query set, one limited process per query, into a solution file");
  a->app = sub;
  sub->add_option("INSTANCE", a->instance, "the instance (.mosb)");
  add_view_choice_options(sub, a->choice, "the objectives the solver optimizes");
  sub->add_option("--solver", a->solver,
                  "the solver's command line, split like a shell but run without one; "
                  "placeholders {instance} {view} {objectives} {query} {source} {target} {front} "
                  "{fronts} {threads} (spec/RUN.md)");
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
      ->transform(memory_size());
  sub->add_option("--grace", a->grace, "seconds between SIGTERM and SIGKILL on a timeout")
      ->check(non_negative_real());
  sub->add_option("--jobs,-j", a->jobs, "queries run at the same time (default 1)")
      ->check(unsigned_integer(1024))
      ->check(CLI::Range(1u, 1024u));
  sub->add_flag("--pin", a->pin, "pin each job to a CPU of its own (sched_setaffinity)");
  sub->add_option("--threads", a->threads, "what {threads} becomes (default 1)")
      ->check(unsigned_integer(4096));
  std::string formats_help = "how the solver reports (spec/RUN.md section 3.1):";
  std::vector<std::string> format_names;
  for (const auto& format : converters::solver_output_formats()) {
    formats_help += std::string(format_names.empty() ? " " : "; ") + std::string(format.name) +
                    ": " + std::string(format.description);
    format_names.emplace_back(format.name);
  }
  sub->add_option("--output-format", a->output_format, formats_help + " (default protocol)")
      ->check(CLI::IsMember(format_names));
  add_measurement_option(sub, a->measurement);
  add_isolation_option(sub, a->isolation);
  sub->add_flag("--resume", a->resume,
                "continue the run the journal OUTPUT.journal records; with --slurm DIR, resubmit "
                "the shards whose file is missing or incomplete");
  sub->add_option("--solver-name", a->solver_name, "the solver's name (default: the program's)")
      ->check(printable_text());
  sub->add_option("--solver-version", a->solver_version, "the solver's version")
      ->check(printable_text());
  sub->add_option("--epsilon", a->epsilon,
                  "the ε the solver claims (0, the default: exact); with 0 a front with a vector "
                  "another dominates is a failure, and eval judges the file by it")
      ->check(epsilon_value());
  sub->add_option("--max-output", a->max_output,
                  "the most a solver may write to any one output file (and a log may decompress "
                  "to), bytes or 512M, 4G; a front of more than SIZE/8 values is refused too "
                  "(default 1G)")
      ->transform(memory_size());
  sub->add_flag("--allow-new-executable", a->allow_new_executable,
                "with --resume: continue although the solver's executable changed (both SHA-256 "
                "are recorded)");
  sub->add_option("--shard", a->shard,
                  "run only shard i of N (query k is in shard k mod N + 1); the other queries "
                  "stay not-run, and solutions merge joins the shards")
      ->option_text("i/N");
  sub->add_option("--profile", a->profile,
                  "run a solver that does not speak the protocol through its profile: a shipped "
                  "one's name (--list-profiles) or a TOML file (spec/RUN.md section 10)")
      ->option_text("NAME|FILE");
  sub->add_option("--executable", a->executable, "with --profile: the solver's program")
      ->option_text("PATH");
  sub->add_option("--profile-option", a->profile_options,
                  "with --profile: one of its options (repeatable)")
      ->option_text("KEY=VALUE")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--scale", a->scale,
                  "with --profile of a solver that reads integer costs: float costs x K rounded; "
                  "its values are divided back and the factor recorded")
      ->check(CLI::PositiveNumber)
      ->option_text("K");
  sub->add_option("--export-cache", a->export_cache,
                  "with --profile: where the text forms are exported once and reused (default "
                  "$MOSB_EXPORT_CACHE, else $XDG_CACHE_HOME/mosb/exports, else "
                  "~/.cache/mosb/exports; mosb cache clear empties it)")
      ->option_text("DIR");
  sub->add_flag("--list-profiles", a->list_profiles, "print the shipped solver profiles");
  add_output_option(sub, a->output, "the solution file (required without --slurm)");
  auto* shards = sub->add_option("--shards", a->shards, "with --slurm: N shards, one task each")
                     ->check(unsigned_integer(1000000));
  add_slurm_options(sub, a->slurm,
                    {"write a SLURM job array to DIR instead of running: one task per shard, each "
                     "writing DIR/shard-i.sol (spec/RUN.md section 8)",
                     "with --slurm: shards of at most K queries (ceil(Q / K) shards)",
                     "with --slurm DIR: the shards' files and the array's state (squeue, sacct)"})
      ->excludes(shards);
  add_json_flag(sub, a->json);
  for (const auto* option : sub->get_options())  // a programming error, caught by every test
    if (find_run_option(option->get_name()) == nullptr)
      throw std::logic_error("mosb run: option " + option->get_name() +
                             " is not in kRunOptionTable");
  return {sub, [a] { return run_command(*a); }};
}

}  // namespace mosb::cli
